//! A block of cases in lockstep, sampled-data.
//!
//! At each control instant t_k = k dt the law reads x_k and the reference at t_k; the command
//! is actuated (scaled, saturated) and held over [t_k, t_k + dt); the law's memory is advanced;
//! the random part of the disturbance is drawn for period k and held; the plant is advanced by
//! `substeps` steps of the integrator, whose stages see the deterministic disturbance at their
//! own times. No heap allocation happens inside the step loop.
//!
//! The cases of a block are the lanes of one [`Real`] value: every branch of the scalar
//! algorithm is a mask (divergence, touchdown, settling), and a stopped case keeps its last
//! admissible state while the others go on. Nothing a lane computes depends on the other
//! lanes, so a case gives the same bits in any block, at any position, alone or padded.
//!
//! A block between two control instants is a [`Block`]: [`Block::start`], one
//! [`Block::period`] per control period with the law's command, [`Block::finish`]. A built-in
//! law drives it from inside the block ([`rollout_block`]); a law computed outside the core
//! drives every block of a batch one period at a time ([`crate::external`]).

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::SVector;

use crate::actuator::{Actuator, Lag};
use crate::control::{AnyLaw, LawInput};
use crate::disturbance::{Disturbance, NoiseStreams, disturbance_stream};
use crate::error::ParamError;
use crate::event::{Event, locate_crossing};
use crate::integrator::{IntegratorKind, Stage, StageDerivative};
use crate::kernel::{LawCalls, OutOfLine};
use crate::lanes::{
    Mask, Real, add, all_finite, div, dot, filled, norm, scale_by, select_vector, sub, zeros,
};
use crate::limits::MAX_STEPS;
use crate::metrics::{
    CaseMetrics, CommandStats, Diverged, Divergence, HighPass, MAX_COMMAND, MAX_STATE, Touchdown,
};
use crate::navigation::Navigator;
use crate::plant::Plant;
use crate::reference::Reference;
use crate::state::State;

/// Tolerance on the tracking-error norm |e| that defines the settle time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// In units of q (m, rad).
    Absolute(f64),
    /// A fraction of the initial error norm (the classical 2 % settling time is `Relative(0.02)`).
    Relative(f64),
}

impl Tolerance {
    pub fn validate(&self) -> Result<(), ParamError> {
        match *self {
            Tolerance::Absolute(v) | Tolerance::Relative(v) => {
                crate::error::require(v >= 0.0, "settle_tolerance", v, "settle_tolerance >= 0")
            }
        }
    }
}

/// Horizon, step and recording of a batch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimConfig {
    /// Control period.
    pub dt: f64,
    /// Number of control periods K; t_final = K dt.
    pub steps: u64,
    /// Integrator steps per control period.
    pub substeps: u32,
    /// Keep every k-th control instant (and always the first and the last); 0 keeps none.
    pub record_every: u64,
    /// Seed of the counter-based random streams.
    pub seed: u64,
    /// Global index of the batch's first case: case i draws from the streams of case
    /// `first_case + i`, so a slice of a campaign can be re-run alone with the same numbers.
    pub first_case: u64,
    /// What "settled" means for the settle-time metric.
    pub settle: Tolerance,
    /// The integrator (chosen at run time).
    pub integrator: IntegratorKind,
    /// Cut-off frequency (Hz) of the high-pass filter behind the chattering metric; NaN for
    /// a tenth of the Nyquist frequency, 1 / (20 dt).
    pub chatter_cutoff: f64,
    /// The event that ends each case, if any ([`crate::event`]): the case is then frozen at
    /// its state at the event.
    pub stop_at: Option<Event>,
}

impl SimConfig {
    /// Checks the horizon: t_final must be a whole number of control periods (to 1e-9
    /// relative), because the zero-order hold has no partial period.
    pub fn new(
        t_final: f64,
        dt: f64,
        substeps: u32,
        record_every: u64,
        seed: u64,
    ) -> Result<Self, ParamError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(ParamError::new("dt", dt, "dt > 0 and finite"));
        }
        if !(t_final.is_finite() && t_final > 0.0) {
            return Err(ParamError::new(
                "t_final",
                t_final,
                "t_final > 0 and finite",
            ));
        }
        let ratio = t_final / dt;
        if ratio < 1.0 - 1e-9 {
            return Err(ParamError::new("t_final", t_final, "t_final >= dt"));
        }
        let steps = ratio.round();
        if (ratio - steps).abs() > 1e-9 * steps.max(1.0) {
            return Err(ParamError::new(
                "t_final",
                t_final,
                "t_final an integer multiple of dt",
            ));
        }
        if steps > MAX_STEPS as f64 {
            return Err(ParamError::new("t_final", t_final, "t_final / dt <= 2^40"));
        }
        if substeps == 0 {
            return Err(ParamError::new("substeps", 0.0, "substeps >= 1"));
        }
        Ok(Self {
            dt,
            steps: steps as u64,
            substeps,
            record_every,
            seed,
            first_case: 0,
            settle: Tolerance::Relative(0.02),
            integrator: IntegratorKind::Rk4,
            chatter_cutoff: f64::NAN,
            stop_at: None,
        })
    }

    /// The same configuration ending each case at `event` (or at t_final only, for None).
    pub fn with_stop_at(mut self, event: Option<Event>) -> Self {
        self.stop_at = event;
        self
    }

    /// The same configuration with another settle tolerance.
    pub fn with_settle(mut self, settle: Tolerance) -> Result<Self, ParamError> {
        settle.validate()?;
        self.settle = settle;
        Ok(self)
    }

    /// The same configuration with another chattering cut-off frequency (Hz, below Nyquist).
    pub fn with_chatter_cutoff(mut self, hz: f64) -> Result<Self, ParamError> {
        let nyquist = 0.5 / self.dt;
        if !(hz > 0.0 && hz < nyquist) {
            return Err(ParamError::new(
                "chatter_cutoff",
                hz,
                "0 < chatter_cutoff < 1 / (2 dt)",
            ));
        }
        self.chatter_cutoff = hz;
        Ok(self)
    }

    /// The high-pass filter of the chattering metric at this step.
    pub fn chatter_filter(&self) -> HighPass {
        let hz = if self.chatter_cutoff.is_nan() {
            0.05 / self.dt
        } else {
            self.chatter_cutoff
        };
        HighPass::butterworth2(hz, self.dt)
    }

    /// The same configuration with another integrator.
    pub fn with_integrator(mut self, integrator: IntegratorKind) -> Self {
        self.integrator = integrator;
        self
    }

    /// The same configuration with the batch's cases numbered from `first_case`.
    pub fn with_first_case(mut self, first_case: u64) -> Self {
        self.first_case = first_case;
        self
    }

    pub fn t_final(&self) -> f64 {
        self.steps as f64 * self.dt
    }

    /// Number of recorded instants.
    pub fn n_records(&self) -> usize {
        match self.record_every {
            0 => 0,
            e => (self.steps / e + 1 + u64::from(!self.steps.is_multiple_of(e))) as usize,
        }
    }

    /// The recorded control instants, in seconds.
    pub fn record_times(&self) -> Vec<f64> {
        let mut t = Vec::with_capacity(self.n_records());
        if self.record_every > 0 {
            let mut k = 0;
            while k < self.steps {
                t.push(k as f64 * self.dt);
                k += self.record_every;
            }
            t.push(self.t_final());
        }
        t
    }
}

