//! `landing._core`: the thin pyo3 layer over `landing_core`.
//!
//! Python configuration objects compile their parameter tables once into handles ([`Plant`],
//! [`Law`], [`Reference`], [`Disturbance`], [`Gravity`], [`FuzzySystem`]) through the core's
//! registries; a batch takes the handles, copies the initial states and runs with the GIL
//! released. Nothing here holds simulation logic.

mod analysis;
mod callables;
mod errors;
mod fuzzy;
mod gravity;
mod laws;
mod output;
mod plants;
mod signals;
mod simulate;
mod table;

use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict, PyList};

use landing_core::control::LAW_KINDS;
use landing_core::gravity::G;
use landing_core::integrator::IntegratorKind;
use landing_core::kernel::Level;
use landing_core::limits::LIMITS;
use landing_core::metrics::{CaseMetrics, Divergence, MAX_COMMAND};
use landing_core::params::{Layout, Param, Shape};
use landing_core::registry::{GRAVITY_KINDS, PLANT_KINDS, schemas};

use errors::guard;
use fuzzy::FuzzySystem;
use gravity::Gravity;
use laws::Law;
use plants::Plant;
use signals::{Disturbance, Reference};

/// The instruction-set levels this CPU supports, lowest first.
#[pyfunction]
fn kernel_levels() -> PyResult<Vec<&'static str>> {
    guard(|| Ok(Level::supported().into_iter().map(Level::name).collect()))
}

/// Bytes a new allocation can count on, as the core measures them (None: the system says not).
#[pyfunction]
fn available_memory() -> PyResult<Option<u64>> {
    guard(|| Ok(landing_core::memory::available_bytes()))
}

/// The level a batch runs at unless told otherwise (`LANDING_KERNEL`, else the best).
#[pyfunction]
fn default_kernel() -> PyResult<&'static str> {
    guard(|| {
        Level::resolve(None)
            .map(Level::name)
            .map_err(|e| errors::InputError::value(e.to_string()).into())
    })
}

/// Test hook: panics inside a guarded entry point, so the tests can check that a panic in
/// the core arrives as a `LandingError` (not documented; not part of the API).
#[pyfunction]
fn _panic_for_test() -> PyResult<()> {
    guard(|| panic!("deliberate panic for the tests"))
}

/// A parameter's declaration: name, shape, unit, rule, required, per_case, doc, and its
/// choices or its nested tables' family (or fixed layout).
fn param<'py>(py: Python<'py>, p: &Param) -> PyResult<Bound<'py, PyDict>> {
    let texts = [
        ("name", p.name),
        ("shape", p.shape.name()),
        ("unit", p.unit),
        ("doc", p.doc),
    ];
    let d = texts.into_py_dict(py)?;
    d.set_item("rule", p.rules())?;
    d.set_item("required", p.required)?;
    d.set_item("per_case", p.varies_by_case())?;
    match p.shape {
        Shape::Choice(names) => d.set_item("choices", names.to_vec())?,
        Shape::Count(values) => d.set_item("choices", values.to_vec())?,
        Shape::Nested(layout) | Shape::List(layout) => match layout {
            Layout::Family(f) => d.set_item("family", f)?,
            Layout::Fixed(params) => {
                d.set_item("family", py.None())?;
                d.set_item("layout", params_list(py, params)?)?;
            }
        },
        _ => {}
    }
    Ok(d)
}

fn params_list<'py>(py: Python<'py>, params: &[Param]) -> PyResult<Bound<'py, PyList>> {
    let items = params
        .iter()
        .map(|p| param(py, p))
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// `SCHEMAS[family][kind]`: what each kind of model declares (see `_core.pyi`).
fn schema_table(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for (family, kinds) in schemas() {
        let f = PyDict::new(py);
        for (kind, schema) in kinds {
            let k = PyDict::new(py);
            k.set_item("parameters", params_list(py, schema.params)?)?;
            if let Some(random) = schema.random {
                k.set_item("random", random)?;
            }
            f.set_item(kind, k)?;
        }
        out.set_item(family, f)?;
    }
    Ok(out)
}

/// The per-case metric columns in output order (`CaseMetrics::COLUMNS`).
fn metric_list(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let items = CaseMetrics::<3>::COLUMNS
        .iter()
        .map(|c| {
            let d = [("name", c.name), ("unit", c.unit), ("doc", c.doc)].into_py_dict(py)?;
            d.set_item("per_axis", c.per_axis())?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Plant>()?;
    m.add_class::<Law>()?;
    m.add_class::<Reference>()?;
    m.add_class::<Disturbance>()?;
    m.add_class::<Gravity>()?;
    m.add_class::<FuzzySystem>()?;
    m.add_function(wrap_pyfunction!(simulate::simulate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(signals::cubic_from_boundary, m)?)?;
    m.add_function(wrap_pyfunction!(fuzzy::variable_rate_system_table, m)?)?;
    m.add_function(wrap_pyfunction!(kernel_levels, m)?)?;
    m.add_function(wrap_pyfunction!(default_kernel, m)?)?;
    m.add_function(wrap_pyfunction!(available_memory, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_test, m)?)?;
    analysis::register(m)?;
    m.add("INTEGRATORS", IntegratorKind::NAMES.to_vec())?;
    m.add("PLANT_KINDS", PLANT_KINDS.to_vec())?;
    m.add("CONTROLLER_KINDS", LAW_KINDS.to_vec())?;
    m.add("GRAVITY_KINDS", GRAVITY_KINDS.to_vec())?;
    m.add("KERNEL_LEVELS", Level::NAMES.to_vec())?;
    m.add("EVENTS", landing_core::event::Event::NAMES.to_vec())?;
    m.add("GRAVITATIONAL_CONSTANT", G)?;
    m.add("DIVERGENCE_REASONS", Divergence::NAMES.to_vec())?;
    m.add("MAX_COMMAND", MAX_COMMAND)?;
    m.add("LIMITS", LIMITS.into_py_dict(m.py())?)?;
    m.add("SCHEMAS", schema_table(m.py())?)?;
    m.add("METRICS", metric_list(m.py())?)?;
    Ok(())
}
