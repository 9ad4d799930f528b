//! Batch output to numpy arrays (no copies beyond handing the buffers over).

use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::BatchOutput;

fn array1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

pub fn array2<'py>(
    py: Python<'py>,
    v: Vec<f64>,
    a: usize,
    b: usize,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(array1(py, v).reshape([a, b])?.into_any())
}

fn array3<'py>(
    py: Python<'py>,
    v: Vec<f64>,
    a: usize,
    b: usize,
    c: usize,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(array1(py, v).reshape([a, b, c])?.into_any())
}

/// A batch's output and the names that go with it.
pub struct Parts<const D: usize> {
    pub out: BatchOutput<D>,
    pub state_names: &'static [&'static str],
    pub control_names: &'static [&'static str],
    pub layout: Vec<(&'static str, usize)>,
}

pub fn to_dict<'py, const D: usize>(
    py: Python<'py>,
    parts: Parts<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let out = parts.out;
    let n = out.n_cases;
    let nr = out.n_records();
    let d = PyDict::new(py);
    let m = &out.metrics;
    let metrics = PyDict::new(py);
    let col = |f: &dyn Fn(usize) -> f64| (0..n).map(f).collect::<Vec<f64>>();
    let cols = |f: &dyn Fn(usize) -> [f64; D]| (0..n).flat_map(f).collect::<Vec<f64>>();
    let nan = f64::NAN;
    let td = |i: usize| m[i].touchdown;
    metrics.set_item(
        "final_position_error",
        array1(py, col(&|i| m[i].final_error.norm())),
    )?;
    metrics.set_item(
        "final_velocity_error",
        array1(py, col(&|i| m[i].final_rate_error.norm())),
    )?;
    metrics.set_item(
        "final_error",
        array2(py, cols(&|i| m[i].final_error.into()), n, D)?,
    )?;
    metrics.set_item(
        "final_rate_error",
        array2(py, cols(&|i| m[i].final_rate_error.into()), n, D)?,
    )?;
    metrics.set_item("fuel_used", array1(py, col(&|i| m[i].fuel_used)))?;
    metrics.set_item("fuel_to_settle", array1(py, col(&|i| m[i].fuel_to_settle)))?;
    metrics.set_item("peak_command", array1(py, col(&|i| m[i].peak_command)))?;
    metrics.set_item(
        "peak_command_axis",
        array2(py, cols(&|i| m[i].peak_command_axis.into()), n, D)?,
    )?;
    metrics.set_item("control_effort", array1(py, col(&|i| m[i].control_effort)))?;
    metrics.set_item("settle_time", array1(py, col(&|i| m[i].settle_time)))?;
    metrics.set_item("iae", array1(py, col(&|i| m[i].iae.sum())))?;
    metrics.set_item("iae_axis", array2(py, cols(&|i| m[i].iae.into()), n, D)?)?;
    metrics.set_item(
        "chattering_variation",
        array1(py, col(&|i| m[i].command_variation.sum())),
    )?;
    metrics.set_item(
        "chattering_variation_axis",
        array2(py, cols(&|i| m[i].command_variation.into()), n, D)?,
    )?;
    metrics.set_item(
        "chattering_hf_share",
        array1(py, col(&|i| m[i].high_frequency_share_total)),
    )?;
    metrics.set_item(
        "chattering_hf_share_axis",
        array2(py, cols(&|i| m[i].high_frequency_share.into()), n, D)?,
    )?;
    metrics.set_item(
        "touchdown_time",
        array1(py, col(&|i| td(i).map_or(nan, |t| t.time))),
    )?;
    metrics.set_item(
        "touchdown_position",
        array2(
            py,
            cols(&|i| td(i).map_or([nan; D], |t| t.position.into())),
            n,
            D,
        )?,
    )?;
    metrics.set_item(
        "touchdown_velocity",
        array2(
            py,
            cols(&|i| td(i).map_or([nan; D], |t| t.velocity.into())),
            n,
            D,
        )?,
    )?;
    metrics.set_item(
        "touchdown_speed",
        array1(py, col(&|i| td(i).map_or(nan, |t| t.velocity.norm()))),
    )?;
    let diverged: Vec<bool> = m.iter().map(|c| c.diverged.is_some()).collect();
    metrics.set_item("diverged", PyArray1::from_vec(py, diverged))?;
    metrics.set_item(
        "diverged_time",
        array1(py, col(&|i| m[i].diverged.map_or(nan, |d| d.time))),
    )?;
    // the codes of landing_core::metrics::Divergence (0: not diverged); the names are
    // `_core.DIVERGENCE_REASONS`
    let reasons: Vec<u8> = m
        .iter()
        .map(|c| c.diverged.map_or(0, |d| d.reason.code()))
        .collect();
    metrics.set_item("diverged_reason", PyArray1::from_vec(py, reasons))?;

    d.set_item("t", array1(py, out.times))?;
    d.set_item("states", array3(py, out.states, n, nr, out.state_dim)?)?;
    d.set_item("controls", array3(py, out.controls, n, nr, D)?)?;
    d.set_item(
        "diagnostics",
        array3(py, out.diagnostics, n, nr, out.diagnostic_dim)?,
    )?;
    d.set_item(
        "final_state",
        array2(py, out.final_state, n, out.state_dim)?,
    )?;
    d.set_item("metrics", metrics)?;
    d.set_item("state_names", parts.state_names.to_vec())?;
    d.set_item("control_names", parts.control_names.to_vec())?;
    d.set_item("diagnostic_layout", parts.layout)?;
    d.set_item("axes", D)?;
    d.set_item("kernel", out.level.name())?;
    Ok(d)
}