/// How often (in integrator steps, rounded to whole control periods) a running block looks at
/// the cancellation flag: a block of the heaviest plant takes well under a millisecond for 64
/// steps, so a cancelled batch stops within milliseconds, and the atomic load costs nothing
/// measurable.
const CANCEL_POLL_STEPS: u64 = 64;

/// When and why each lane stopped: NaN and 0 while it runs.
struct Stops<R: Real> {
    time: R,
    reason: R,
}

impl<R: Real> Stops<R> {
    fn new() -> Self {
        Self {
            time: R::splat(f64::NAN),
            reason: R::zero(),
        }
    }

    #[inline(always)]
    fn mark(&mut self, lanes: R::Mask, t: f64, reason: Divergence) {
        self.time = R::select(lanes, R::splat(t), self.time);
        self.reason = R::select(lanes, R::splat(f64::from(reason.code())), self.reason);
    }

    fn lane(&self, i: usize) -> Option<Diverged> {
        Divergence::from_code(self.reason.lane(i) as u8).map(|reason| Diverged {
            time: self.time.lane(i),
            reason,
        })
    }
}

/// The live lanes whose command is bad, marked in `stops` with the reason: non-finite, or a
/// component beyond [`MAX_COMMAND`] in magnitude.
#[inline(always)]
fn bad_command<const D: usize, R: Real>(
    live: R::Mask,
    u: &SVector<R, D>,
    t: f64,
    stops: &mut Stops<R>,
) -> R::Mask {
    // |u_i| <= MAX is false for NaN too: one compare per axis in the common case
    let limit = R::splat(MAX_COMMAND);
    let mut ok = u[0].abs().simd_le(limit);
    for i in 1..D {
        ok = ok & u[i].abs().simd_le(limit);
    }
    let bad = live & !ok;
    if bad.any() {
        let non_finite = bad & !all_finite(u);
        stops.mark(non_finite, t, Divergence::NonFiniteCommand);
        stops.mark(bad & !non_finite, t, Divergence::CommandOutOfRange);
    }
    bad
}

/// Most values a law's diagnostics take per instant (checked when a batch is built).
pub const MAX_DIAGNOSTIC_WIDTH: usize = 16;

/// Where the lanes of a block write their recordings: the buffers of the block's cases, case
/// after case, pre-filled with NaN (a stopped case never writes again, so it reads NaN from its
/// divergence on). The slices are empty when nothing is recorded.
pub(crate) struct BlockBuffers<'a, const D: usize> {
    /// cases x n_records x state dim.
    pub states: &'a mut [f64],
    /// cases x n_records x D.
    pub controls: &'a mut [f64],
    /// cases x n_records x diagnostic width.
    pub diagnostics: &'a mut [f64],
    /// cases x state dim.
    pub final_state: &'a mut [f64],
    /// One per case of the block (the padding lanes have none).
    pub metrics: &'a mut [CaseMetrics<D>],
}

impl<const D: usize> BlockBuffers<'_, D> {
    /// Fills the recording with NaN: what [`crate::batch::Outputs::allocate`] does for the
    /// whole batch, done by the block's own job when its buffers were allocated untouched.
    pub(crate) fn fill_nan(&mut self) {
        self.states.fill(f64::NAN);
        self.controls.fill(f64::NAN);
        self.diagnostics.fill(f64::NAN);
    }
}

/// The deterministic disturbance shared by every case of a batch, evaluated once per stage of
/// every integrator step: `values[(k * substeps + j) * stages + s]` for control period k,
/// substep j and the integrator's stage s, with the same operations a lane would use.
pub struct StageTable<const D: usize> {
    values: Vec<SVector<f64, D>>,
    substeps: usize,
    stages: usize,
}

impl<const D: usize> StageTable<D> {
    /// Most bytes a table may take; beyond, every block evaluates its own (same bits).
    pub const MAX_BYTES: usize = 64 << 20;

