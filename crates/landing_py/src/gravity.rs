//! The gravity handle: a field compiled once through the core's registry, evaluated on demand.

use nalgebra::Vector3;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::registry::AnyGravity;

use crate::errors::{InputError, guard};
use crate::table::Table;

/// A compiled gravity field (`landing.gravity.Gravity` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Gravity {
    /// One per case, or one for all.
    fields: Vec<AnyGravity>,
}

#[pymethods]
impl Gravity {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = Table::from_py(table).map_err(|e| e.context(owner))?;
            let (fields, _) = t
                .read_cases(None, |p| AnyGravity::from_params(p))
                .map_err(|e| e.context(owner))?;
            Ok(Self {
                fields: fields.iter().copied().collect(),
            })
        })
    }

    /// The field's kind (one of GRAVITY_KINDS).
    #[getter]
    fn kind(&self) -> PyResult<&'static str> {
        guard(|| Ok(self.fields[0].kind().name()))
    }

    /// Acceleration (N, 3) or potential (N,) at positions (N, 3).
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        positions: PyReadonlyArray2<'py, f64>,
        potential: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| self.evaluate_unguarded(py, positions, potential))
    }
}

impl Gravity {
    fn evaluate_unguarded<'py>(
        &self,
        py: Python<'py>,
        positions: PyReadonlyArray2<'py, f64>,
        potential: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let shape = positions.shape();
        if shape[1] != 3 {
            return Err(InputError::value(format!(
                "r has shape ({}, {}); it takes (3,) or (N, 3)",
                shape[0], shape[1]
            ))
            .into());
        }
        if self.fields.len() != 1 {
            return Err(InputError::value(
                "evaluating a field needs parameters shared by all cases",
            )
            .into());
        }
        let f = &self.fields[0];
        let r = positions.as_slice()?;
        let n = shape[0];
        if let Some((k, v)) = r.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(InputError::value(format!(
                "r[{}, {}] = {v} violates finite values",
                k / 3,
                k % 3
            ))
            .into());
        }
        let mut out = Vec::with_capacity(if potential { n } else { 3 * n });
        for row in r.chunks_exact(3) {
            let x = Vector3::new(row[0], row[1], row[2]);
            if potential {
                out.push(f.potential(&x));
            } else {
                out.extend_from_slice(f.acceleration(&x).as_slice());
            }
        }
        let arr = PyArray1::from_vec(py, out);
        Ok(if potential {
            arr.into_any()
        } else {
            arr.reshape([n, 3])?.into_any()
        })
    }
}
