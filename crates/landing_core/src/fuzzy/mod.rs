//! Fuzzy logic: membership functions and a general Mamdani inference engine.

mod mamdani;
mod membership;

pub use mamdani::{
    MAX_INPUTS, MAX_OUTPUT_SETS, Mamdani, Rule, Variable, even_triangles, variable_rate_system,
};
pub use membership::Membership;
