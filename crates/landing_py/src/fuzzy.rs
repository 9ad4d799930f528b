//! Fuzzy inference systems: a Mamdani table (`landing_core::fuzzy`'s `table.rs` reads it)
//! compiled once into a handle.

use std::sync::Arc;

use numpy::{PyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::fuzzy::{Mamdani, Variable, checked_variable_rate_system};

use crate::errors::{InputError, guard};
use crate::table;

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
            let t = table::from_py("fuzzy system", table)?;
            let system = t
                .read_one::<Mamdani>()
                .map_err(|e| InputError::from(e).context("fuzzy system"))?;
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
            let (columns, system) = (inputs.shape()[1], self.system.clone());
            let rows: Vec<f64> = inputs.as_array().iter().copied().collect();
            let out = py.detach(move || system.evaluate_rows(&rows, columns));
            let out = out.map_err(InputError::from)?;
            Ok(PyArray1::from_vec(py, out))
        })
    }
}

fn variable_table<'py>(py: Python<'py>, v: &Variable) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("lo", v.lo)?;
    d.set_item("hi", v.hi)?;
    let sets: Vec<(&str, Vec<f64>)> = v
        .sets
        .iter()
        .map(|s| (s.shape().name(), s.corners()))
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
    guard(|| {
        let m = checked_variable_rate_system(resolution).map_err(InputError::from)?;
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
                let mut sets = r.antecedent.clone();
                sets.push(r.consequent);
                sets
            })
            .collect();
        d.set_item("rules", rules)?;
        d.set_item("resolution", m.resolution())?;
        Ok(d)
    })
}
