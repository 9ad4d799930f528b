//! A tabulated open-loop force: the replay of an offline thrust profile.
//!
//! Seed 001 ("Mars Powered Descent Phase Guidance Design Based on Fixed-time Stabilization
//! Technique", section IV, Fig. 3 and 4) compares its guidance with an offline
//! fuel-optimal thrust profile flown open loop, with and without the disturbance
//! `a_p = sin(t)` per axis (Fig. 3(c), (d)). This law flies such a profile: row `j` of the table is a
//! generalized force per axis (thrust, N, on the Mars lander), held for `hold` control periods
//! (zero-order hold), so that at control instant `k` (t = k dt) the law commands
//!
//! ```text
//! a_k = F_j / M(x_k),   j = floor(k / hold)
//! ```
//!
//! with `M` the plant's diagonal inertia (the lander's mass, seed eq. 14's F = m a read the
//! other way). The plant's actuator multiplies by the same inertia, so the applied force is the
//! tabulated one up to a rounding, then clips it to the actuator's limit; the lander holds it
//! over the control period. Replaying a profile computed on the same grid with the same
//! integrator therefore reproduces it step by step (`landing.optimal`).
//!
//! After the table (`k >= rows * hold`) the law commands the last row (`after = "hold"`) or
//! zero (`after = "zero"`, the engine off).
//!
//! The rows are read from the list `rows` of tables with one key `force` each (D values, or one
//! row of D per case); every case of a batch has the same number of rows.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check, require};
use crate::lanes::{Gather, Real};
use crate::params::{Declared, FromParams, Layout, Param, ParamSource, Schema};

crate::named! {
    /// What the law commands after its table.
    pub enum AfterTable {
        /// The last row, held.
        Hold => "hold",
        /// Zero force.
        Zero => "zero",
    }
}

const FORCE: Param = Param::axes("force")
    .unit("N")
    .doc("the row's generalized force per axis (N on the Mars lander)");
const ROWS: Param = Param::list("rows", Layout::Fixed(&[FORCE]))
    .rule("at least one row")
    .doc("the table, one row per hold period, every case the same number of rows");
const HOLD: Param = Param::scalar("hold")
    .unit("1")
    .rule("hold a whole number >= 1")
    .doc("control periods each row is held for");
const AFTER: Param = Param::choice("after", AfterTable::NAMES)
    .doc("after the table: hold the last row, or command zero (engine off)");

#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated<const D: usize, R = f64> {
    /// The rows, a generalized force per axis each.
    pub rows: Vec<SVector<R, D>>,
    /// Control periods each row is held for (>= 1). Shared by a block.
    pub hold: usize,
    /// What follows the table. Shared by a block.
    pub after: AfterTable,
}

impl<const D: usize, R: Real> Gather<R> for Tabulated<D, R> {
    type Case = Tabulated<D>;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Tabulated<D>) -> Self {
        let first = case(0);
        Self {
            rows: (0..first.rows.len())
                .map(|j| <SVector<R, D> as Gather<R>>::gather(&|i| &case(i).rows[j]))
                .collect(),
            hold: first.hold,
            after: first.after,
        }
    }

    fn same_shape(a: &Tabulated<D>, b: &Tabulated<D>) -> bool {
        a.rows.len() == b.rows.len() && a.hold == b.hold && a.after == b.after
    }
}

impl<const D: usize, R: Real> Tabulated<D, R> {
    /// The row in force at control instant `k`, or None after the table with `after = zero`.
    #[inline(always)]
    pub fn row(&self, k: usize) -> Option<&SVector<R, D>> {
        let j = k / self.hold;
        match self.rows.get(j) {
            Some(r) => Some(r),
            None => match self.after {
                AfterTable::Hold => self.rows.last(),
                AfterTable::Zero => None,
            },
        }
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for Tabulated<D, R> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &[];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), input: &LawInput<D, R>) -> SVector<R, D> {
        // control instants are t = k dt exactly (the rollout computes t from k), so the
        // rounded quotient is k
        let k = (input.t / input.dt).round() as usize;
        match self.row(k) {
            Some(f) => SVector::from_fn(|i, _| f[i] / input.inertia[i]),
            None => SVector::from_fn(|_, _| R::zero()),
        }
    }
}

