//! Batch output to numpy arrays (no copies beyond handing the buffers over).

use numpy::ndarray::IntoDimension;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::BatchOutput;
use landing_core::error::ReadError;
use landing_core::metrics::{CaseMetrics, ColumnValues};
use landing_core::params::Values;

use crate::errors::InputError;

fn array1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

/// `v` as an array of `shape` (C order), handed over without a copy.
pub fn shaped<'py, Sh: IntoDimension>(
    py: Python<'py>,
    v: Vec<f64>,
    shape: Sh,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(array1(py, v).reshape(shape)?.into_any())
}

/// A batch's output and the names that go with it.
pub struct Parts<'py, const D: usize> {
    pub out: BatchOutput<D>,
    pub state_names: &'static [&'static str],
    pub control_names: &'static [&'static str],
    pub layout: Vec<(String, usize)>,
    /// The arrays the recording was written into, when the caller lent them: the output's
    /// states, controls and diagnostics.
    pub lent: Option<[Bound<'py, PyAny>; 3]>,
}

/// The metric columns of `out`, one array per column of [`CaseMetrics::COLUMNS`]: (N,) or
/// (N, D), float64 except the flag (bool) and the reason code (uint8).
fn metrics<'py, const D: usize>(
    py: Python<'py>,
    out: &BatchOutput<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let n = out.n_cases;
    let d = PyDict::new(py);
    for col in CaseMetrics::<D>::COLUMNS {
        let values = match col.values(&out.metrics) {
            ColumnValues::Scalar(v) => array1(py, v).into_any(),
            ColumnValues::Axes(v) => shaped(py, v, [n, D])?,
            ColumnValues::Flag(v) => PyArray1::from_vec(py, v).into_any(),
            ColumnValues::Code(v) => PyArray1::from_vec(py, v).into_any(),
        };
        d.set_item(col.name, values)?;
    }
    Ok(d)
}

/// A handle's numeric parameter as the core reads it (`values`, read by the handle's owner):
/// (cases, axes) per axis, (cases,) for a scalar (cases = 1 when shared).
pub fn parameter<'py>(
    py: Python<'py>,
    values: Result<Values, ReadError>,
    owner: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let v = values.map_err(|e| InputError::from(e).context(owner))?;
    if v.per_axis {
        shaped(py, v.data, [v.cases, v.width])
    } else {
        Ok(array1(py, v.data).into_any())
    }
}

pub fn to_dict<'py, const D: usize>(
    py: Python<'py>,
    parts: Parts<'py, D>,
) -> PyResult<Bound<'py, PyDict>> {
    let out = parts.out;
    let n = out.n_cases;
    let nr = out.n_records();
    let d = PyDict::new(py);
    let metrics = metrics(py, &out)?;
    d.set_item("t", array1(py, out.times))?;
    let [states, controls, diagnostics] = match parts.lent {
        Some(lent) => lent,
        None => [
            shaped(py, out.states, [n, nr, out.state_dim])?,
            shaped(py, out.controls, [n, nr, D])?,
            shaped(py, out.diagnostics, [n, nr, out.diagnostic_dim])?,
        ],
    };
    d.set_item("states", states)?;
    d.set_item("controls", controls)?;
    d.set_item("diagnostics", diagnostics)?;
    d.set_item(
        "final_state",
        shaped(py, out.final_state, [n, out.state_dim])?,
    )?;
    d.set_item("metrics", metrics)?;
    d.set_item("state_names", parts.state_names.to_vec())?;
    d.set_item("control_names", parts.control_names.to_vec())?;
    d.set_item("diagnostic_layout", parts.layout)?;
    d.set_item("axes", D)?;
    d.set_item("kernel", out.level.name())?;
    Ok(d)
}