    /// The table of `disturbance` for `cfg`, or None if it would be too large.
    pub fn new(disturbance: &Disturbance<D>, cfg: &SimConfig) -> Option<Self> {
        let stages = cfg.integrator.stages();
        let substeps = cfg.substeps as usize;
        let len = (cfg.steps as u128) * (substeps as u128) * (stages.len() as u128);
        if len * (D as u128) * 8 > Self::MAX_BYTES as u128 {
            return None;
        }
        let h = cfg.dt / f64::from(cfg.substeps);
        let mut values = Vec::with_capacity(len as usize);
        for k in 0..cfg.steps {
            let t = k as f64 * cfg.dt;
            for j in 0..substeps {
                let tj = t + j as f64 * h;
                for s in stages {
                    values.push(disturbance.deterministic(s.time(tj, h)));
                }
            }
        }
        Some(Self {
            values,
            substeps,
            stages: stages.len(),
        })
    }

    #[inline(always)]
    fn get(&self, k: u64, j: usize, stage: usize) -> &SVector<f64, D> {
        &self.values[(k as usize * self.substeps + j) * self.stages + stage]
    }
}

/// The disturbance at a stage (control period k, substep j, the stage) at `time`: the
/// deterministic part, from the batch's table or per lane (the same bits), plus the random
/// part `held` drawn for the period.
#[inline(always)]
pub(crate) fn stage_disturbance<const D: usize, R: Real>(
    disturbance: &Disturbance<D, R>,
    table: Option<&StageTable<D>>,
    (k, j, stage): (u64, usize, Stage),
    time: f64,
    held: &SVector<R, D>,
) -> SVector<R, D> {
    let det = match table {
        Some(tab) => {
            let v = tab.get(k, j, stage.index());
            let mut splat = zeros();
            for i in 0..D {
                splat[i] = R::splat(v[i]);
            }
            splat
        }
        None => disturbance.deterministic(time),
    };
    add(&det, held)
}

/// The command over a period's stages: held as it is, or the actuator's lag through the
/// plant's limits. A type, not a branch in the stage: the held command's |u| is then computed
/// once per period (a branch per stage kept the compiler from hoisting it: W1 25 % slower, BENCHMARKS.md).
/// It returns the command rather than calling a closure with it: a closure is not always
/// inlined, and the lag's was not, so that every lane operation of the plant's derivative ran
/// out of line without the kernel's instruction set (BENCHMARKS.md).
trait StageCommand<const D: usize, R: Real, P> {
    /// The command at `time`: the held one, or one written into `room`.
    fn command<'s>(
        &'s self,
        plant: &P,
        time: f64,
        room: &'s mut SVector<R, D>,
    ) -> &'s SVector<R, D>;
}

struct Constant<'a, const D: usize, R: Real>(&'a SVector<R, D>);

impl<const D: usize, R: Real, P, U: StageCommand<D, R, P>> StageCommand<D, R, P> for &U {
    #[inline(always)]
    fn command<'s>(
        &'s self,
        plant: &P,
        time: f64,
        room: &'s mut SVector<R, D>,
    ) -> &'s SVector<R, D> {
        (**self).command(plant, time, room)
    }
}

impl<const D: usize, R: Real, P> StageCommand<D, R, P> for Constant<'_, D, R> {
    #[inline(always)]
    fn command<'s>(
        &'s self,
        _plant: &P,
        _time: f64,
        _room: &'s mut SVector<R, D>,
    ) -> &'s SVector<R, D> {
        self.0
    }
}

impl<const D: usize, R: Real, P: Plant<R, D>> StageCommand<D, R, P> for Lag<D, R> {
    #[inline(always)]
    fn command<'s>(
        &'s self,
        plant: &P,
        time: f64,
        room: &'s mut SVector<R, D>,
    ) -> &'s SVector<R, D> {
        *room = plant.limit(&self.at(time));
        room
    }
}

/// The plant's derivative over one step with the command held: what the integrator steps.
struct Held<'a, const D: usize, R: Real, P, U> {
    plant: &'a P,
    disturbance: &'a Disturbance<D, R>,
    table: Option<&'a StageTable<D>>,
    /// Control period, substep, and the substep's start time and length.
    k: u64,
    j: usize,
    tj: f64,
    h: f64,
    /// The command: held, or the actuator's lag.
    u: U,
    /// The random disturbance drawn for the period.
    held: &'a SVector<R, D>,
    /// The modelled acceleration at the period's start (the law's input).
    drift: &'a SVector<R, D>,
}

impl<const D: usize, R: Real, P: Plant<R, D>, U: StageCommand<D, R, P>> StageDerivative<R, P::State>
    for Held<'_, D, R, P, U>
{
    #[inline(always)]
    fn at(&self, stage: Stage, y: &P::State) -> P::State {
        let mut k = *y;
        self.at_into(stage, y, &mut k);
        k
    }

    #[inline(always)]
    fn at_into(&self, stage: Stage, y: &P::State, k: &mut P::State) {
        let time = stage.time(self.tj, self.h);
        let d = stage_disturbance(
            self.disturbance,
            self.table,
            (self.k, self.j, stage),
            time,
            self.held,
        );
        // One call, the drift chosen before it: two calls returning the state from the
        // branches of an `if` made the compiler copy the (kilobyte) result out of each.
        // `derivative_with_drift` at the modelled acceleration is `derivative` by contract,
        // and plants that ignore the drift let the unused evaluation be optimised away.
        let drift = if self.j == 0 && stage == Stage::Start {
            *self.drift
        } else {
            self.plant.modelled_acceleration(time, y)
        };
        let mut room = crate::lanes::zeros();
        let u = self.u.command(self.plant, time, &mut room);
        self.plant.derivative_into(time, y, u, &d, &drift, k)
    }
}

