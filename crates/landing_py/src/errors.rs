//! Errors at the boundary, converted in one place.
//!
//! The exception classes live in `landing.errors` (Python), so that one base class,
//! `LandingError`, can sit under ValueError, TypeError and RuntimeError; pyo3 imports each
//! once, on first use (the package imports `landing.errors` before `_core`). Every binding
//! function returns `Result<_, InputError>` or `PyResult` and uses `?`.

use pyo3::exceptions::PyMemoryError;
use pyo3::prelude::*;

use landing_core::error::ReadError;
use landing_core::{BatchError, ParamError};

/// An input problem found while reading arguments.
#[derive(Debug)]
pub enum InputError {
    /// Wrong shape, length or value (ValueError).
    Value(String),
    /// Wrong type (TypeError).
    Type(String),
    /// A Python error raised on the way (passed through).
    Py(PyErr),
}

impl InputError {
    pub fn value(msg: impl Into<String>) -> Self {
        Self::Value(msg.into())
    }

    pub fn type_(msg: impl Into<String>) -> Self {
        Self::Type(msg.into())
    }

    /// Prefix the message with where the input came from.
    pub fn context(self, owner: &str) -> Self {
        match self {
            Self::Value(m) => Self::Value(format!("{owner}: {m}")),
            Self::Type(m) => Self::Type(format!("{owner}: {m}")),
            e @ Self::Py(_) => e,
        }
    }
}

impl From<PyErr> for InputError {
    fn from(e: PyErr) -> Self {
        Self::Py(e)
    }
}

/// A core validation error: "param = value violates rule (axis i)".
impl From<ParamError> for InputError {
    fn from(e: ParamError) -> Self {
        ReadError::from(e).into()
    }
}

impl From<ReadError> for InputError {
    fn from(e: ReadError) -> Self {
        match e {
            ReadError::Value(m) => Self::Value(m),
            ReadError::Type(m) => Self::Type(m),
        }
    }
}

/// Returns early with an [`InputError::Value`] (a `ParameterError`) of `format!(...)`, from a
/// function returning `PyResult` or `Result<_, InputError>`.
macro_rules! invalid {
    ($($message:tt)*) => {
        return Err($crate::errors::InputError::value(format!($($message)*)).into())
    };
}
pub(crate) use invalid;

pyo3::import_exception!(landing.errors, ParameterError);
pyo3::import_exception!(landing.errors, ParameterTypeError);
pyo3::import_exception!(landing.errors, SimulationError);

impl From<InputError> for PyErr {
    fn from(e: InputError) -> Self {
        match e {
            InputError::Value(m) => ParameterError::new_err(m),
            InputError::Type(m) => ParameterTypeError::new_err(m),
            InputError::Py(e) => e,
        }
    }
}

/// A batch that could not run.
pub fn batch_error(e: BatchError) -> PyErr {
    match e {
        BatchError::Allocation { .. } => PyMemoryError::new_err(e.to_string()),
        BatchError::Length { .. }
        | BatchError::Shape { .. }
        | BatchError::Level(_)
        | BatchError::Event(_)
        | BatchError::Lent { .. } => ParameterError::new_err(e.to_string()),
        BatchError::ThreadPool(_) | BatchError::Cancelled => {
            SimulationError::new_err(e.to_string())
        }
    }
}

/// A panic in the core, as an exception (never an abort).
pub fn internal_error(panic: Box<dyn std::any::Any + Send>) -> PyErr {
    let what = panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "panic".into());
    SimulationError::new_err(format!(
        "internal error in the simulation core ({what}); this is a bug, please report it"
    ))
}

/// Runs the body of a binding entry point (every `#[pyfunction]` and `#[pymethods]` item
/// goes through it), so that a panic left in the core arrives as `landing.errors.
/// SimulationError` (a `LandingError`, an Exception) rather than pyo3's `PanicException`,
/// a BaseException that `except Exception` does not catch. Inputs are validated before the
/// code that could panic on them; this is the net under that rule, not a substitute for it.
pub fn guard<T>(body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(body)) {
        Ok(result) => result,
        Err(panic) => Err(internal_error(panic)),
    }
}

/// An axis count other than the plants' (2 or 3).
pub fn axes_error(axes: usize) -> InputError {
    InputError::value(format!("axes = {axes} violates axes in (2, 3)"))
}
