//! The plant handle: a plant table compiled once ([`PlantCase`] per case, through the core's
//! registry), with the queries the Python layer makes of it.

use nalgebra::SVector;
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::PerCase;
use landing_core::plant::PlantModel;
use landing_core::registry::{AnyPlant, PlantCase, PlantVisitor};
use landing_core::state::State;

use crate::errors::{InputError, guard};
use crate::output;
use crate::table::{Cases, Table};

/// A compiled plant (`landing.plants.Plant` holds one): one per case, or one for all.
#[pyclass(frozen, module = "landing._core")]
pub struct Plant {
    pub plants: AnyPlant,
    pub cases: Cases,
    pub kind: String,
}

impl Plant {
    pub fn compile(owner: &str, table: &Table) -> Result<Self, InputError> {
        let (cases, found) = table
            .read_cases(None, |p| PlantCase::from_params(p))
            .map_err(|e| e.context(owner))?;
        let plants = AnyPlant::from_cases(cases.iter().cloned().collect()).map_err(|m| {
            InputError::value(format!(
                "{owner}: case {} has another plant type than case 0 (nodes or the gravity field's kind differ)",
                m.case
            ))
        })?;
        Ok(Self {
            plants,
            cases: found,
            kind: table.kind().unwrap_or_default().to_string(),
        })
    }
}

/// Names, axes, figures and the largest stable step of a batch's plants.
struct Describe;

type Description = (
    &'static [&'static str],
    &'static [&'static str],
    usize,
    Vec<(&'static str, Vec<f64>)>,
    f64,
);

impl PlantVisitor for Describe {
    type Output = Description;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Description {
        // the smallest step over the cases, so one integrator step serves the whole batch
        let step = plants
            .iter()
            .map(|p| p.max_step())
            .fold(f64::INFINITY, f64::min);
        (
            P::STATE_NAMES,
            P::CONTROL_NAMES,
            D,
            plants.get(0).figures(),
            step,
        )
    }
}

/// The state names of a batch's plants.
pub struct Names;

impl PlantVisitor for Names {
    type Output = (&'static [&'static str],);
    fn visit<const D: usize, P: PlantModel<D>>(self, _plants: &PerCase<P>) -> Self::Output {
        (P::STATE_NAMES,)
    }
}

/// The coordinates (q, q') of states (rows of the state).
struct Coordinates<'a> {
    states: &'a [f64],
    rows: usize,
}

impl PlantVisitor for Coordinates<'_> {
    type Output = (Vec<f64>, Vec<f64>, usize);
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output {
        let nx = P::STATE_DIM;
        let (mut q, mut qd) = (
            Vec::with_capacity(self.rows * D),
            Vec::with_capacity(self.rows * D),
        );
        for row in self.states.chunks_exact(nx) {
            let x = <P as landing_core::plant::Plant<f64, D>>::State::from_components(|i| row[i]);
            let (a, b) = plants.get(0).coordinates(&x);
            q.extend_from_slice(a.as_slice());
            qd.extend_from_slice(b.as_slice());
        }
        (q, qd, D)
    }
}

/// States from rows of (q, q').
struct StatesAt<'a> {
    rows: &'a [f64],
}

impl PlantVisitor for StatesAt<'_> {
    type Output = Result<Vec<f64>, InputError>;
    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output {
        let n = self.rows.len() / (2 * D);
        if plants.len() != 1 && plants.len() != n {
            return Err(InputError::value(format!(
                "the plant has {} cases and the coordinates {n} rows",
                plants.len()
            )));
        }
        let mut out = Vec::with_capacity(n * P::STATE_DIM);
        for (i, r) in self.rows.chunks_exact(2 * D).enumerate() {
            if let Some(v) = r.iter().find(|v| !v.is_finite()) {
                return Err(InputError::value(format!(
                    "coordinates[{i}] = {v} violates finite values"
                )));
            }
            let q = SVector::<f64, D>::from_column_slice(&r[..D]);
            let qd = SVector::<f64, D>::from_column_slice(&r[D..]);
            match plants.get(i).state_at(&q, &qd) {
                None => {
                    return Err(InputError::value(
                        "this plant's state is not determined by its coordinates",
                    ));
                }
                Some(x) => {
                    let x = x.map_err(|e| InputError::from(e).context(&format!("row {i}")))?;
                    if x.iter().any(|v| !v.is_finite()) {
                        return Err(InputError::value(format!(
                            "coordinates[{i}] = {r:?} violates coordinates that give a finite state (angles and rates too large)"
                        )));
                    }
                    out.extend(x)
                }
            }
        }
        Ok(out)
    }
}

#[pymethods]
impl Plant {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            Ok(Self::compile(
                owner,
                &Table::from_py(table).map_err(|e| e.context(owner))?,
            )?)
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
        guard(|| self.info_unguarded(py))
    }

    /// The generalized coordinates (q, q') the laws read, for states (M, state dim).
    fn coordinates<'py>(
        &self,
        py: Python<'py>,
        states: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        guard(|| self.coordinates_unguarded(py, states))
    }

    /// States (M, state dim) at coordinates: rows (q, q') of 2 D values, for the plants whose
    /// state they determine (the tethered satellite: phi, theta, phi_dot, theta_dot).
    fn state_at<'py>(
        &self,
        py: Python<'py>,
        rows: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| self.state_at_unguarded(py, rows))
    }
}

impl Plant {
    fn info_unguarded<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (state, control, axes, figures, step) = self.plants.visit(Describe);
        let d = PyDict::new(py);
        d.set_item("state_names", state.to_vec())?;
        d.set_item("control_names", control.to_vec())?;
        d.set_item("axes", axes)?;
        d.set_item("max_step", step)?;
        for (name, v) in figures {
            if v.len() == 1 {
                d.set_item(name, v[0])?;
            } else {
                d.set_item(name, v)?;
            }
        }
        Ok(d)
    }

    fn coordinates_unguarded<'py>(
        &self,
        py: Python<'py>,
        states: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let (names, ..) = self.plants.visit(Describe);
        let shape = states.shape();
        if shape[1] != names.len() {
            return Err(InputError::value(format!(
                "states have {} components; this plant's have {} ({names:?})",
                shape[1],
                names.len()
            ))
            .into());
        }
        let data = states.as_slice()?;
        let (q, qd, d) = self.plants.visit(Coordinates {
            states: data,
            rows: shape[0],
        });
        Ok((
            output::array2(py, q, shape[0], d)?,
            output::array2(py, qd, shape[0], d)?,
        ))
    }

    fn state_at_unguarded<'py>(
        &self,
        py: Python<'py>,
        rows: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let axes = self.plants.axes();
        let shape = rows.shape();
        if shape[1] != 2 * axes {
            return Err(InputError::value(format!(
                "coordinates have shape ({}, {}); give (M, {}): q then q'",
                shape[0],
                shape[1],
                2 * axes
            ))
            .into());
        }
        let data = self.plants.visit(StatesAt {
            rows: rows.as_slice()?,
        })?;
        let nx = data.len() / shape[0].max(1);
        output::array2(py, data, shape[0], nx)
    }
}
