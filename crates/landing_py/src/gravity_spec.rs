//! Gravity fields from Python tables, and their evaluation for `landing.gravity`.

use nalgebra::Vector3;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::gravity::{G, GravityField, Harmonic2, PointMass, TwoPointMass};

use crate::errors::{InputError, param_error, to_pyerr};
use crate::params::{Params, pick};
use crate::specs::kind_of;

pub const KINDS: [&str; 3] = ["point_mass", "two_point_mass", "harmonic2"];

/// The fields one per case (or shared), by kind.
pub enum GravitySpec {
    PointMass(Vec<PointMass>),
    TwoPointMass(Vec<TwoPointMass>),
    Harmonic2(Vec<Harmonic2>),
}

fn build<T>(
    n: usize,
    make: impl Fn(usize) -> T,
    check: impl Fn(&T) -> Result<(), landing_core::ParamError>,
) -> Result<Vec<T>, InputError> {
    (0..n)
        .map(|i| {
            let g = make(i);
            check(&g).map_err(|e| param_error(&e, (n > 1).then_some(i)))?;
            Ok(g)
        })
        .collect()
}

/// Reads a gravity table with the case count of `parent` (merged back into it).
pub fn parse_gravity_into<'py>(
    table: Bound<'py, PyDict>,
    parent: &mut Params<'py>,
) -> Result<GravitySpec, InputError> {
    let kind = kind_of(&table, "gravity")?;
    let mut c = parent.child(table);
    let spec = match kind.as_str() {
        "point_mass" => {
            let mu = c.scalar("mu")?;
            parent.merge(&c)?;
            GravitySpec::PointMass(build(
                c.count(),
                |i| PointMass { mu: pick(&mu, i) },
                GravityField::validate,
            )?)
        }
        "two_point_mass" => {
            let m1 = c.scalar("m1")?;
            let m2 = c.scalar("m2")?;
            let p1 = c.axes::<3>("position1")?;
            let p2 = c.axes::<3>("position2")?;
            let g = c.scalar("G")?;
            parent.merge(&c)?;
            GravitySpec::TwoPointMass(build(
                c.count(),
                |i| TwoPointMass {
                    mu: [pick(&g, i) * pick(&m1, i), pick(&g, i) * pick(&m2, i)],
                    positions: [pick(&p1, i), pick(&p2, i)],
                },
                GravityField::validate,
            )?)
        }
        "harmonic2" => {
            let mu = c.scalar("mu")?;
            let r0 = c.scalar("r0")?;
            let c20 = c.scalar("c20")?;
            let c22 = c.scalar("c22")?;
            parent.merge(&c)?;
            GravitySpec::Harmonic2(build(
                c.count(),
                |i| Harmonic2 {
                    mu: pick(&mu, i),
                    r0: pick(&r0, i),
                    c20: pick(&c20, i),
                    c22: pick(&c22, i),
                },
                GravityField::validate,
            )?)
        }
        other => {
            return Err(InputError::Value(format!(
                "unknown gravity kind {other:?}; known: {KINDS:?}"
            )));
        }
    };
    Ok(spec)
}

fn field_values<F: GravityField>(
    fields: &[F],
    r: &[Vector3<f64>],
    potential: bool,
) -> Result<Vec<f64>, InputError> {
    if fields.len() != 1 {
        return Err(InputError::Shape(
            "evaluating a field needs parameters shared by all cases".into(),
        ));
    }
    let f = &fields[0];
    Ok(if potential {
        r.iter().map(|x| f.potential(x)).collect()
    } else {
        r.iter()
            .flat_map(|x| f.acceleration(x).as_slice().to_vec())
            .collect()
    })
}

/// Acceleration (N, 3) or potential (N,) of a gravity table at positions (N, 3).
#[pyfunction]
pub fn evaluate_gravity<'py>(
    py: Python<'py>,
    table: Bound<'py, PyDict>,
    positions: PyReadonlyArray2<'py, f64>,
    potential: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let run = || -> Result<(Vec<f64>, usize), InputError> {
        let shape = positions.shape();
        if shape[1] != 3 {
            return Err(InputError::Shape(format!(
                "r has shape ({}, {}); it takes (3,) or (N, 3)",
                shape[0], shape[1]
            )));
        }
        let view = positions.as_array();
        let r: Vec<Vector3<f64>> = view
            .outer_iter()
            .map(|row| Vector3::new(row[0], row[1], row[2]))
            .collect();
        let mut p = Params::new("gravity", PyDict::new(py), None);
        let spec = parse_gravity_into(table.clone(), &mut p)?;
        let v = match &spec {
            GravitySpec::PointMass(f) => field_values(f, &r, potential)?,
            GravitySpec::TwoPointMass(f) => field_values(f, &r, potential)?,
            GravitySpec::Harmonic2(f) => field_values(f, &r, potential)?,
        };
        Ok((v, r.len()))
    };
    let (v, n) = run().map_err(|e| to_pyerr(py, e.context("gravity")))?;
    let arr = PyArray1::from_vec(py, v);
    if potential {
        Ok(arr.into_any())
    } else {
        Ok(arr.reshape([n, 3])?.into_any())
    }
}

/// Validates a gravity table.
#[pyfunction]
pub fn check_gravity(py: Python<'_>, owner: &str, table: Bound<'_, PyDict>) -> PyResult<()> {
    let mut p = Params::new(owner, PyDict::new(py), None);
    parse_gravity_into(table, &mut p)
        .map(|_| ())
        .map_err(|e| to_pyerr(py, e.context(owner)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(evaluate_gravity, m)?)?;
    m.add_function(wrap_pyfunction!(check_gravity, m)?)?;
    m.add("GRAVITATIONAL_CONSTANT", G)?;
    m.add("GRAVITY_KINDS", KINDS.to_vec())?;
    Ok(())
}
