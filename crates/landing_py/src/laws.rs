//! The law handle: a controller table compiled once, through the core's law registry, for the
//! axis counts the plants use.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::control::AnyLaw;

use crate::compiled::{ByAxes, ReadFor};
use crate::errors::{InputError, guard};
use crate::table::{Reader, Table};

struct Laws;

impl ReadFor for Laws {
    type At<const D: usize> = AnyLaw<D>;
    fn read<const D: usize>(p: &mut Reader<'_>) -> Result<AnyLaw<D>, InputError> {
        AnyLaw::<D>::from_params(p)
    }
}

/// A compiled law (`landing.controllers.Controller` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Law {
    pub kind: String,
    pub compiled: ByAxes,
}

#[pymethods]
impl Law {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = Table::from_py(table).map_err(|e| e.context(owner))?;
            // a table whose per-axis arrays all have length 2 is meant for 2 axes: its error
            // names the axis (read for 3 axes it would be one value per case)
            let lengths = t.trailing_lengths();
            let two_axes = lengths.contains(&2) && !lengths.contains(&3);
            Ok(Self {
                kind: t.kind().unwrap_or_default().to_string(),
                compiled: ByAxes::compile::<Laws>(owner, &t, two_axes)?,
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
        guard(|| self.diagnostic_layout_unguarded(axes))
    }
}

impl Law {
    fn diagnostic_layout_unguarded(&self, axes: usize) -> PyResult<Vec<(&'static str, usize)>> {
        Ok(match axes {
            3 => self
                .compiled
                .get::<AnyLaw<3>, 3>()?
                .0
                .get(0)
                .diagnostic_layout(),
            2 => self
                .compiled
                .get::<AnyLaw<2>, 2>()?
                .0
                .get(0)
                .diagnostic_layout(),
            _ => {
                return Err(
                    InputError::value(format!("axes = {axes} violates axes in (2, 3)")).into(),
                );
            }
        })
    }
}