/// Why a block stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Cancelled;

/// Builds what the law sees at (t, x).
#[inline(always)]
fn law_input<const D: usize, R: Real, P: Plant<R, D>>(
    plant: &P,
    reference: &Reference<D, R>,
    t: f64,
    dt: f64,
    x: &P::State,
) -> LawInput<D, R> {
    let (q, qd) = plant.coordinates(x);
    let r = reference.at(t);
    LawInput {
        t,
        dt,
        e: sub(&q, &r.position),
        de: sub(&qd, &r.velocity),
        reference: r,
        drift: plant.modelled_acceleration(t, x),
        inertia: plant.inertia(x),
    }
}

/// A block's navigation ([`crate::navigation`]) and what the law reads through it.
struct Sensed<const D: usize, R: Real> {
    nav: Navigator<D, R>,
    view: LawInput<D, R>,
}

/// The law's input at (t, x) seen through the estimate `[q_hat, q'_hat]`: the input at the
/// state with its coordinates replaced, so that the drift and inertia are the plant's there
/// (the other components, a lander's mass, are known to the law).
#[inline(always)]
fn seen<const D: usize, R: Real, P: Plant<R, D>>(
    plant: &P,
    reference: &Reference<D, R>,
    (t, dt): (f64, f64),
    x: &P::State,
    estimate: &[SVector<R, D>; 2],
) -> LawInput<D, R> {
    let (qc, vc) = plant.coordinate_components();
    let mut at = *x;
    for i in 0..D {
        at.set_component(qc[i], estimate[0][i]);
        at.set_component(vc[i], estimate[1][i]);
    }
    law_input(plant, reference, t, dt, &at)
}

/// Writes record `slot` of the live lanes: the state, the applied command and the law's
/// diagnostics.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn record<const D: usize, R: Real, S: State<R>>(
    out: &mut BlockBuffers<'_, D>,
    used: usize,
    n_records: usize,
    slot: usize,
    live: R::Mask,
    nx: usize,
    x: &S,
    u: &SVector<R, D>,
    (diag, estimate): (&[R], Option<&[SVector<R, D>; 2]>),
) {
    let nd = diag.len() + estimate.map_or(0, |_| 2 * D);
    for i in 0..used {
        if !live.lane(i) {
            continue;
        }
        let row = i * n_records + slot;
        for c in 0..nx {
            out.states[row * nx + c] = x.component(c).lane(i);
        }
        for c in 0..D {
            out.controls[row * D + c] = u[c].lane(i);
        }
        for (c, d) in diag.iter().enumerate() {
            out.diagnostics[row * nd + c] = d.lane(i);
        }
        // the navigation's estimate, after the law's own diagnostics: q_hat, then q'_hat
        if let Some(est) = estimate {
            let at = row * nd + diag.len();
            for (c, v) in est.iter().flat_map(|part| part.iter()).enumerate() {
                out.diagnostics[at + c] = v.lane(i);
            }
        }
    }
}

/// What a control period holds over its substeps: the applied command (at the period's
/// start, when the actuator lags), the actuator's lag, the random disturbance drawn for the
/// period, its start time and the substep's length.
pub(crate) struct PeriodHold<const D: usize, R: Real> {
    pub u: SVector<R, D>,
    pub lag: Option<Lag<D, R>>,
    pub disturbance: SVector<R, D>,
    pub t: f64,
    pub h: f64,
}

/// What the periods of a block read and never change.
pub(crate) struct Setting<'a, const D: usize, R: Real, P> {
    pub plant: &'a P,
    pub reference: &'a Reference<D, R>,
    pub disturbance: &'a Disturbance<D, R>,
    pub table: Option<&'a StageTable<D>>,
    pub cfg: &'a SimConfig,
}

/// A block of cases between two control periods: the plant's state, the law's input at the
/// coming instant, the metric accumulators, the stops and the recording cursor. The law is
/// not here: a built-in law's memory lives in the lanes beside it ([`rollout_block`]), an
/// external law's outside the core ([`crate::batch::run_external`]). Both drive a block the
/// same way, [`Block::start`], one [`Block::period`] per control period with the law's
/// command, [`Block::finish`], so the physics and the metrics are one implementation.
pub(crate) struct Block<const D: usize, R: Real, P: Plant<R, D>> {
    rng: Vec<NoiseStreams>,
    stats: CommandStats<D, R>,
    x: P::State,
    // the step's result and the integrator's stage point and derivative, kept in the block
    // so that the integrator writes them in place
    next: P::State,
    scratch: [P::State; 2],
    m0: Option<R>,
    input: LawInput<D, R>,
    live: R::Mask,
    stops: Stops<R>,
    touched: R::Mask,
    // the lanes stopped by the run's event (not diverged: their state is the event's), and
    // their tracking errors there, against the reference at the end of the event's step (the
    // law's input goes on at later instants for the block's other lanes)
    landed: R::Mask,
    landed_e: SVector<R, D>,
    landed_de: SVector<R, D>,
    td_time: R,
    td_position: SVector<R, D>,
    td_velocity: SVector<R, D>,
    slot: usize,
    next_record: u64,
    // compared squared: no square root per step
    tolerance_sq: R,
    // per lane: the last control instant at which |e| was outside the tolerance (-1 for
    // none), and the mass at the instant after it (the settle instant, should the error stay
    // inside from there on)
    last_outside: R,
    settle_mass: Option<R>,
    was_outside: R::Mask,
    // the actuator's delay and lag, when the plant has them (boxed: most blocks have none)
    actuator: Option<Box<Actuator<D, R>>>,
    // the sensor and filter, when the plant has them: the law reads their view, the metrics
    // and the physics `input`, the truth
    nav: Option<Box<Sensed<D, R>>>,
    used: usize,
}

