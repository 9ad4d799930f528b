//! The law handle: a controller table compiled once, through the core's law registry, for the
//! axis counts the plants use.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::control::{LawKind, Laws};
use landing_core::params::{ByAxes, Table};

use crate::errors::{InputError, axes_error, guard};
use crate::{output, table};

/// A compiled law (`landing.controllers.Controller` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Law {
    pub kind: String,
    table: Table,
    pub compiled: ByAxes<Laws>,
}

#[pymethods]
impl Law {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = table::from_py(owner, table)?;
            // a table meant for 2 axes gets the 2-axis reading's error (read for 3 axes, its
            // per-axis arrays would be one value per case)
            let compiled =
                ByAxes::compile(owner, &t, t.meant_for_two_axes()).map_err(InputError::from)?;
            Ok(Self {
                kind: t.kind().unwrap_or_default().to_string(),
                table: t,
                compiled,
            })
        })
    }

    #[getter]
    fn kind(&self) -> PyResult<&str> {
        guard(|| Ok(self.kind.as_str()))
    }

    /// The axis counts the law's parameters fit.
    #[getter]
    fn axes(&self) -> PyResult<Vec<usize>> {
        guard(|| Ok(self.compiled.axes()))
    }

    /// Names and widths of the diagnostic signals for `axes` axes.
    fn diagnostic_layout(&self, axes: usize) -> PyResult<Vec<(&'static str, usize)>> {
        guard(|| {
            landing_core::with_axes!(axes, D => {
                Ok(self.compiled.get::<D>().map_err(InputError::from)?.0.get(0).diagnostic_layout())
            }, a => Err(axes_error(a).into()))
        })
    }

    /// The numeric parameter `name` as the law reads it for `axes` axes (see `output::parameter`).
    fn parameter<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        axes: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| output::parameter(py, self.table.values::<LawKind>(name, axes), &self.kind))
    }
}
