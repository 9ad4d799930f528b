//! Plants: the dynamics a rollout integrates and the model a law may use.
//!
//! Every plant is a fully actuated mechanical system in D generalized coordinates q (position
//! for the landers, angles for the tethered satellite). Laws compute a generalized-acceleration
//! command from the tracking errors and the plant's modelled drift; the plant's actuator turns
//! it into the applied command (thrust, control acceleration, torque) and saturates it.
//!
//! A plant type is generic over its number type (see [`crate::lanes`]): `MarsLander` is one
//! case, `MarsLander<Lanes<W>>` a block of W cases advanced together, one lane per case.

mod double_integrator;
mod mars;
pub mod small_body;
pub mod tether;

pub use double_integrator::DoubleIntegrator;
pub use mars::MarsLander;
pub use small_body::SmallBody;
pub use tether::{TetheredFlexible, TetheredSimplified};

use nalgebra::SVector;

use crate::actuator::ActuatorSpec;
use crate::error::{ParamError, Validate, require};
use crate::lanes::{Gather, Mask, Real};
use crate::navigation::Navigation;
use crate::state::State;

/// The dynamics over lanes of cases.
pub trait Plant<R: Real, const D: usize>: Send + Sync {
    type State: State<R>;

    /// Generalized coordinates and their rates, as the law reads them.
    fn coordinates(&self, x: &Self::State) -> (SVector<R, D>, SVector<R, D>);

    /// The part of q'' the controller may model (gravity, modelled drag, frame terms), without
    /// the command and without the unknown disturbance. Equivalent controls cancel it.
    fn modelled_acceleration(&self, t: f64, x: &Self::State) -> SVector<R, D>;

    /// Diagonal inertia seen by the command: q'' gains `u_i / inertia_i`. The mass for a
    /// lander commanded in force, 1 for a commanded acceleration.
    fn inertia(&self, x: &Self::State) -> SVector<R, D>;

    /// The applied command for a commanded generalized acceleration: scaling to actuator units
    /// and saturation. Held over the control period.
    fn actuate(&self, x: &Self::State, acceleration: &SVector<R, D>) -> SVector<R, D>;

    /// The actuator's delay and lag ([`crate::actuator`]), for plants that model them; None
    /// (the command acts at once, as it is) by default and when no lane of the block has one.
    #[inline(always)]
    fn actuator(&self) -> Option<ActuatorSpec<R>> {
        None
    }

    /// The sensor and filter between the plant and the law ([`crate::navigation`]), for
    /// plants that carry one; None (the law reads the true state) by default.
    #[inline(always)]
    fn navigation(&self) -> Option<&Navigation<D, R>> {
        None
    }

    /// Diagnostic columns a run records beside the law's: with a sensor, the estimate the law
    /// read (q_hat, then q'_hat, D each).
    fn navigation_width(&self) -> usize {
        self.navigation().map_or(0, |_| 2 * D)
    }

    /// The actuator's limits imposed on a command in actuator units: what `actuate` applies
    /// after scaling, so that `actuate(x, a) == limit(scaled a)`. The lag's output passes it
    /// at every stage. No limits by default.
    #[inline(always)]
    fn limit(&self, u: &SVector<R, D>) -> SVector<R, D> {
        *u
    }

    /// `x'` under the held command `u` and the disturbance acceleration `d`.
    fn derivative(
        &self,
        t: f64,
        x: &Self::State,
        u: &SVector<R, D>,
        d: &SVector<R, D>,
    ) -> Self::State;

    /// `x'` at a control instant, where the law has just evaluated `drift`, the modelled
    /// acceleration at the same `(t, x)`: plants whose derivative contains it reuse it (the
    /// Mars lander's drag exponential is then computed once for the law and the first stage).
    /// With `drift = modelled_acceleration(t, x)` it must give `derivative`'s bits: the rollout
    /// calls it at every stage.
    #[inline(always)]
    fn derivative_with_drift(
        &self,
        t: f64,
        x: &Self::State,
        u: &SVector<R, D>,
        d: &SVector<R, D>,
        _drift: &SVector<R, D>,
    ) -> Self::State {
        self.derivative(t, x, u, d)
    }

