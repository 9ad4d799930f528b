//! Errors at the boundary. The exception classes live in `landing.errors` (Python), so that
//! one base class, `LandingError`, can sit under both ValueError and TypeError; they are looked
//! up when an error is raised.

use pyo3::exceptions::{PyRuntimeError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyType;

use landing_core::{BatchError, ParamError};

/// An input problem found while reading arguments.
#[derive(Debug)]
pub enum InputError {
    /// Wrong shape or length (ValueError).
    Shape(String),
    /// Value outside the rule (ValueError).
    Value(String),
    /// Wrong type (TypeError).
    Type(String),
    /// A Python error raised on the way (passed through).
    Py(PyErr),
}

impl InputError {
    pub fn is_shape(&self) -> bool {
        matches!(self, Self::Shape(_))
    }

    /// Prefix the message with where the input came from.
    pub fn context(self, owner: &str) -> Self {
        match self {
            Self::Shape(m) => Self::Shape(format!("{owner}: {m}")),
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

/// Formats a core validation error for a parameter, with the case index when per case.
pub fn param_error(e: &ParamError, case: Option<usize>) -> InputError {
    let mut where_ = Vec::new();
    if let Some(a) = e.axis {
        where_.push(format!("axis {a}"));
    }
    if let Some(c) = case {
        where_.push(format!("case {c}"));
    }
    let at = if where_.is_empty() {
        String::new()
    } else {
        format!(" ({})", where_.join(", "))
    };
    InputError::Value(format!(
        "{} = {} violates {}{}",
        e.param, e.value, e.rule, at
    ))
}

fn landing_error<'py>(py: Python<'py>, name: &str) -> Option<Bound<'py, PyType>> {
    let module = py.import("landing.errors").ok()?;
    module.getattr(name).ok()?.cast_into::<PyType>().ok()
}

fn raise(py: Python<'_>, class: &str, fallback: fn(String) -> PyErr, msg: String) -> PyErr {
    match landing_error(py, class) {
        Some(ty) => PyErr::from_type(ty, msg),
        None => fallback(msg),
    }
}

pub fn to_pyerr(py: Python<'_>, e: InputError) -> PyErr {
    match e {
        InputError::Shape(m) | InputError::Value(m) => {
            raise(py, "ParameterError", PyValueError::new_err::<String>, m)
        }
        InputError::Type(m) => raise(py, "ParameterTypeError", PyTypeError::new_err::<String>, m),
        InputError::Py(e) => e,
    }
}

pub fn batch_error(py: Python<'_>, e: BatchError) -> PyErr {
    match e {
        BatchError::Allocation { .. } => pyo3::exceptions::PyMemoryError::new_err(e.to_string()),
        BatchError::Length { .. } => raise(
            py,
            "ParameterError",
            PyValueError::new_err::<String>,
            e.to_string(),
        ),
        BatchError::ThreadPool(_) => raise(
            py,
            "SimulationError",
            PyRuntimeError::new_err::<String>,
            e.to_string(),
        ),
    }
}

pub fn internal_error(py: Python<'_>, what: String) -> PyErr {
    raise(
        py,
        "SimulationError",
        PyRuntimeError::new_err::<String>,
        format!("internal error in the simulation core ({what}); this is a bug, please report it"),
    )
}
