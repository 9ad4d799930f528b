//! Reading a configured model from a table of named parameters.
//!
//! Each plant, law, gravity field, reference and disturbance reads its own keys
//! ([`FromParams`], written beside the type), from a [`ParamSource`]: a table positioned at one
//! case of a batch. The Python bindings implement the source over the Python layer's
//! parameter tables (and know how many cases a table holds); the registries
//! ([`crate::registry`], [`crate::control::AnyLaw`]) pick the type from the table's `kind`.

use std::sync::Arc;

use nalgebra::SVector;

use crate::error::ParamError;
use crate::fuzzy::Mamdani;

mod names;

pub use names::{Counted, Named};

/// A table of named parameters, read at one case.
pub trait ParamSource {
    type Error: From<ParamError>;

    /// A number: shared by every case, or this case's.
    fn scalar(&mut self, key: &'static str) -> Result<f64, Self::Error>;

    /// A number that may be absent (or None).
    fn opt_scalar(&mut self, key: &'static str) -> Result<Option<f64>, Self::Error>;

    /// D numbers, one per axis (a single number serves every axis).
    fn axes<const D: usize>(&mut self, key: &'static str) -> Result<SVector<f64, D>, Self::Error>;

    /// D numbers that may be absent (or None).
    fn opt_axes<const D: usize>(
        &mut self,
        key: &'static str,
    ) -> Result<Option<SVector<f64, D>>, Self::Error>;

    /// One of `T`'s names, shared by every case.
    fn choice<T: Named>(&mut self, key: &'static str) -> Result<T, Self::Error>;

    /// A flag, shared by every case.
    fn flag(&mut self, key: &'static str) -> Result<bool, Self::Error>;

    /// A whole number in `allowed`, shared by every case (it fixes a size or a type).
    fn count(
        &mut self,
        key: &'static str,
        allowed: &'static [usize],
        rule: &'static str,
    ) -> Result<usize, Self::Error>;

    /// The `kind` of the table being read, one of `T`'s names (an error naming them if it is
    /// none of them).
    fn kind<T: Named>(&mut self) -> Result<T, Self::Error>;

    /// A whole number among `T`'s values, shared by every case (it picks a compiled type).
    fn count_of<T: Counted>(
        &mut self,
        key: &'static str,
        rule: &'static str,
    ) -> Result<T, Self::Error> {
        let n = self.count(key, T::VALUES, rule)?;
        T::from_value(n).ok_or_else(|| ParamError::new(key, n as f64, rule).into())
    }

    /// Reads the nested table `key` with `read`.
    fn nested<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&mut Self) -> Result<T, Self::Error>,
    ) -> Result<T, Self::Error>;

    /// Number of tables in the list `key` (0 if absent).
    fn list_len(&mut self, key: &'static str) -> Result<usize, Self::Error>;

    /// Reads table `index` of the list `key` with `read`.
    fn list_item<T>(
        &mut self,
        key: &'static str,
        index: usize,
        read: impl FnOnce(&mut Self) -> Result<T, Self::Error>,
    ) -> Result<T, Self::Error>;

    /// A fuzzy inference system, shared by every case.
    fn fuzzy_system(&mut self, key: &'static str) -> Result<Arc<Mamdani>, Self::Error>;

    /// Marks `key` as known but unused by this kind (so that it is not reported as unknown).
    fn skip(&mut self, key: &'static str);
}

/// A configured model that reads its parameters from a table (one case at a time).
pub trait FromParams: Sized {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, S::Error>;
}
