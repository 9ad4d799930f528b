//! Reference and disturbance handles: tables compiled once for 3 and 2 axes.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::disturbance::Disturbance as CoreDisturbance;
use landing_core::error::Validate;
use landing_core::params::FromParams;
use landing_core::reference::Reference as CoreReference;

use crate::compiled::{ByAxes, ReadFor};
use crate::errors::{InputError, guard};
use crate::output;
use crate::table::{Reader, Table, Value};

/// Reads a model and validates it.
fn read_valid<T: FromParams + Validate>(p: &mut Reader<'_>) -> Result<T, InputError> {
    let v = T::from_params(p)?;
    v.validate()?;
    Ok(v)
}

struct References;

impl ReadFor for References {
    type At<const D: usize> = CoreReference<D>;
    fn read<const D: usize>(p: &mut Reader<'_>) -> Result<CoreReference<D>, InputError> {
        read_valid(p)
    }
}

struct Disturbances;

impl ReadFor for Disturbances {
    type At<const D: usize> = CoreDisturbance<D>;
    fn read<const D: usize>(p: &mut Reader<'_>) -> Result<CoreDisturbance<D>, InputError> {
        read_valid(p)
    }
}

/// A compiled reference (`landing.reference.Reference` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct Reference {
    pub compiled: ByAxes,
}

#[pymethods]
impl Reference {
    #[new]
    fn new(owner: &str, table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = Table::from_py(table).map_err(|e| e.context(owner))?;
            Ok(Self {
                compiled: ByAxes::compile::<References>(owner, &t, false)?,
            })
        })
    }

    /// Position, velocity and acceleration at times `t`, each (T, axes).
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        axes: usize,
        t: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        guard(|| self.evaluate_unguarded(py, axes, t))
    }
}

impl Reference {
    fn evaluate_unguarded<'py>(
        &self,
        py: Python<'py>,
        axes: usize,
        t: Vec<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        if let Some((i, v)) = t.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(InputError::value(format!("t[{i}] = {v} violates finite values")).into());
        }
        fn eval<const D: usize>(c: &ByAxes, t: &[f64]) -> Result<[Vec<f64>; 3], InputError> {
            let (refs, _) = c.get::<CoreReference<D>, D>()?;
            if !refs.is_shared() {
                return Err(InputError::value(
                    "evaluate() needs a reference shared by all cases",
                ));
            }
            let r = refs.get(0);
            let mut out = [
                Vec::with_capacity(t.len() * D),
                Vec::with_capacity(t.len() * D),
                Vec::with_capacity(t.len() * D),
            ];
            for (i, &ti) in t.iter().enumerate() {
                let pt = r.at(ti);
                let values = [&pt.position, &pt.velocity, &pt.acceleration];
                if values.iter().any(|v| v.iter().any(|x| !x.is_finite())) {
                    // a cubic far before 0 overflows
                    return Err(InputError::value(format!(
                        "t[{i}] = {ti} violates times at which the reference is finite"
                    )));
                }
                out[0].extend_from_slice(pt.position.as_slice());
                out[1].extend_from_slice(pt.velocity.as_slice());
                out[2].extend_from_slice(pt.acceleration.as_slice());
            }
            Ok(out)
        }
        let values = match axes {
            3 => eval::<3>(&self.compiled, &t)?,
            2 => eval::<2>(&self.compiled, &t)?,
            _ => {
                return Err(
                    InputError::value(format!("axes = {axes} violates axes in (2, 3)")).into(),
                );
            }
        };
        let d = PyDict::new(py);
        for (name, v) in ["position", "velocity", "acceleration"]
            .into_iter()
            .zip(values)
        {
            d.set_item(name, output::array2(py, v, t.len(), axes)?)?;
        }
        Ok(d)
    }
}

/// A compiled disturbance (`landing.disturbances.Disturbance` holds one): the sum of its
/// components.
#[pyclass(frozen, module = "landing._core")]
pub struct Disturbance {
    /// The components' tables, kept to build sums.
    components: Vec<Table>,
    pub compiled: ByAxes,
}

impl Disturbance {
    fn from_components(owner: &str, components: Vec<Table>) -> Result<Self, InputError> {
        let table = Table::with_list("components", components.clone());
        Ok(Self {
            compiled: ByAxes::compile::<Disturbances>(owner, &table, false)?,
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
            let t = Table::from_py(table).map_err(|e| e.context(owner))?;
            let components = match t.entry("components") {
                Some(Value::List(items)) => items.clone(),
                _ => {
                    return Err(InputError::type_(format!(
                        "{owner}: a disturbance table has a list 'components'"
                    ))
                    .into());
                }
            };
            Ok(Self::from_components(owner, components)?)
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
        guard(|| self.bound_unguarded(axes))
    }
}

impl Disturbance {
    fn bound_unguarded(&self, axes: usize) -> PyResult<Vec<f64>> {
        fn b<const D: usize>(c: &ByAxes) -> Result<Vec<f64>, InputError> {
            let (d, _) = c.get::<CoreDisturbance<D>, D>()?;
            if !d.is_shared() {
                return Err(InputError::value(
                    "the bound needs a disturbance shared by all cases",
                ));
            }
            Ok(d.get(0).bound().as_slice().to_vec())
        }
        Ok(match axes {
            3 => b::<3>(&self.compiled)?,
            2 => b::<2>(&self.compiled)?,
            _ => {
                return Err(
                    InputError::value(format!("axes = {axes} violates axes in (2, 3)")).into(),
                );
            }
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
) -> PyResult<Vec<Vec<f64>>> {
    guard(|| cubic_from_boundary_unguarded(p0, v0, pt, vt, t_end))
}

fn cubic_from_boundary_unguarded(
    p0: Vec<f64>,
    v0: Vec<f64>,
    pt: Vec<f64>,
    vt: Vec<f64>,
    t_end: f64,
) -> PyResult<Vec<Vec<f64>>> {
    fn fit<const D: usize>(v: [&[f64]; 4], t_end: f64) -> Result<Vec<Vec<f64>>, InputError> {
        let s = v.map(nalgebra::SVector::<f64, D>::from_column_slice);
        match CoreReference::cubic_from_boundary(s[0], s[1], s[2], s[3], t_end)? {
            CoreReference::Cubic { coefficients, .. } => {
                Ok(coefficients.iter().map(|c| c.as_slice().to_vec()).collect())
            }
            CoreReference::Constant { .. } => unreachable!("cubic_from_boundary builds a cubic"),
        }
    }
    for (name, v) in [("p0", &p0), ("v0", &v0), ("pT", &pt), ("vT", &vt)] {
        if let Some((i, x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            return Err(
                InputError::value(format!("{name}[{i}] = {x} violates finite values")).into(),
            );
        }
    }
    let d = p0.len();
    for (name, v) in [("v0", &v0), ("pT", &pt), ("vT", &vt)] {
        if v.len() != d {
            return Err(
                InputError::value(format!("{name} has {} axes, p0 has {d}", v.len())).into(),
            );
        }
    }
    let all = [p0.as_slice(), v0.as_slice(), pt.as_slice(), vt.as_slice()];
    Ok(match d {
        3 => fit::<3>(all, t_end)?,
        2 => fit::<2>(all, t_end)?,
        _ => {
            return Err(InputError::value(format!("p0 has {d} axes; 2 or 3 are supported")).into());
        }
    })
}
