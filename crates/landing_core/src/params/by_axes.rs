//! A table read for each axis count the plants have (3 for the landers, 2 for the tethered
//! satellite): a law, a reference or a disturbance does not know its plant until it meets it.

use super::{Cases, Reader, Table};
use crate::batch::PerCase;
use crate::error::ReadError;

/// How a model is read for D axes (the laws: [`crate::control::Laws`], the references and
/// the disturbances: [`crate::reference::References`], [`crate::disturbance::Disturbances`]).
pub trait ReadFor {
    type At<const D: usize>: Clone + Send + Sync + 'static;
    fn read<const D: usize>(p: &mut Reader<'_>) -> Result<Self::At<D>, ReadError>;
}

/// Reads a model and validates it (the [`ReadFor`] of the families whose `from_params` does
/// not validate on its own).
pub fn read_valid<T: super::FromParams + crate::error::Validate>(
    p: &mut Reader<'_>,
) -> Result<T, ReadError> {
    let v = T::from_params(p)?;
    v.validate()?;
    Ok(v)
}

/// A table's reading for D axes (with its cases), or why the table does not fit D axes.
type Reading<T> = Result<(PerCase<T>, Cases), ReadError>;

/// The readings of one table for each axis count.
pub struct ByAxes<M: ReadFor> {
    two: Reading<M::At<2>>,
    three: Reading<M::At<3>>,
}

/// An axis count, as a type.
pub struct Dim<const D: usize>;

/// The axis counts a plant may have: [`ByAxes`] holds a reading for each. A plant with
/// another count is a compile error where the registry visits it (add the count here, with
/// its field in [`ByAxes`] and its arm in [`with_axes!`](crate::with_axes)).
pub trait AxisCount<const D: usize> {
    fn reading<M: ReadFor>(b: &ByAxes<M>) -> &Reading<M::At<D>>;
}

impl AxisCount<2> for Dim<2> {
    fn reading<M: ReadFor>(b: &ByAxes<M>) -> &Reading<M::At<2>> {
        &b.two
    }
}

impl AxisCount<3> for Dim<3> {
    fn reading<M: ReadFor>(b: &ByAxes<M>) -> &Reading<M::At<3>> {
        &b.three
    }
}

/// Runs `$body` with the const `$d` set to the axis count `$axes` (2 or 3), or gives `$err`
/// (with `$other` the count) for any other: the one place that turns a run-time axis count
/// into a compiled one.
#[macro_export]
macro_rules! with_axes {
    ($axes:expr, $d:ident => $body:expr, $other:ident => $err:expr) => {
        match $axes {
            2 => {
                const $d: usize = 2;
                $body
            }
            3 => {
                const $d: usize = 3;
                $body
            }
            $other => $err,
        }
    };
}

impl<M: ReadFor> ByAxes<M> {
    /// Reads `table` for every axis count, its errors prefixed with `owner`; fails only if no
    /// reading succeeds, with the error of the three-axis reading, or of the two-axis one if
    /// `prefer_two`.
    pub fn compile(owner: &str, table: &Table, prefer_two: bool) -> Result<Self, ReadError> {
        let two = table
            .read_cases(None, |p| M::read::<2>(p))
            .map_err(|e| e.context(owner));
        let three = table
            .read_cases(None, |p| M::read::<3>(p))
            .map_err(|e| e.context(owner));
        match (two, three) {
            (Err(e2), Err(e3)) => Err(if prefer_two { e2 } else { e3 }),
            (two, three) => Ok(Self { two, three }),
        }
    }

    /// The reading for D axes (with its cases), or why the table does not fit D axes.
    pub fn get<const D: usize>(&self) -> Result<(&PerCase<M::At<D>>, &Cases), ReadError>
    where
        Dim<D>: AxisCount<D>,
    {
        match Dim::<D>::reading(self) {
            Ok((v, c)) => Ok((v, c)),
            Err(e) => Err(e.clone()),
        }
    }

    /// The reading for D axes if it fits a batch of `n` cases (`owner` names it in the error).
    pub fn for_cases<const D: usize>(
        &self,
        owner: &str,
        n: usize,
    ) -> Result<PerCase<M::At<D>>, ReadError>
    where
        Dim<D>: AxisCount<D>,
    {
        let (models, cases) = self.get::<D>()?;
        if let Err(e) = cases.check(owner, n) {
            // a vector sized for a plant of the other axis count reads as per case here (a
            // law's per-axis defaults on another paper's plant): say both readings
            return Err(match &cases.key {
                Some(key) if cases.count != D && self.axes().contains(&cases.count) => {
                    ReadError::value(format!(
                        "{owner}: {key} has {count} values: one per axis of a {count}-axis plant, but this \
                         plant has {D} axes; one per case would be {n} (the batch's cases)",
                        count = cases.count
                    ))
                }
                _ => e,
            });
        }
        Ok(models.clone())
    }

    /// The axis counts the table fits.
    pub fn axes(&self) -> Vec<usize> {
        let mut a = Vec::new();
        if self.two.is_ok() {
            a.push(2);
        }
        if self.three.is_ok() {
            a.push(3);
        }
        a
    }
}
