//! Reading parameter tables from Python and broadcasting them over the cases of a batch.
//!
//! Every numeric parameter may be shared or given per case (SPEC 8):
//! - a scalar parameter takes `()` or `(N,)`;
//! - a per-axis parameter takes `()`, `(D,)` per axis, `(N, D)` per case and axis, `(N, 1)`
//!   or `(N,)` per case (the same on every axis). A 1-D array whose length is D is read per
//!   axis, even when N = D; give `(N, 1)` to sweep per case then.

use nalgebra::SVector;
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use landing_core::{ParamError, PerCase};

use crate::errors::{InputError, param_error};

pub fn pick<T: Copy>(values: &[T], case: usize) -> T {
    values[if values.len() == 1 { 0 } else { case }]
}

pub struct Params<'py> {
    /// What the table describes, for messages (e.g. "FixedTimeMSS").
    pub owner: String,
    dict: Bound<'py, PyDict>,
    /// Number of cases; `None` while it is inferred from the first per-case parameter.
    n: Option<usize>,
    per_case: bool,
}

/// A numeric array read from Python, in C order.
struct Array {
    data: Vec<f64>,
    shape: Vec<usize>,
}

fn shape_str(shape: &[usize]) -> String {
    match shape {
        [a] => format!("({a},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

impl<'py> Params<'py> {
    pub fn new(owner: impl Into<String>, dict: Bound<'py, PyDict>, n: Option<usize>) -> Self {
        Self {
            owner: owner.into(),
            dict,
            n,
            per_case: false,
        }
    }

    /// How many values each per-case table holds: N if any parameter was per case, else 1.
    pub fn count(&self) -> usize {
        if self.per_case {
            self.n.unwrap_or(1)
        } else {
            1
        }
    }

    fn raw(&self, key: &str) -> Result<Option<Bound<'py, PyAny>>, InputError> {
        match self.dict.get_item(key)? {
            Some(v) if !v.is_none() => Ok(Some(v)),
            _ => Ok(None),
        }
    }

    fn array(&self, key: &str) -> Result<Option<Array>, InputError> {
        let Some(obj) = self.raw(key)? else {
            return Ok(None);
        };
        let arr: PyReadonlyArrayDyn<'py, f64> = obj.extract().map_err(|_| {
            InputError::Type(format!(
                "{key} must be a real number or an array of real numbers"
            ))
        })?;
        let shape = arr.shape().to_vec();
        let data: Vec<f64> = arr.as_array().iter().copied().collect();
        if let Some((i, v)) = data.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            let at = if data.len() > 1 {
                format!(" (entry {i})")
            } else {
                String::new()
            };
            return Err(InputError::Value(format!(
                "{key} = {v} violates finite values{at}"
            )));
        }
        Ok(Some(Array { data, shape }))
    }

    /// Registers a per-case length for `key`.
    fn claim(&mut self, key: &str, len: usize) -> Result<(), InputError> {
        match self.n {
            Some(n) if n != len => Err(InputError::Shape(format!(
                "{key} has {len} values per case but the batch has {n} cases"
            ))),
            _ => {
                self.n = Some(len);
                self.per_case = true;
                Ok(())
            }
        }
    }

    fn required(&self, key: &str) -> InputError {
        InputError::Type(format!("missing parameter {key}"))
    }

    /// A scalar parameter: shared (one value) or per case (N values).
    pub fn scalar(&mut self, key: &str) -> Result<Vec<f64>, InputError> {
        let a = self.array(key)?.ok_or_else(|| self.required(key))?;
        match a.shape.as_slice() {
            [] | [1] => Ok(a.data),
            [len] => {
                self.claim(key, *len)?;
                Ok(a.data)
            }
            s => Err(InputError::Shape(format!(
                "{key} has shape {}; it takes a scalar or one value per case, shape (N,)",
                shape_str(s)
            ))),
        }
    }

    /// An optional scalar parameter (absent or None gives `None`).
    pub fn opt_scalar(&mut self, key: &str) -> Result<Option<Vec<f64>>, InputError> {
        if self.raw(key)?.is_none() {
            return Ok(None);
        }
        self.scalar(key).map(Some)
    }

    /// A count shared by every case (it fixes a type or a size): a whole number in
    /// `allowed`.
    pub fn shared_count(
        &mut self,
        key: &str,
        allowed: &[usize],
        rule: &str,
    ) -> Result<usize, InputError> {
        let values = self.scalar(key)?;
        let first = values[0];
        if values.iter().any(|&v| v != first) {
            return Err(InputError::Value(format!(
                "{key} must be the same for every case (it fixes the model's size)"
            )));
        }
        let n = first as usize;
        if first.fract() != 0.0 || first < 0.0 || !allowed.contains(&n) {
            return Err(InputError::Value(format!(
                "{key} = {first} violates {rule}"
            )));
        }
        Ok(n)
    }

    /// A per-axis parameter (see the module documentation for the accepted shapes).
    pub fn axes<const D: usize>(&mut self, key: &str) -> Result<Vec<SVector<f64, D>>, InputError> {
        self.opt_axes(key)?.ok_or_else(|| self.required(key))
    }

    pub fn opt_axes<const D: usize>(
        &mut self,
        key: &str,
    ) -> Result<Option<Vec<SVector<f64, D>>>, InputError> {
        let Some(a) = self.array(key)? else {
            return Ok(None);
        };
        let repeat = |v: &[f64]| v.iter().map(|&x| SVector::repeat(x)).collect::<Vec<_>>();
        let rows = |v: &[f64]| {
            v.chunks_exact(D)
                .map(SVector::<f64, D>::from_column_slice)
                .collect::<Vec<_>>()
        };
        let out = match a.shape.as_slice() {
            [] | [1] => repeat(&a.data),
            [d] if *d == D => rows(&a.data),
            [len] => {
                self.claim(key, *len)?;
                repeat(&a.data)
            }
            [1, d] if *d == D => rows(&a.data),
            [len, 1] => {
                self.claim(key, *len)?;
                repeat(&a.data)
            }
            [len, d] if *d == D => {
                self.claim(key, *len)?;
                rows(&a.data)
            }
            s => {
                return Err(InputError::Shape(format!(
                    "{key} has shape {}; it takes a scalar, one value per axis ({D},), or per case (N,), (N, 1), (N, {D})",
                    shape_str(s)
                )));
            }
        };
        Ok(Some(out))
    }

    /// A nested table (a plant's gravity field, a law's fuzzy system).
    pub fn table(&self, key: &str, what: &str) -> Result<Bound<'py, PyDict>, InputError> {
        self.raw(key)?
            .ok_or_else(|| self.required(key))?
            .cast_into::<PyDict>()
            .map_err(|_| InputError::Type(format!("{key} must be {what}")))
    }

    /// A list of nested tables (e.g. the components of a disturbance).
    pub fn list_of_dicts(&self, key: &str) -> Result<Vec<Bound<'py, PyDict>>, InputError> {
        let Some(obj) = self.raw(key)? else {
            return Ok(Vec::new());
        };
        let mut out = Vec::new();
        for item in obj
            .try_iter()
            .map_err(|_| InputError::Type(format!("{key} must be a list")))?
        {
            let item = item?;
            out.push(
                item.cast_into::<PyDict>()
                    .map_err(|_| InputError::Type(format!("{key} must be a list of tables")))?,
            );
        }
        Ok(out)
    }

    /// Adopts the case count found by a nested table.
    pub fn merge(&mut self, other: &Params<'py>) -> Result<(), InputError> {
        if other.per_case {
            self.claim("(nested)", other.n.unwrap_or(1))?;
        }
        Ok(())
    }

    pub fn child(&self, dict: Bound<'py, PyDict>) -> Params<'py> {
        Params {
            owner: self.owner.clone(),
            dict,
            n: self.n,
            per_case: false,
        }
    }

    /// One of a fixed set of names.
    pub fn choice(&self, key: &str, names: &[&str]) -> Result<String, InputError> {
        let obj = self.raw(key)?.ok_or_else(|| self.required(key))?;
        let s = obj
            .cast::<PyString>()
            .map_err(|_| InputError::Type(format!("{key} must be a string, one of {names:?}")))?
            .to_string();
        if names.contains(&s.as_str()) {
            Ok(s)
        } else {
            Err(InputError::Value(format!(
                "{key} = {s:?} is not one of {names:?}"
            )))
        }
    }

    pub fn flag(&self, key: &str) -> Result<bool, InputError> {
        let obj = self.raw(key)?.ok_or_else(|| self.required(key))?;
        obj.extract::<bool>()
            .map_err(|_| InputError::Type(format!("{key} must be True or False")))
    }

    /// `count` values built by `make(case)`, each checked by `validate`.
    pub fn build<T>(
        &self,
        make: impl Fn(usize) -> T,
        validate: impl Fn(&T) -> Result<(), ParamError>,
    ) -> Result<PerCase<T>, InputError> {
        let count = self.count();
        let mut items = Vec::with_capacity(count);
        for i in 0..count {
            let item = make(i);
            validate(&item).map_err(|e| param_error(&e, (count > 1).then_some(i)))?;
            items.push(item);
        }
        Ok(PerCase::from_vec(items))
    }
}
