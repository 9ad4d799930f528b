//! Control laws (SPEC section 5).
//!
//! A law reads the tracking errors and the plant's model at a control instant and returns a
//! commanded generalized acceleration `a`, meaning `q'' = drift + a + d` with `drift` the
//! plant's modelled acceleration and `d` the unknown disturbance. The plant's actuator turns
//! `a` into thrust, torque or control acceleration. Laws with internal states (integrators,
//! adaptive weights) keep them in their `Memory`, advanced once per control period by forward
//! Euler after the command is computed (SPEC 2).

mod fast_terminal;
mod fixed_time_mss;
mod fixed_time_ntsmc;
mod fuzzy_fast_terminal;
mod fuzzy_variable_rate;
mod integral_reaching;
mod ntsmc;
mod open_loop;
mod pd_sliding;
pub mod rbf;
mod super_twisting;

pub use fast_terminal::{FastTerminalSmc, TerminalSurface};
pub use fixed_time_mss::{FixedTimeMss, MssVariant};
pub use fixed_time_ntsmc::{FixedTimeNtsmc, zeta, zeta_slope};
pub use fuzzy_fast_terminal::FuzzyFastTerminalSmc;
pub use fuzzy_variable_rate::{FuzzyVariableRate, VariableRateMemory};
pub use integral_reaching::{IntegralExponentialReaching, IntegralSurface};
pub use ntsmc::Ntsmc;
pub use open_loop::OpenLoop;
pub use pd_sliding::PdSlidingMode;
pub use super_twisting::{SuperTwisting, SuperTwistingVariant};

use nalgebra::SVector;

use crate::error::{ParamError, require};
use crate::math::Switch;
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

    /// Names of scalar diagnostic signals (blending coefficients, distances), recorded after
    /// the D-vector ones.
    const SCALAR_DIAGNOSTICS: &'static [&'static str] = &[];

    fn start(&self, input: &LawInput<D>) -> Self::Memory;

    /// Commanded generalized acceleration at this instant.
    fn command(&self, memory: &Self::Memory, input: &LawInput<D>) -> SVector<f64, D>;

    /// Advance the memory over one control period (forward Euler with `input.dt`).
    #[inline(always)]
    fn advance(&self, _memory: &mut Self::Memory, _input: &LawInput<D>) {}

    /// Write `DIAGNOSTICS.len() * D + SCALAR_DIAGNOSTICS.len()` values into `out`, signal by
    /// signal (see [`diagnostic_width`]).
    fn diagnostics(&self, _memory: &Self::Memory, _input: &LawInput<D>, _out: &mut [f64]) {}

    fn validate(&self) -> Result<(), ParamError>;
}

/// Number of values a law's diagnostics take per recorded instant.
pub fn diagnostic_width<const D: usize, L: ControlLaw<D>>() -> usize {
    L::DIAGNOSTICS.len() * D + L::SCALAR_DIAGNOSTICS.len()
}

/// A switching function's boundary layer must be positive.
pub(crate) fn validate_switch(switch: &Switch) -> Result<(), ParamError> {
    match switch.width() {
        Some(phi) => require(phi > 0.0, "boundary_layer", phi, "boundary_layer > 0"),
        None => Ok(()),
    }
}
