//! Plants: the dynamics a rollout integrates and the model a law may use.
//!
//! Every plant is a fully actuated mechanical system in D generalized coordinates q (position
//! for the landers, angles for the tethered satellite). Laws compute a generalized-acceleration
//! command from the tracking errors and the plant's modelled drift; the plant's actuator turns
//! it into the applied command (thrust, control acceleration, torque) and saturates it.

mod double_integrator;
mod mars;
mod small_body;
pub mod tether;

pub use double_integrator::DoubleIntegrator;
pub use mars::MarsLander;
pub use small_body::SmallBody;
pub use tether::{TetheredFlexible, TetheredSimplified};

use nalgebra::SVector;

use crate::error::{ParamError, require};
use crate::state::State;

pub trait Plant<const D: usize>: Send + Sync {
    type State: State;

    /// Names of the state components, for tables and plots.
    const STATE_NAMES: &'static [&'static str];
    /// Names of the applied-command components.
    const CONTROL_NAMES: &'static [&'static str];

    /// Generalized coordinates and their rates, as the law reads them.
    fn coordinates(&self, x: &Self::State) -> (SVector<f64, D>, SVector<f64, D>);

    /// The part of q'' the controller may model (gravity, modelled drag, frame terms), without
    /// the command and without the unknown disturbance. Equivalent controls cancel it.
    fn modelled_acceleration(&self, t: f64, x: &Self::State) -> SVector<f64, D>;

    /// Diagonal inertia seen by the command: q'' gains `u_i / inertia_i`. The mass for a
    /// lander commanded in force, 1 for a commanded acceleration.
    fn inertia(&self, x: &Self::State) -> SVector<f64, D>;

    /// The applied command for a commanded generalized acceleration: scaling to actuator units
    /// and saturation. Held over the control period.
    fn actuate(&self, x: &Self::State, acceleration: &SVector<f64, D>) -> SVector<f64, D>;

    /// `x'` under the held command `u` and the disturbance acceleration `d`.
    fn derivative(
        &self,
        t: f64,
        x: &Self::State,
        u: &SVector<f64, D>,
        d: &SVector<f64, D>,
    ) -> Self::State;

    /// Whether the model is defined at `x` (finite, positive mass, ...). A rollout stops and
    /// flags the case as diverged when it is not.
    fn admissible(&self, x: &Self::State) -> bool {
        x.all_finite()
    }

    /// Mass, for plants that burn propellant (fuel used = m0 - m(t_final)).
    fn mass(&self, _x: &Self::State) -> Option<f64> {
        None
    }

    /// Height above the landing surface, for plants that can touch down.
    fn altitude(&self, _x: &Self::State) -> Option<f64> {
        None
    }

    /// Checks an initial state; by default, that it is finite.
    fn check_initial(&self, x: &Self::State) -> Result<(), ParamError> {
        for (i, v) in x.as_slice().iter().enumerate() {
            require(v.is_finite(), "x0", *v, "finite values").map_err(|e| e.on_axis(i))?;
        }
        Ok(())
    }

    fn validate(&self) -> Result<(), ParamError>;
}
