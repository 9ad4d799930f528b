//! The gravity handle: a field compiled once through the core's registry, evaluated on demand.

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::PerCase;
use landing_core::params::Table;
use landing_core::registry::{AnyGravity, GravityKind};

use crate::errors::{InputError, guard};
use crate::{output, table};

/// A compiled gravity field (`landing.gravity.Gravity` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Gravity {
    /// One per case, or one for all.
    fields: PerCase<AnyGravity>,
    table: Table,
}

#[pymethods]
impl Gravity {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = table::from_py(owner, table)?;
            let (fields, _) = t
                .read_cases(None, |p| AnyGravity::from_params(p))
                .map_err(|e| InputError::from(e).context(owner))?;
            Ok(Self { fields, table: t })
        })
    }

    /// The field's kind (one of GRAVITY_KINDS).
    #[getter]
    fn kind(&self) -> PyResult<&'static str> {
        guard(|| Ok(self.fields.get(0).kind().name()))
    }

    /// Acceleration (N, 3) or potential (N,) at positions (N, 3).
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        positions: PyReadonlyArray2<'py, f64>,
        potential: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let (r, shape) = (
                positions.as_slice()?,
                [positions.shape()[0], positions.shape()[1]],
            );
            let field = self.fields.single("evaluating a field");
            let out = field.and_then(|f| f.evaluate(r, shape, potential));
            let out = out.map_err(InputError::from)?;
            let arr = PyArray1::from_vec(py, out);
            Ok(if potential {
                arr.into_any()
            } else {
                arr.reshape(shape)?.into_any()
            })
        })
    }

    /// The numeric parameter `name` as the field reads it (see `output::parameter`).
    fn parameter<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        axes: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let owner = self.fields.get(0).kind().name();
            output::parameter(py, self.table.values::<GravityKind>(name, axes), owner)
        })
    }
}
