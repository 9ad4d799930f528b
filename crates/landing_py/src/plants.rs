//! The plant handle: a plant table compiled once (one plant per case, or one for all, through
//! the core's registry), with the queries the Python layer makes of it.

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::params::{Cases, Table};
use landing_core::registry::{AnyPlant, PlantKind};

use crate::errors::{InputError, guard};
use crate::{output, table};

/// A compiled plant (`landing.plants.Plant` holds one): one per case, or one for all.
#[pyclass(frozen, module = "landing._core")]
pub struct Plant {
    pub plants: AnyPlant,
    pub cases: Cases,
    pub kind: String,
    table: Table,
}

#[pymethods]
impl Plant {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = table::from_py(owner, table)?;
            let (plants, cases) =
                AnyPlant::from_table(&t).map_err(|e| InputError::from(e).context(owner))?;
            Ok(Self {
                plants,
                cases,
                kind: t.kind().unwrap_or_default().to_string(),
                table: t,
            })
        })
    }

    #[getter]
    fn kind(&self) -> PyResult<&str> {
        guard(|| Ok(self.kind.as_str()))
    }

    /// Number of generalized coordinates.
    #[getter]
    fn axes(&self) -> PyResult<usize> {
        guard(|| Ok(self.plants.axes()))
    }

    /// Number of cases the parameters hold (1 when shared).
    #[getter]
    fn cases(&self) -> PyResult<usize> {
        guard(|| Ok(self.cases.count))
    }

    /// state_names, control_names, axes, max_step and the model's derived figures (the
    /// tethered satellite's inertia, orbital_rate, thrust_limit, torque_limit, and for the
    /// flexible model nodes and segment_length), of the first case.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        guard(|| {
            let info = self.plants.info();
            let d = PyDict::new(py);
            d.set_item("state_names", info.state_names.to_vec())?;
            d.set_item("control_names", info.control_names.to_vec())?;
            d.set_item("axes", info.axes)?;
            d.set_item("max_step", info.max_step)?;
            for (name, v) in info.figures {
                match v.as_slice() {
                    [x] => d.set_item(name, x)?,
                    _ => d.set_item(name, v)?,
                }
            }
            Ok(d)
        })
    }

    /// The generalized coordinates (q, q') the laws read, for states (M, state dim).
    fn coordinates<'py>(
        &self,
        py: Python<'py>,
        states: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        guard(|| {
            let [rows, width] = [states.shape()[0], states.shape()[1]];
            let (q, qd) = self
                .plants
                .coordinates(states.as_slice()?, width)
                .map_err(InputError::from)?;
            let axes = self.plants.axes();
            Ok((
                output::shaped(py, q, [rows, axes])?,
                output::shaped(py, qd, [rows, axes])?,
            ))
        })
    }

    /// States (M, state dim) at coordinates: rows (q, q') of 2 D values, for the plants whose
    /// state they determine (the tethered satellite: phi, theta, phi_dot, theta_dot).
    fn state_at<'py>(
        &self,
        py: Python<'py>,
        rows: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            let n = rows.shape()[0];
            let data = self
                .plants
                .states_at(rows.as_slice()?, [n, rows.shape()[1]]);
            let data = data.map_err(InputError::from)?;
            let nx = data.len() / n.max(1);
            output::shaped(py, data, [n, nx])
        })
    }

    /// The numeric parameter `name` as the plant reads it (see `output::parameter`).
    fn parameter<'py>(
        &self,
        py: Python<'py>,
        name: &str,
        axes: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| output::parameter(py, self.table.values::<PlantKind>(name, axes), &self.kind))
    }
}
