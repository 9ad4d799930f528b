//! Fuzzy logic: membership functions and a general Mamdani inference engine, read from a
//! table (`table.rs`).

mod mamdani;
mod membership;
mod table;

pub use mamdani::{
    MAX_INPUTS, MAX_OUTPUT_SETS, Mamdani, Rule, Variable, checked_variable_rate_system,
    even_triangles, variable_rate_system,
};
pub use membership::{Membership, MembershipShape, TRAPEZOID, TRIANGLE};
