//! Parameter validation errors. The core never panics on bad parameters: every constructor
//! a caller can reach has a `validate` that names the parameter, its value and the rule.

use std::fmt;

use crate::params::schema::Param;

#[derive(Clone, Debug, PartialEq)]
pub struct ParamError {
    /// Parameter name as the user spells it (the Python keyword).
    pub param: &'static str,
    pub value: f64,
    /// The rule, written as an inequality over the parameter, e.g. `"0 < q1 < 1"`.
    pub rule: &'static str,
    /// Axis the value belongs to, for per-axis parameters.
    pub axis: Option<usize>,
}

impl ParamError {
    pub fn new(param: &'static str, value: f64, rule: &'static str) -> Self {
        Self {
            param,
            value,
            rule,
            axis: None,
        }
    }

    pub fn on_axis(mut self, axis: usize) -> Self {
        self.axis = Some(axis);
        self
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {} violates {}", self.param, self.value, self.rule)?;
        if let Some(a) = self.axis {
            write!(f, " (axis {a})")?;
        }
        Ok(())
    }
}

impl std::error::Error for ParamError {}

/// Checks a predicate on a value and produces the error. Keeps validators one line per rule.
#[inline]
pub fn require(
    ok: bool,
    param: &'static str,
    value: f64,
    rule: &'static str,
) -> Result<(), ParamError> {
    if ok && value.is_finite() {
        Ok(())
    } else if !value.is_finite() {
        Err(ParamError::new(param, value, "finite values"))
    } else {
        Err(ParamError::new(param, value, rule))
    }
}

/// `require` for the parameter `p`, under its declared name and rule.
#[inline]
pub fn check(p: &Param, value: f64, ok: impl Fn(f64) -> bool) -> Result<(), ParamError> {
    require(ok(value), p.name, value, p.rule)
}

/// `require` for the parameter `p`, under its declared name and second rule ([`Param::also`]).
#[inline]
pub fn check_also(p: &Param, value: f64, ok: bool) -> Result<(), ParamError> {
    require(ok, p.name, value, p.also)
}

/// [`check`] for each axis of a per-axis parameter.
pub fn check_axes(p: &Param, values: &[f64], ok: impl Fn(f64) -> bool) -> Result<(), ParamError> {
    require_axes(values, p.name, p.rule, ok)
}

/// `require` for each axis of a per-axis parameter.
pub fn require_axes(
    values: &[f64],
    param: &'static str,
    rule: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), ParamError> {
    for (i, &v) in values.iter().enumerate() {
        require(ok(v), param, v, rule).map_err(|e| e.on_axis(i))?;
    }
    Ok(())
}

/// The rules a configured model (one case's `f64` parameters) must satisfy: plants, laws,
/// gravity fields, references, disturbances. The core never panics on bad parameters; a batch
/// validates every case before it runs.
pub trait Validate {
    fn validate(&self) -> Result<(), ParamError>;
}

/// A table that cannot be read: a missing, misspelt or misshapen parameter (`Type`: a wrong
/// type, as Python's TypeError; `Value`: a wrong value or shape, as ValueError). A
/// [`ParamError`] from a validator arrives as a `Value`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ReadError {
    Value(String),
    Type(String),
}

impl ReadError {
    pub fn value(msg: impl Into<String>) -> Self {
        Self::Value(msg.into())
    }

    pub fn type_(msg: impl Into<String>) -> Self {
        Self::Type(msg.into())
    }

    /// The message prefixed with where the table came from.
    pub fn context(self, owner: &str) -> Self {
        match self {
            Self::Value(m) => Self::Value(format!("{owner}: {m}")),
            Self::Type(m) => Self::Type(format!("{owner}: {m}")),
        }
    }

    pub fn message(&self) -> &str {
        match self {
            Self::Value(m) | Self::Type(m) => m,
        }
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.message())
    }
}

impl std::error::Error for ReadError {}

impl From<ParamError> for ReadError {
    fn from(e: ParamError) -> Self {
        Self::Value(e.to_string())
    }
}

/// Refuses the first non-finite value of `values` by its position: `name[i] = v violates
/// finite values`.
pub fn finite(name: &str, values: &[f64]) -> Result<(), ReadError> {
    match values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        Some((i, v)) => Err(ReadError::value(format!(
            "{name}[{i}] = {v} violates finite values"
        ))),
        None => Ok(()),
    }
}