impl<const D: usize> Validate for Tabulated<D> {
    fn validate(&self) -> Result<(), ParamError> {
        require(
            !self.rows.is_empty(),
            ROWS.name,
            self.rows.len() as f64,
            ROWS.rule,
        )?;
        check(&HOLD, self.hold as f64, |v| v >= 1.0)?;
        for row in &self.rows {
            for (i, f) in row.iter().enumerate() {
                check(&FORCE, *f, |_| true).map_err(|e| e.on_axis(i))?;
            }
        }
        Ok(())
    }
}

impl<const D: usize> Declared for Tabulated<D> {
    const SCHEMA: Schema = Schema::new(&[ROWS, HOLD, AFTER]);
}

impl<const D: usize> FromParams for Tabulated<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let hold = p.scalar(&HOLD)?;
        if !(hold >= 1.0 && hold.fract() == 0.0 && hold <= u32::MAX as f64) {
            return Err(ParamError::new(HOLD.name, hold, HOLD.rule).into());
        }
        let after = p.choice::<AfterTable>(&AFTER)?;
        let n = p.list_len(&ROWS)?;
        let mut rows = Vec::with_capacity(n);
        for j in 0..n {
            rows.push(p.list_item(&ROWS, j, |q| q.axes::<D>(&FORCE))?);
        }
        Ok(Self {
            rows,
            hold: hold as usize,
            after,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::RefPoint;
    use nalgebra::Vector3;

    fn input(k: usize, dt: f64, mass: f64) -> LawInput<3> {
        LawInput {
            t: k as f64 * dt,
            dt,
            e: SVector::zeros(),
            de: SVector::zeros(),
            reference: RefPoint {
                position: SVector::zeros(),
                velocity: SVector::zeros(),
                acceleration: SVector::zeros(),
            },
            drift: SVector::zeros(),
            inertia: SVector::repeat(mass),
        }
    }

    fn law(after: AfterTable) -> Tabulated<3> {
        Tabulated {
            rows: vec![
                Vector3::new(100.0, -200.0, 300.0),
                Vector3::new(1.0, 2.0, 3.0),
            ],
            hold: 3,
            after,
        }
    }

    #[test]
    fn holds_each_row_for_its_periods_and_divides_by_the_inertia() {
        let l = law(AfterTable::Hold);
        // dt = 0.1 is not exact in binary: k dt / dt must still give k
        for k in 0..3 {
            let a = l.command(&(), &input(k, 0.1, 50.0));
            assert_eq!(a, Vector3::new(2.0, -4.0, 6.0), "k = {k}");
        }
        for k in 3..6 {
            let a = l.command(&(), &input(k, 0.1, 2.0));
            assert_eq!(a, Vector3::new(0.5, 1.0, 1.5), "k = {k}");
        }
    }

    #[test]
    fn after_the_table_holds_the_last_row_or_stops() {
        let a = law(AfterTable::Hold).command(&(), &input(1000, 1e-3, 1.0));
        assert_eq!(a, Vector3::new(1.0, 2.0, 3.0));
        let a = law(AfterTable::Zero).command(&(), &input(6, 1e-3, 1.0));
        assert_eq!(a, Vector3::zeros());
        let a = law(AfterTable::Zero).command(&(), &input(5, 1e-3, 1.0));
        assert_eq!(a, Vector3::new(1.0, 2.0, 3.0));
    }

    #[test]
    fn the_row_index_survives_long_tables_at_fine_steps() {
        // 30 s at 1 ms: t = k dt rounds back to k at every instant
        let dt = 1e-3;
        for k in [0usize, 1, 999, 1000, 29_999, 30_000] {
            let t = k as f64 * dt;
            assert_eq!((t / dt).round() as usize, k);
        }
    }

    #[test]
    fn validation_refuses_an_empty_table_and_zero_hold() {
        let mut l = law(AfterTable::Hold);
        l.rows.clear();
        assert_eq!(l.validate().unwrap_err().param, "rows");
        let l = Tabulated {
            hold: 0,
            ..law(AfterTable::Hold)
        };
        assert_eq!(l.validate().unwrap_err().param, "hold");
        assert!(law(AfterTable::Zero).validate().is_ok());
    }
}
