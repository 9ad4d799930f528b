//! `landing_core`: spacecraft landing and attitude control under sliding-mode and fuzzy laws.
//!
//! Pure Rust, no Python. One trait per concept: [`gravity::GravityField`], [`plant::Plant`],
//! [`control::ControlLaw`], and the fixed-step integrators ([`integrator::IntegratorKind`]). A
//! batch is dispatched once on its plant's type ([`registry::AnyPlant::visit`]) to the block
//! rollout ([`rollout`]), compiled for that plant at each instruction-set level ([`kernel`]);
//! the law ([`control::AnyLaw`]) and the integrator are chosen at run time. The rollout runs on
//! fixed-size nalgebra types without heap allocation per step; [`batch::run`] runs the blocks on
//! rayon. The sampled-data semantics are those README.md states ("Semantics").

pub mod actuator;
pub mod batch;
pub mod control;
pub mod dispersion;
pub mod disturbance;
pub mod error;
pub mod event;
pub mod external;
pub mod fuzzy;
pub mod gravity;
pub mod integrator;
pub mod interrupt;
pub mod kernel;
pub mod lanes;
pub mod limits;
pub mod math;
pub mod memory;
pub mod metrics;
pub mod navigation;
mod parallel;
pub mod params;
pub mod plant;
pub mod reference;
pub mod registry;
pub mod rng;
pub mod rollout;
pub mod special;
pub mod state;
pub mod theory;
#[cfg(feature = "workloads")]
pub mod workloads;

pub use batch::{Batch, BatchError, BatchOutput, PerCase, RunOptions};
pub use error::ParamError;
pub use kernel::Level;
pub use metrics::{CaseMetrics, Touchdown};
pub use rollout::{SimConfig, Tolerance};