impl<const D: usize, R: Real, P: Plant<R, D>> Block<D, R, P> {
    /// The block at t = 0: lane i is case `cases[i]` (its global index, which keys its random
    /// streams); the first `used` lanes are real cases, the others padding.
    #[inline(always)]
    pub(crate) fn start(
        set: &Setting<'_, D, R, P>,
        x0: &P::State,
        cases: &[u64],
        used: usize,
    ) -> Self {
        let cfg = set.cfg;
        let nan = R::splat(f64::NAN);
        let input = law_input(set.plant, set.reference, 0.0, cfg.dt, x0);
        let tolerance = match cfg.settle {
            Tolerance::Absolute(v) => R::splat(v),
            Tolerance::Relative(f) => norm(&input.e) * f,
        };
        let m0 = set.plant.mass(x0);
        let nav = set.plant.navigation().map(|n| {
            let (q, v) = set.plant.coordinates(x0);
            let nav = Navigator::start(n, (cfg.seed, cases, cfg.dt), (&q, &v));
            let view = seen(set.plant, set.reference, (0.0, cfg.dt), x0, nav.estimate());
            Box::new(Sensed { nav, view })
        });
        Self {
            rng: cases
                .iter()
                .map(|&c| disturbance_stream(cfg.seed, c))
                .collect(),
            stats: CommandStats::<D, R>::new(cfg.chatter_filter()),
            x: *x0,
            next: *x0,
            scratch: [*x0; 2],
            m0,
            input,
            live: R::Mask::splat(true),
            stops: Stops::<R>::new(),
            touched: R::Mask::splat(false),
            landed: R::Mask::splat(false),
            landed_e: filled(nan),
            landed_de: filled(nan),
            td_time: nan,
            td_position: filled(nan),
            td_velocity: filled(nan),
            slot: 0,
            next_record: 0,
            tolerance_sq: tolerance * tolerance,
            last_outside: R::splat(-1.0),
            settle_mass: m0,
            was_outside: R::Mask::splat(false),
            actuator: set
                .plant
                .actuator()
                .and_then(|spec| Actuator::new(&spec, set.plant.limit(&zeros())))
                .map(Box::new),
            nav,
            used,
        }
    }

    /// What the law sees at the coming control instant: the truth, or the navigation's view.
    #[inline(always)]
    pub(crate) fn input(&self) -> &LawInput<D, R> {
        match &self.nav {
            None => &self.input,
            Some(sensed) => &sensed.view,
        }
    }

    /// Whether any lane still runs.
    #[inline(always)]
    pub(crate) fn any_live(&self) -> bool {
        self.live.any()
    }

    /// Whether control instant `k` is recorded (the law's diagnostics are then needed).
    #[inline(always)]
    pub(crate) fn records(&self, cfg: &SimConfig, k: u64) -> bool {
        cfg.record_every > 0 && k == self.next_record
    }

    /// Control period k under the law's commanded acceleration `a` (and, when the instant is
    /// recorded, its diagnostics `diag`): the command is actuated and held, checked, recorded
    /// and counted in the statistics; the random disturbance is drawn; the plant is advanced by
    /// the period's substeps, each crossing of the ground located and each stop flagged; the
    /// law's input at t_(k+1) is made. Returns whether any lane still runs.
    ///
    /// The period is [`Block::begin_period`], per substep one integrator step from
    /// [`Block::state`] into [`Block::next_mut`] and [`Block::end_substep`], then
    /// [`Block::end_period`]: a driver whose plant computes its derivatives elsewhere
    /// ([`crate::external`]) calls the pieces itself.
    #[inline(always)]
    pub(crate) fn period<K: LawCalls<D, R>>(
        &mut self,
        set: &Setting<'_, D, R, P>,
        k: u64,
        a: &SVector<R, D>,
        diag: &[R],
        out: &mut BlockBuffers<'_, D>,
    ) -> bool {
        let Some(hold) = self.begin_period::<K>(set, k, a, diag, out) else {
            return false;
        };
        let cfg = set.cfg;
        let ran = match &hold.lag {
            None => self.substeps::<K, _>(set, k, &hold, Constant(&hold.u)),
            Some(lag) => self.substeps::<K, _>(set, k, &hold, *lag),
        };
        if !ran {
            return false;
        }
        if let (Some(actuator), Some(lag)) = (self.actuator.as_deref_mut(), &hold.lag) {
            actuator.end(lag, (k + 1) as f64 * cfg.dt);
        }
        self.end_period(set, k);
        true
    }

    /// The substeps of period k under the command `u`. Returns whether any lane still runs.
    #[inline(always)]
    fn substeps<K: LawCalls<D, R>, U: StageCommand<D, R, P>>(
        &mut self,
        set: &Setting<'_, D, R, P>,
        k: u64,
        hold: &PeriodHold<D, R>,
        u: U,
    ) -> bool {
        let cfg = set.cfg;
        for j in 0..cfg.substeps as usize {
            let tj = hold.t + j as f64 * hold.h;
            let f = Held {
                plant: set.plant,
                disturbance: set.disturbance,
                table: set.table,
                k,
                j,
                tj,
                h: hold.h,
                u: &u,
                held: &hold.disturbance,
                drift: &self.input.drift,
            };
            cfg.integrator
                .step_into(&f, &self.x, hold.h, &mut self.next, &mut self.scratch);
            if !self.end_substep::<K>(set, tj, hold.h) {
                return false;
            }
        }
        true
    }

