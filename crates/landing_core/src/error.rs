//! Parameter validation errors. The core never panics on bad parameters: every constructor
//! a caller can reach has a `validate` that names the parameter, its value and the rule.

use std::fmt;

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
