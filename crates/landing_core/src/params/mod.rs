//! Reading a configured model from a table of named parameters.
//!
//! Each plant, law, gravity field, reference, disturbance, dispersion and fuzzy system declares
//! its parameters once ([`Param`] constants and its [`Schema`], beside the type) and reads them
//! through those declarations ([`FromParams`]) from a [`ParamSource`]: a table positioned at one
//! case of a batch ([`Reader`] over a [`Table`]). The registries ([`crate::registry`],
//! [`crate::control::AnyLaw`]) pick the type from the table's `kind`.

use std::sync::Arc;

use nalgebra::SVector;

use crate::error::{ParamError, ReadError};
use crate::fuzzy::Mamdani;

mod by_axes;
mod names;
pub mod schema;
mod table;

pub use by_axes::{AxisCount, ByAxes, Dim, ReadFor, read_valid};
pub use names::{Counted, Kinds, Named};
pub use schema::{Declared, Layout, Param, Schema, Shape};
pub use table::{Array, Cases, Reader, Table, Value, Values, shape_str};

/// A table of named parameters, read at one case. Every read names the parameter's
/// declaration, whose name is the key.
pub trait ParamSource {
    /// A number: shared by every case, or this case's.
    fn scalar(&mut self, p: &Param) -> Result<f64, ReadError>;

    /// A number that may be absent (or None).
    fn opt_scalar(&mut self, p: &Param) -> Result<Option<f64>, ReadError>;

    /// D numbers, one per axis (a single number serves every axis).
    fn axes<const D: usize>(&mut self, p: &Param) -> Result<SVector<f64, D>, ReadError>;

    /// D numbers that may be absent (or None).
    fn opt_axes<const D: usize>(&mut self, p: &Param)
    -> Result<Option<SVector<f64, D>>, ReadError>;

    /// A number per component, shared by every case (a single number serves every component).
    fn components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError>;

    /// A number per component, shared (`(K,)` or a scalar) or per case (`(N, K)`, or `(N, 1)`
    /// for one number on every component): this case's ([`Param::per_case`] declares it).
    fn case_components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError>;

    /// One of `T`'s names, shared by every case.
    fn choice<T: Named>(&mut self, p: &Param) -> Result<T, ReadError>;

    /// A flag, shared by every case.
    fn flag(&mut self, p: &Param) -> Result<bool, ReadError>;

    /// A whole number among the parameter's allowed values ([`Shape::Count`]), shared by every
    /// case (it fixes a size or a type).
    fn count(&mut self, p: &Param) -> Result<usize, ReadError>;

    /// [`ParamSource::count`] as one of `T`'s values (the count picks a compiled type).
    fn count_of<T: Counted>(&mut self, p: &Param) -> Result<T, ReadError> {
        let n = self.count(p)?;
        T::from_value(n).ok_or_else(|| ParamError::new(p.name, n as f64, p.rule).into())
    }

    /// The `kind` of the table being read, one of `T`'s names (an error naming them if it is
    /// none of them).
    fn kind<T: Kinds>(&mut self) -> Result<T, ReadError>;

    /// Reads the nested table `p` with `read`.
    fn nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError>;

    /// Reads the nested table `p` with `read` if it is given; None when it is absent.
    fn opt_nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<Option<T>, ReadError>;

    /// Number of tables in the list `p` (0 if absent).
    fn list_len(&mut self, p: &Param) -> Result<usize, ReadError>;

    /// Reads table `index` of the list `p` with `read`.
    fn list_item<T>(
        &mut self,
        p: &Param,
        index: usize,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError>;

    /// A fuzzy inference system, shared by every case.
    fn fuzzy_system(&mut self, p: &Param) -> Result<Arc<Mamdani>, ReadError>;

    /// Marks `p` as known but unused by this kind (so that it is not reported as unknown).
    fn skip(&mut self, p: &Param);
}

/// A configured model that reads its parameters from a table (one case at a time).
pub trait FromParams: Sized {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError>;
}