    /// [`derivative_with_drift`](Self::derivative_with_drift) written into `dx`, with its bits:
    /// what the rollout calls at every stage. Plants with a large state override it to write
    /// in place (returned by value, the state was copied out at every stage).
    #[inline(always)]
    fn derivative_into(
        &self,
        t: f64,
        x: &Self::State,
        u: &SVector<R, D>,
        d: &SVector<R, D>,
        drift: &SVector<R, D>,
        dx: &mut Self::State,
    ) {
        *dx = self.derivative_with_drift(t, x, u, d, drift);
    }

    /// Whether the finite state `x` is in the model's documented domain (positive mass,
    /// within the plant's range, outside singularities), per lane; docs/parameters.md lists
    /// each plant's. A rollout stops a case and flags it `OutOfDomain` when it is not (a
    /// non-finite state is flagged `NonFiniteState` before this is asked). Every finite state
    /// by default.
    #[inline(always)]
    fn in_domain(&self, _x: &Self::State) -> R::Mask {
        R::Mask::splat(true)
    }

    /// Mass, for plants that burn propellant (fuel used = m0 - m(t_final)).
    #[inline(always)]
    fn mass(&self, _x: &Self::State) -> Option<R> {
        None
    }

    /// Number of state components recorded: the state's, unless the state type has room for
    /// more than the plant uses (a plant written in Python).
    #[inline(always)]
    fn state_dim(&self) -> usize {
        <Self::State as State<R>>::DIM
    }

    /// Height above the landing surface, for plants that can touch down.
    #[inline(always)]
    fn altitude(&self, _x: &Self::State) -> Option<R> {
        None
    }

    /// The axis whose coordinate is the altitude (`q[axis]`), when it is one: the touchdown
    /// is then located on the coordinates' interpolant ([`crate::event`]), else on the chord.
    #[inline(always)]
    fn altitude_axis(&self) -> Option<usize> {
        None
    }

    /// The state components of q and of q', axis by axis (where an event writes the state it
    /// froze a case in): q then q', the landers' layout, unless the plant says otherwise.
    #[inline(always)]
    fn coordinate_components(&self) -> ([usize; D], [usize; D]) {
        (std::array::from_fn(|i| i), std::array::from_fn(|i| D + i))
    }
}

/// A plant as configured: one case's `f64` parameters, its names and rules, and the same
/// plant over lanes ([`PlantModel::At`]).
pub trait PlantModel<const D: usize>:
    Plant<f64, D> + Validate + Clone + Send + Sync + 'static
{
    /// The plant over lanes of cases.
    type At<R: Real>: Plant<R, D> + Gather<R, Case = Self> + 'static;

    /// How wide its blocks are at each instruction-set level ([`crate::kernel::Wide`] or
    /// [`crate::kernel::Narrow`]): a performance choice, measured; the bits do not depend on
    /// it.
    type Blocks: crate::kernel::Blocks;

    /// Number of state components.
    const STATE_DIM: usize = <<Self as Plant<f64, D>>::State as State<f64>>::DIM;
    /// Names of the state components, for tables and plots.
    const STATE_NAMES: &'static [&'static str];
    /// Names of the applied-command components.
    const CONTROL_NAMES: &'static [&'static str];

    /// Derived figures of the model, for tables and documentation (e.g. the tethered
    /// satellite's inertia and orbital rate): names and values.
    fn figures(&self) -> Vec<(&'static str, Vec<f64>)> {
        Vec::new()
    }

    /// The largest stable RK4 step of the model's fastest mode, s (infinite unless stiff).
    fn max_step(&self) -> f64 {
        f64::INFINITY
    }

    /// The state at generalized coordinates `q` and rates `qd`, for plants whose state they
    /// determine (None for the others).
    fn state_at(
        &self,
        _q: &SVector<f64, D>,
        _qd: &SVector<f64, D>,
    ) -> Option<Result<Vec<f64>, ParamError>> {
        None
    }

    /// Checks an initial state; by default, that it is finite.
    fn check_initial(&self, x: &[f64]) -> Result<(), ParamError> {
        for (i, v) in x.iter().enumerate() {
            require(v.is_finite(), "x0", *v, "finite values").map_err(|e| e.on_axis(i))?;
        }
        Ok(())
    }
}
