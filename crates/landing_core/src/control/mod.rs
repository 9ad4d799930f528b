//! Control laws (SPEC section 5).
//!
//! A law reads the tracking errors and the plant's model at a control instant and returns a
//! commanded generalized acceleration `a`, meaning `q'' = drift + a + d` with `drift` the
//! plant's modelled acceleration and `d` the unknown disturbance. The plant's actuator turns
//! `a` into thrust, torque or control acceleration. Laws with internal states (integrators,
//! adaptive weights) keep them in their `Memory`, advanced once per control period by forward
//! Euler after the command is computed (SPEC 2).

mod fixed_time_mss;
mod fixed_time_ntsmc;
mod ntsmc;
mod open_loop;
pub mod rbf;
mod super_twisting;

pub use fixed_time_mss::{FixedTimeMss, MssVariant};
pub use fixed_time_ntsmc::{FixedTimeNtsmc, zeta, zeta_slope};
pub use ntsmc::Ntsmc;
pub use open_loop::OpenLoop;
pub use super_twisting::{SuperTwisting, SuperTwistingVariant};

use nalgebra::SVector;

use crate::error::ParamError;
use crate::reference::RefPoint;

/// What a law sees at a control instant.
#[derive(Clone, Copy, Debug)]
pub struct LawInput<const D: usize> {
    pub t: f64,
    /// Control period.
    pub dt: f64,
    /// Tracking error `e = q - q_ref`.
    pub e: SVector<f64, D>,
    /// Rate error `e' = q' - q_ref'`.
    pub de: SVector<f64, D>,
    pub reference: RefPoint<D>,
    /// The plant's modelled acceleration (see `Plant::modelled_acceleration`).
    pub drift: SVector<f64, D>,
    /// The plant's diagonal inertia (see `Plant::inertia`).
    pub inertia: SVector<f64, D>,
}

pub trait ControlLaw<const D: usize>: Send + Sync {
    /// Internal state carried from one control period to the next.
    type Memory: Copy + Send + Sync;

    /// Names of the law's diagnostic signals (sliding variables, adaptive terms), each a
    /// D-vector, recorded alongside the states.
    const DIAGNOSTICS: &'static [&'static str];

    fn start(&self, input: &LawInput<D>) -> Self::Memory;

    /// Commanded generalized acceleration at this instant.
    fn command(&self, memory: &Self::Memory, input: &LawInput<D>) -> SVector<f64, D>;

    /// Advance the memory over one control period (forward Euler with `input.dt`).
    #[inline(always)]
    fn advance(&self, _memory: &mut Self::Memory, _input: &LawInput<D>) {}

    /// Write `DIAGNOSTICS.len() * D` values into `out`, signal by signal.
    fn diagnostics(&self, _memory: &Self::Memory, _input: &LawInput<D>, _out: &mut [f64]) {}

    fn validate(&self) -> Result<(), ParamError>;
}