    /// The start of control period k: the command is actuated, checked, recorded and counted;
    /// the random disturbance is drawn. None when no lane runs on.
    #[inline(always)]
    pub(crate) fn begin_period<K: LawCalls<D, R>>(
        &mut self,
        set: &Setting<'_, D, R, P>,
        k: u64,
        a: &SVector<R, D>,
        diag: &[R],
        out: &mut BlockBuffers<'_, D>,
    ) -> Option<PeriodHold<D, R>> {
        let (plant, cfg) = (set.plant, set.cfg);
        let t = k as f64 * cfg.dt;
        let (u, lag) = self.applied(plant, k, t, a);
        if let Some(Sensed { nav, view }) = self.nav.as_deref_mut() {
            nav.hold(&u, &view.inertia, &view.drift);
        }
        let bad = bad_command(self.live, &u, t, &mut self.stops);
        if bad.any() {
            self.stats.freeze(bad);
            self.live = self.live & !bad;
            if !self.live.any() {
                return None;
            }
        }
        if self.records(cfg, k) {
            record(
                out,
                self.used,
                cfg.n_records(),
                self.slot,
                self.live,
                plant.state_dim(),
                &self.x,
                &u,
                (diag, self.nav.as_ref().map(|n| n.nav.estimate())),
            );
            self.slot += 1;
            self.next_record += cfg.record_every;
        }
        let live = self.live;
        let input = &self.input;
        K::add_stats(&mut self.stats, &u, &input.e, cfg.dt);
        let outside = dot(&input.e, &input.e).simd_gt(self.tolerance_sq);
        self.last_outside = R::select(live & outside, R::splat(k as f64), self.last_outside);
        if let (Some(sm), Some(m)) = (self.settle_mass.as_mut(), plant.mass(&self.x)) {
            *sm = R::select(live & self.was_outside & !outside, m, *sm);
        }
        self.was_outside = (live & outside) | (!live & self.was_outside);

        let disturbance = if set.disturbance.is_random() {
            set.disturbance.draw(&self.rng, k, &div(&u, &input.inertia))
        } else {
            zeros()
        };
        Some(PeriodHold {
            u,
            lag,
            disturbance,
            t,
            h: cfg.dt / f64::from(cfg.substeps),
        })
    }

    /// The command applied at instant k (time t) for the law's command `a`: actuated, then
    /// delayed and lagged when the plant's actuator has them, and the lag over the period.
    #[inline(always)]
    fn applied(
        &mut self,
        plant: &P,
        k: u64,
        t: f64,
        a: &SVector<R, D>,
    ) -> (SVector<R, D>, Option<Lag<D, R>>) {
        let u = plant.actuate(&self.x, a);
        match self.actuator.as_deref_mut() {
            None => (u, None),
            Some(actuator) => {
                let (c, lag) = actuator.begin(k, t, &u);
                // a delayed command is already within the limits (and the idle one too)
                (if lag.is_some() { plant.limit(&c) } else { c }, lag)
            }
        }
    }

    /// The plant's state at the start of the substep.
    #[inline(always)]
    pub(crate) fn state(&self) -> &P::State {
        &self.x
    }

    /// The state at the substep's start, and where the integrator writes the state at its end.
    #[inline(always)]
    pub(crate) fn next_mut(&mut self) -> (&P::State, &mut P::State) {
        (&self.x, &mut self.next)
    }

    /// The end of the substep `[tj, tj + h]` whose end state the integrator wrote: a crossing
    /// of the ground is located, the lanes whose state is non-finite or out of the domain are
    /// stopped, the others take the new state. Returns whether any lane still runs.
    #[inline(always)]
    pub(crate) fn end_substep<K: LawCalls<D, R>>(
        &mut self,
        set: &Setting<'_, D, R, P>,
        tj: f64,
        h: f64,
    ) -> bool {
        let plant = set.plant;
        let zero = R::zero();
        if let (Some(z0), Some(z1)) = (plant.altitude(&self.x), plant.altitude(&self.next)) {
            let cross = self.live & !self.touched & z0.simd_gt(zero) & z1.simd_le(zero);
            if cross.any() {
                return self.touch_down::<K>(set, tj, h, (z0, z1), cross);
            }
        }
        self.settle(set, tj, h, None)
    }

    /// [`Block::end_substep`] for a substep in which the lanes `cross` reach the ground, out of
    /// the hot path (once per case): [`Block::locate_touchdown`], through the level's
    /// out-of-line trampoline. A generic function compiled on its own lacks the level's
    /// instructions: every lane operation was a call (`_mm512_mul_pd` and the like, 1.4 % of a
    /// Mars campaign's samples with the function's own; BENCHMARKS.md).
    #[cold]
    #[inline(never)]
    fn touch_down<K: LawCalls<D, R>>(
        &mut self,
        set: &Setting<'_, D, R, P>,
        tj: f64,
        h: f64,
        z: (R, R),
        cross: R::Mask,
    ) -> bool {
        K::out_of_line(TouchDown {
            block: self,
            set,
            tj,
            h,
            z,
            cross,
        })
    }

