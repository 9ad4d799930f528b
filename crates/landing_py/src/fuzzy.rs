//! Fuzzy inference systems: `{"inputs": [var, ...], "output": var, "rules": [[set indices...,
//! output set], ...], "resolution": n}`, each variable `{"lo": .., "hi": .., "sets":
//! [["triangle", a, b, c] | ["trapezoid", a, b, c, d], ...]}`, compiled once into a handle.

use std::sync::Arc;

use numpy::{PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::fuzzy::{Mamdani, Membership, Rule, Variable, variable_rate_system};
use landing_core::limits::MAX_FUZZY_RESOLUTION;

use crate::errors::{InputError, guard, within_cap};

fn item<'py, T: for<'a> FromPyObject<'a, 'py>>(
    d: &Bound<'py, PyDict>,
    key: &str,
    what: &str,
) -> Result<T, InputError> {
    d.get_item(key)?
        .ok_or_else(|| InputError::type_(format!("{what} has no '{key}'")))?
        .extract::<T>()
        .map_err(|_| InputError::type_(format!("{what}: '{key}' has the wrong type")))
}

fn variable(d: &Bound<'_, PyDict>, what: &str) -> Result<Variable, InputError> {
    let lo: f64 = item(d, "lo", what)?;
    let hi: f64 = item(d, "hi", what)?;
    let raw: Vec<(String, Vec<f64>)> = item(d, "sets", what)?;
    let mut sets = Vec::with_capacity(raw.len());
    for (kind, p) in raw {
        sets.push(match (kind.as_str(), p.as_slice()) {
            ("triangle", [a, b, c]) => Membership::Triangle(*a, *b, *c),
            ("trapezoid", [a, b, c, d]) => Membership::Trapezoid(*a, *b, *c, *d),
            _ => {
                return Err(InputError::value(format!(
                    "{what}: a set is ('triangle', a, b, c) or ('trapezoid', a, b, c, d), got ({kind:?}, {p:?})"
                )));
            }
        });
    }
    // checked here too (Mamdani::new checks them again) so that the error names the variable
    // and the set, not only the set's shape
    for (j, set) in sets.iter().enumerate() {
        set.validate().map_err(|e| {
            InputError::value(format!(
                "{what}: sets[{j}] {} = {} violates {}",
                e.param, e.value, e.rule
            ))
        })?;
    }
    Ok(Variable { lo, hi, sets })
}

/// Builds and validates a Mamdani system from its table.
fn parse(table: &Bound<'_, PyDict>) -> Result<Mamdani, InputError> {
    let inputs: Vec<Bound<'_, PyDict>> = item(table, "inputs", "fuzzy system")?;
    let inputs = inputs
        .iter()
        .enumerate()
        .map(|(i, d)| variable(d, &format!("input {i}")))
        .collect::<Result<Vec<_>, _>>()?;
    let output: Bound<'_, PyDict> = item(table, "output", "fuzzy system")?;
    let output = variable(&output, "output")?;
    let raw: Vec<Vec<usize>> = item(table, "rules", "fuzzy system")?;
    let rules = raw
        .into_iter()
        .map(|mut r| {
            let consequent = r.pop().unwrap_or(usize::MAX);
            Rule {
                antecedent: r,
                consequent,
            }
        })
        .collect();
    let resolution: usize = item(table, "resolution", "fuzzy system")?;
    Ok(Mamdani::new(inputs, output, rules, resolution)?)
}

/// A compiled Mamdani system (`landing.fuzzy.Mamdani` holds one).
#[pyclass(frozen, module = "landing._core")]
pub struct FuzzySystem {
    pub system: Arc<Mamdani>,
}

#[pymethods]
impl FuzzySystem {
    #[new]
    fn new(table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let system = parse(table).map_err(|e| e.context("fuzzy system"))?;
            Ok(Self {
                system: Arc::new(system),
            })
        })
    }

    /// Crisp outputs for inputs of shape (N, number of inputs).
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        inputs: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        guard(|| {
            let shape = inputs.shape();
            if shape[1] != self.system.n_inputs() {
                return Err(InputError::value(format!(
                    "inputs has {} columns; the system takes {}",
                    shape[1],
                    self.system.n_inputs()
                ))
                .into());
            }
            let x = inputs.as_array();
            if let Some(((i, j), v)) = x.indexed_iter().find(|(_, v)| !v.is_finite()) {
                return Err(InputError::value(format!(
                    "inputs[{i}, {j}] = {v} violates finite values"
                ))
                .into());
            }
            let rows: Vec<Vec<f64>> = x
                .outer_iter()
                .map(|r| r.iter().copied().collect())
                .collect();
            let system = self.system.clone();
            let out: Vec<f64> =
                py.detach(move || rows.iter().map(|r| system.evaluate::<f64>(r)).collect());
            Ok(PyArray1::from_vec(py, out))
        })
    }
}

fn variable_table<'py>(py: Python<'py>, v: &Variable) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("lo", v.lo)?;
    d.set_item("hi", v.hi)?;
    let sets: Vec<(String, Vec<f64>)> = v
        .sets
        .iter()
        .map(|s| match *s {
            Membership::Triangle(a, b, c) => ("triangle".to_string(), vec![a, b, c]),
            Membership::Trapezoid(a, b, c, d) => ("trapezoid".to_string(), vec![a, b, c, d]),
        })
        .collect();
    d.set_item("sets", sets)?;
    Ok(d)
}

/// The table of the seed-002 variable-rate system, as the core defines it.
#[pyfunction]
pub fn variable_rate_system_table(
    py: Python<'_>,
    resolution: usize,
) -> PyResult<Bound<'_, PyDict>> {
    guard(|| variable_rate_system_table_unguarded(py, resolution))
}

fn variable_rate_system_table_unguarded(
    py: Python<'_>,
    resolution: usize,
) -> PyResult<Bound<'_, PyDict>> {
    if resolution < 2 {
        return Err(InputError::value(format!(
            "resolution = {resolution} violates resolution >= 2"
        ))
        .into());
    }
    within_cap(
        "resolution",
        resolution as u64,
        "max_fuzzy_resolution",
        MAX_FUZZY_RESOLUTION,
    )?;
    let m = variable_rate_system(resolution);
    let d = PyDict::new(py);
    let inputs = m
        .inputs()
        .iter()
        .map(|v| variable_table(py, v))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("inputs", inputs)?;
    d.set_item("output", variable_table(py, m.output())?)?;
    let rules: Vec<Vec<usize>> = m
        .rules()
        .iter()
        .map(|r| {
            r.antecedent
                .iter()
                .copied()
                .chain(std::iter::once(r.consequent))
                .collect()
        })
        .collect();
    d.set_item("rules", rules)?;
    d.set_item("resolution", m.resolution())?;
    Ok(d)
}
