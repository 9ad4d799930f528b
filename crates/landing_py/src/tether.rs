//! What the tethered satellite needs beyond the generic plant bindings: states from angles
//! (the flexible model's state holds positions, not angles) and its derived figures.

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::PerCase;
use landing_core::plant::Plant;
use landing_core::plant::tether::{TetherBody, TetheredFlexible};
use landing_core::state::State;

use crate::errors::{InputError, to_pyerr};
use crate::output;
use crate::params::Params;
use crate::specs::{PlantSpec, kind_of, parse_plant};

fn body_items(d: &Bound<'_, PyDict>, b: &TetherBody) -> PyResult<()> {
    d.set_item("inertia", b.inertia().as_slice().to_vec())?;
    d.set_item("orbital_rate", b.orbital_rate)?;
    d.set_item("thrust_limit", b.thrust_limit)?;
    d.set_item("torque_limit", b.torque_limit)?;
    Ok(())
}

fn flexible_items<const N: usize, const S: usize>(
    d: &Bound<'_, PyDict>,
    plants: &PerCase<TetheredFlexible<N, S>>,
) -> PyResult<()> {
    let first = plants.get(0);
    body_items(d, &first.body)?;
    d.set_item("nodes", N)?;
    d.set_item("segment_length", first.segment_length())?;
    // the smallest over the cases, so one integrator step serves the whole batch
    let step = plants
        .iter()
        .map(|p| p.max_step())
        .fold(f64::INFINITY, f64::min);
    d.set_item("max_step", step)?;
    Ok(())
}

/// Adds the tethered satellite's derived figures to `plant_info`: the controller's inertia,
/// the orbital rate and the actuator limits of the first case, and for the flexible model its
/// node count, segment length and the largest stable RK4 step over the cases.
pub fn extras(spec: &PlantSpec, d: &Bound<'_, PyDict>) -> PyResult<()> {
    match spec {
        PlantSpec::TetherSimplified(p) => {
            body_items(d, &p.get(0).body)?;
            d.set_item("max_step", f64::INFINITY)
        }
        PlantSpec::TetherFlexible2(p) => flexible_items(d, p),
        PlantSpec::TetherFlexible4(p) => flexible_items(d, p),
        PlantSpec::TetherFlexible8(p) => flexible_items(d, p),
        PlantSpec::TetherFlexible16(p) => flexible_items(d, p),
        PlantSpec::Mars(_)
        | PlantSpec::DoubleIntegrator(_)
        | PlantSpec::SmallBodyPointMass(_)
        | PlantSpec::SmallBodyTwoPointMass(_)
        | PlantSpec::SmallBodyHarmonic2(_) => Ok(()),
    }
}

/// Builds a plant's states from rows (phi, theta, phi', theta').
trait FromAngles: Plant<2> {
    fn state_from_angles(&self, a: [f64; 4]) -> Result<Self::State, InputError>;
}

impl<const N: usize, const S: usize> FromAngles for TetheredFlexible<N, S> {
    fn state_from_angles(&self, a: [f64; 4]) -> Result<Self::State, InputError> {
        self.state_at(a[0], a[1], a[2], a[3]).map_err(|e| {
            InputError::Value(format!("{} = {} violates {}", e.param, e.value, e.rule))
        })
    }
}

impl FromAngles for landing_core::plant::TetheredSimplified {
    fn state_from_angles(&self, a: [f64; 4]) -> Result<Self::State, InputError> {
        Ok(Self::State::from(a))
    }
}

fn states<P: FromAngles>(
    plants: &PerCase<P>,
    rows: &[[f64; 4]],
) -> Result<(Vec<f64>, usize), InputError> {
    if plants.len() != 1 && plants.len() != rows.len() {
        return Err(InputError::Shape(format!(
            "the plant has {} cases and the angles {} rows",
            plants.len(),
            rows.len()
        )));
    }
    let nx = P::State::DIM;
    let mut out = Vec::with_capacity(rows.len() * nx);
    for (i, r) in rows.iter().enumerate() {
        if let Some(v) = r.iter().find(|v| !v.is_finite()) {
            return Err(InputError::Value(format!(
                "angles[{i}] = {v} violates finite values"
            )));
        }
        let x = plants
            .get(i)
            .state_from_angles(*r)
            .map_err(|e| e.context(&format!("row {i}")))?;
        out.extend_from_slice(x.as_slice());
    }
    Ok((out, nx))
}

/// States (M, state dim) of a tethered satellite from rows (phi, theta, phi', theta'), rad and
/// rad/s: the simplified model's state is the row itself; the flexible model lays the tether
/// straight and stretched by the rigid dumbbell's tension (`TetheredFlexible::state_at`).
#[pyfunction]
pub fn tether_initial_state<'py>(
    py: Python<'py>,
    table: Bound<'py, PyDict>,
    angles: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = angles.shape().to_vec();
    let run = || -> Result<(Vec<f64>, usize), InputError> {
        if shape[1] != 4 {
            return Err(InputError::Shape(format!(
                "angles have shape ({}, {}); give (M, 4): phi, theta, phi_dot, theta_dot",
                shape[0], shape[1]
            )));
        }
        let rows: Vec<[f64; 4]> = angles
            .as_array()
            .outer_iter()
            .map(|r| [r[0], r[1], r[2], r[3]])
            .collect();
        let kind = kind_of(&table, "plant")?;
        let mut p = Params::new(format!("plant ({kind})"), table.clone(), Some(rows.len()));
        let spec = parse_plant(&kind, &mut p).map_err(|e| e.context(&p.owner))?;
        match &spec {
            PlantSpec::TetherSimplified(p) => states(p, &rows),
            PlantSpec::TetherFlexible2(p) => states(p, &rows),
            PlantSpec::TetherFlexible4(p) => states(p, &rows),
            PlantSpec::TetherFlexible8(p) => states(p, &rows),
            PlantSpec::TetherFlexible16(p) => states(p, &rows),
            PlantSpec::Mars(_)
            | PlantSpec::DoubleIntegrator(_)
            | PlantSpec::SmallBodyPointMass(_)
            | PlantSpec::SmallBodyTwoPointMass(_)
            | PlantSpec::SmallBodyHarmonic2(_) => Err(InputError::Value(format!(
                "tether_initial_state takes a tethered_satellite, not a {kind}"
            ))),
        }
    };
    let (data, nx) = run().map_err(|e| to_pyerr(py, e))?;
    output::array2(py, data, shape[0], nx)
}