    /// The crossing of the lanes `cross` located and, under the touchdown event, those lanes
    /// frozen there.
    #[inline(always)]
    fn locate_touchdown(
        &mut self,
        set: &Setting<'_, D, R, P>,
        tj: f64,
        h: f64,
        (z0, z1): (R, R),
        cross: R::Mask,
    ) -> bool {
        let plant = set.plant;
        let (x, next) = (&self.x, &self.next);
        let (q0, v0) = plant.coordinates(x);
        let (q1, v1) = plant.coordinates(next);
        let (s, q, v) = match plant.altitude_axis() {
            Some(axis) => locate_crossing((&q0, &v0), (&q1, &v1), axis, h, cross),
            // an altitude that is not a coordinate: the chord
            None => {
                let s = z0 / (z0 - z1);
                let at = |a: &SVector<R, D>, b: &SVector<R, D>| add(a, &scale_by(&sub(b, a), s));
                (s, at(&q0, &q1), at(&v0, &v1))
            }
        };
        self.td_time = R::select(cross, s * R::splat(h) + R::splat(tj), self.td_time);
        self.td_position = select_vector(cross, &q, &self.td_position);
        self.td_velocity = select_vector(cross, &v, &self.td_velocity);
        self.touched = self.touched | cross;
        if set.cfg.stop_at != Some(Event::Touchdown) {
            return self.settle(set, tj, h, None);
        }
        // the case ends at the event, frozen in the state there: the coordinates as located,
        // the other components (a lander's mass) along the chord
        let (qc, vc) = plant.coordinate_components();
        let mut at = <P::State as State<R>>::from_components(|c| {
            let (a, b) = (x.component(c), next.component(c));
            a + (b - a) * s
        });
        for i in 0..D {
            at.set_component(qc[i], q[i]);
            at.set_component(vc[i], v[i]);
        }
        self.next.select_assign(cross, &at);
        self.settle(set, tj, h, Some(cross))
    }

    /// The rest of [`Block::end_substep`]: the lanes `landing` end at the event; of the others
    /// those whose state is non-finite or out of the domain stop, the rest take the new state.
    #[inline(always)]
    fn settle(
        &mut self,
        set: &Setting<'_, D, R, P>,
        tj: f64,
        h: f64,
        landing: Option<R::Mask>,
    ) -> bool {
        let plant = set.plant;
        let next = &self.next;
        // |x_i| <= MAX_STATE is false for a NaN too: one compare per component in the common
        // case, the reason told apart only when a lane stops
        let within = next.all_within(R::splat(MAX_STATE));
        let ends = match landing {
            None => self.live,
            Some(landing) => self.live & !landing,
        };
        let bad = ends & !(within & plant.in_domain(next));
        if bad.any() {
            let finite = next.all_finite();
            self.stops
                .mark(bad & !finite, tj + h, Divergence::NonFiniteState);
            self.stops
                .mark(bad & finite, tj + h, Divergence::OutOfDomain);
            self.stats.freeze(bad);
            self.live = self.live & !bad;
        }
        if let Some(landing) = landing {
            self.x.select_assign(landing, &self.next);
            self.stats.freeze(landing);
            self.landed = self.landed | landing;
            self.live = self.live & !landing;
            let (q, v) = plant.coordinates(&self.x);
            let r = set.reference.at(tj + h);
            self.landed_e = select_vector(landing, &sub(&q, &r.position), &self.landed_e);
            self.landed_de = select_vector(landing, &sub(&v, &r.velocity), &self.landed_de);
        }
        self.x.select_assign(self.live, &self.next);
        self.live.any()
    }

    /// The end of control period k: the law's input at t_(k+1).
    #[inline(always)]
    pub(crate) fn end_period(&mut self, set: &Setting<'_, D, R, P>, k: u64) {
        let cfg = set.cfg;
        let t = (k + 1) as f64 * cfg.dt;
        self.input = law_input(set.plant, set.reference, t, cfg.dt, &self.x);
        if let Some(Sensed { nav, view }) = self.nav.as_deref_mut() {
            let (q, v) = set.plant.coordinates(&self.x);
            nav.advance(k + 1, (&q, &v), self.live);
            *view = seen(
                set.plant,
                set.reference,
                (t, cfg.dt),
                &self.x,
                nav.estimate(),
            );
        }
    }

    /// Writes the block's final states and metrics. `last` is the law's command (and
    /// diagnostics) at t_final, given when a lane still runs: it is recorded, being what would
    /// be held next, and checked, but not applied.
    #[inline(always)]
    pub(crate) fn finish(
        &mut self,
        set: &Setting<'_, D, R, P>,
        last: Option<(&SVector<R, D>, &[R])>,
        out: &mut BlockBuffers<'_, D>,
    ) {
        let (plant, cfg) = (set.plant, set.cfg);
        let mut finished = self.live;
        if let Some((a, diag)) = last.filter(|_| self.live.any()) {
            // what would be applied next: through the actuator's delay and lag
            let (u, _) = self.applied(plant, cfg.steps, cfg.t_final(), a);
            let bad = bad_command(self.live, &u, cfg.t_final(), &mut self.stops);
            finished = self.live & !bad;
            if cfg.record_every > 0 {
                record(
                    out,
                    self.used,
                    cfg.n_records(),
                    self.slot,
                    finished,
                    plant.state_dim(),
                    &self.x,
                    &u,
                    (diag, self.nav.as_ref().map(|n| n.nav.estimate())),
                );
            }
        }
        // a case the event ended finished there, in the state it was frozen in
        finished = finished | self.landed;
        let e = select_vector(self.landed, &self.landed_e, &self.input.e);
        let de = select_vector(self.landed, &self.landed_de, &self.input.de);
        let inside = dot(&e, &e).simd_le(self.tolerance_sq);
        if let (Some(sm), Some(m)) = (self.settle_mass.as_mut(), plant.mass(&self.x)) {
            *sm = R::select(inside & self.was_outside, m, *sm);
        }
        let mass = plant.mass(&self.x);
        let nx = plant.state_dim();
        for i in 0..self.used {
            let m = &mut out.metrics[i];
            *m = CaseMetrics::new();
            self.stats.finish_lane(i, m);
            m.navigation = self.nav.as_ref().map(|n| n.nav.metrics(i));
            if self.touched.lane(i) {
                m.touchdown = Some(Touchdown {
                    time: self.td_time.lane(i),
                    position: SVector::from_fn(|c, _| self.td_position[c].lane(i)),
                    velocity: SVector::from_fn(|c, _| self.td_velocity[c].lane(i)),
                });
            }
            let final_error: SVector<f64, D> = SVector::from_fn(|c, _| e[c].lane(i));
            let final_rate_error: SVector<f64, D> = SVector::from_fn(|c, _| de[c].lane(i));
            // |e| of a state within MAX_STATE is finite, but a reference far beyond it is not
            let errors_finite = final_error.norm_squared().is_finite()
                && final_rate_error.norm_squared().is_finite();
            if finished.lane(i) && !(errors_finite && m.accumulations_finite()) {
                // the safety net behind MAX_COMMAND and MAX_STATE: no non-finite statistic
                // goes unflagged
                m.diverged = Some(Diverged {
                    time: cfg.t_final(),
                    reason: Divergence::NonFiniteMetric,
                });
                continue;
            }
            if !finished.lane(i) {
                m.diverged = self.stops.lane(i);
                continue;
            }
            for c in 0..nx {
                out.final_state[i * nx + c] = self.x.component(c).lane(i);
            }
            if inside.lane(i) {
                let last = self.last_outside.lane(i);
                m.settle_time = if last < 0.0 {
                    0.0
                } else {
                    (last + 1.0) * cfg.dt
                };
                if let (Some(m0), Some(ms)) = (self.m0, self.settle_mass) {
                    m.fuel_to_settle = m0.lane(i) - ms.lane(i);
                }
            }
            m.final_error = final_error;
            m.final_rate_error = final_rate_error;
            if let (Some(m0), Some(mf)) = (self.m0, mass) {
                m.fuel_used = m0.lane(i) - mf.lane(i);
            }
        }
    }
}

