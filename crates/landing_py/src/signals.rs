//! Reference and disturbance handles: tables compiled once for each axis count.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::disturbance::{COMPONENTS, Disturbances, component_values, components_of};
use landing_core::error::finite;
use landing_core::params::{ByAxes, Table};
use landing_core::reference::{ReferenceKind, References, cubic_from_slices};
use landing_core::with_axes;

use crate::errors::{InputError, axes_error, guard};
use crate::{output, table};

/// A compiled reference (`landing.reference.Reference` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Reference {
    table: Table,
    pub compiled: ByAxes<References>,
}

#[pymethods]
impl Reference {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = table::from_py(owner, table)?;
            let compiled = ByAxes::compile(owner, &t, false).map_err(InputError::from)?;
            Ok(Self { table: t, compiled })
        })
    }

    /// Position, velocity and acceleration at times `t`, each (T, axes).
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        axes: usize,
        t: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            finite("t", &t).map_err(InputError::from)?;
            let values = with_axes!(axes, D => {
                let (refs, _) = self.compiled.get::<D>().map_err(InputError::from)?;
                let reference = refs.single("evaluate()").map_err(InputError::from)?;
                reference.trajectory(&t).map_err(InputError::from)?
            }, a => return Err(axes_error(a).into()));
            let d = PyDict::new(py);
            for (name, v) in ["position", "velocity", "acceleration"]
                .into_iter()
                .zip(values)
            {
                d.set_item(name, output::shaped(py, v, [t.len(), axes])?)?;
            }
            Ok(d)
        })
    }

    /// The numeric parameter `name` as the reference reads it (see `output::parameter`).
    fn parameter<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        axes: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            output::parameter(
                py,
                self.table.values::<ReferenceKind>(name, axes),
                "reference",
            )
        })
    }
}

/// A compiled disturbance (`landing.disturbances.Disturbance` holds one): the sum of its
/// components.
#[pyclass(frozen, module = "landing._core")]
pub struct Disturbance {
    /// The components' tables, kept to build sums.
    components: Vec<Table>,
    pub compiled: ByAxes<Disturbances>,
}

impl Disturbance {
    fn from_components(owner: &str, components: Vec<Table>) -> Result<Self, InputError> {
        let table = Table::with_list(COMPONENTS.name, components.clone());
        Ok(Self {
            compiled: ByAxes::compile(owner, &table, false)?,
            components,
        })
    }
}

#[pymethods]
impl Disturbance {
    /// A disturbance from its table `{"components": [...]}`.
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let components = components_of(&table::from_py(owner, table)?, owner);
            Ok(Self::from_components(
                owner,
                components.map_err(InputError::from)?,
            )?)
        })
    }

    /// The disturbances acting together (their components add up).
    #[staticmethod]
    fn combine(parts: Vec<PyRef<'_, Disturbance>>) -> PyResult<Self> {
        guard(|| {
            let components = parts
                .iter()
                .flat_map(|p| p.components.iter().cloned())
                .collect();
            Ok(Self::from_components("disturbance", components)?)
        })
    }

    /// Per-axis bound on |d_i(t)| (shared by all cases): |constant| + sum of |amplitudes| +
    /// noise bound.
    fn bound(&self, axes: usize) -> PyResult<Vec<f64>> {
        guard(|| {
            with_axes!(axes, D => {
                let (d, _) = self.compiled.get::<D>().map_err(InputError::from)?;
                let d = d.single("the bound").map_err(InputError::from)?;
                Ok(d.bound().as_slice().to_vec())
            }, a => Err(axes_error(a).into()))
        })
    }

    /// The numeric parameter `name` of the component that has it (see `output::parameter`).
    fn parameter<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        axes: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let values = component_values(&self.components, name, axes);
            output::parameter(py, values, "disturbance")
        })
    }
}

/// Coefficients (c0, c1, c2, c3), each of length D, of the cubic through the boundary states.
#[pyfunction]
pub fn cubic_from_boundary(
    p0: Vec<f64>,
    v0: Vec<f64>,
    pt: Vec<f64>,
    vt: Vec<f64>,
    t_end: f64,
) -> PyResult<[Vec<f64>; 4]> {
    guard(|| Ok(cubic_from_slices(&p0, &v0, &pt, &vt, t_end).map_err(InputError::from)?))
}