/// A block's touchdown ([`Block::locate_touchdown`]), run out of line through
/// [`LawCalls::out_of_line`] so that it is compiled with the level's instructions.
struct TouchDown<'a, 'b, const D: usize, R: Real, P: Plant<R, D>> {
    block: &'a mut Block<D, R, P>,
    set: &'a Setting<'b, D, R, P>,
    tj: f64,
    h: f64,
    z: (R, R),
    cross: R::Mask,
}

impl<const D: usize, R: Real, P: Plant<R, D>> OutOfLine<D, R> for TouchDown<'_, '_, D, R, P> {
    /// Whether any lane still runs.
    type Output = bool;

    #[inline(always)]
    fn run<K: LawCalls<D, R>>(self) -> bool {
        self.block
            .locate_touchdown(self.set, self.tj, self.h, self.z, self.cross)
    }
}

/// One control period of a block ([`Block::period`]), run out of line through
/// [`LawCalls::out_of_line`]: compiled once per plant and level, whichever driver calls it.
pub(crate) struct Period<'a, 'b, 'c, const D: usize, R: Real, P: Plant<R, D>> {
    pub block: &'a mut Block<D, R, P>,
    pub set: &'a Setting<'b, D, R, P>,
    pub k: u64,
    pub a: &'a SVector<R, D>,
    pub diag: &'a [R],
    pub out: &'a mut BlockBuffers<'c, D>,
}

impl<const D: usize, R: Real, P: Plant<R, D>> OutOfLine<D, R> for Period<'_, '_, '_, D, R, P> {
    /// Whether any lane still runs.
    type Output = bool;

    #[inline(always)]
    fn run<K: LawCalls<D, R>>(self) -> bool {
        self.block
            .period::<K>(self.set, self.k, self.a, self.diag, self.out)
    }
}

/// Simulates the cases of one block under a built-in law. Lane i is case `cases[i]`; the
/// first `used` lanes are real cases, the others padding whose results are dropped. Stops
/// early, with nothing written that matters, when `cancel` is raised.
#[inline(always)]
pub(crate) fn rollout_block<const D: usize, R: Real, P: Plant<R, D>, K: LawCalls<D, R>>(
    set: &Setting<'_, D, R, P>,
    law: &AnyLaw<D, R>,
    x0: &P::State,
    cases: &[u64],
    used: usize,
    cancel: &AtomicBool,
    out: &mut BlockBuffers<'_, D>,
) -> Result<(), Cancelled> {
    let cfg = set.cfg;
    let mut block = Block::start(set, x0, cases, used);
    let mut memory = K::start(law, block.input());
    let advances = law.has_memory();
    let nd = law.diagnostic_width();
    let mut diag = [R::zero(); MAX_DIAGNOSTIC_WIDTH];
    let poll_every = (CANCEL_POLL_STEPS / u64::from(cfg.substeps)).max(1);
    for k in 0..cfg.steps {
        if k % poll_every == 0 && cancel.load(Ordering::Relaxed) {
            return Err(Cancelled);
        }
        // the diagnostics read the memory the command reads; the memory is then advanced over
        // the period (it plays no part in the plant's step)
        if block.records(cfg, k) {
            K::diagnostics(law, &memory, block.input(), &mut diag[..nd]);
        }
        let a = if advances {
            K::command_and_advance(law, &mut memory, block.input())
        } else {
            K::command(law, &memory, block.input())
        };
        let period = Period {
            block: &mut block,
            set,
            k,
            a: &a,
            diag: &diag[..nd],
            out: &mut *out,
        };
        if !K::out_of_line(period) {
            break;
        }
    }
    let last = if block.any_live() {
        let a = K::command(law, &memory, block.input());
        if cfg.record_every > 0 {
            K::diagnostics(law, &memory, block.input(), &mut diag[..nd]);
        }
        Some(a)
    } else {
        None
    };
    block.finish(set, last.as_ref().map(|a| (a, &diag[..nd])), out);
    Ok(())
}
