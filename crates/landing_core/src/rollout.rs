//! One case, sampled-data (SPEC section 2).
//!
//! At each control instant t_k = k dt the law reads x_k and the reference at t_k; the command
//! is actuated (scaled, saturated) and held over [t_k, t_k + dt); the law's memory is advanced;
//! the random part of the disturbance is drawn for period k and held; the plant is advanced by
//! `substeps` steps of the integrator, whose stages see the deterministic disturbance at their
//! own times. No heap allocation happens inside the step loop.

use std::cell::Cell;

use nalgebra::SVector;

use crate::control::{ControlLaw, LawInput};
use crate::disturbance::{Disturbance, disturbance_stream};
use crate::error::ParamError;
use crate::integrator::Integrator;
use crate::metrics::{CaseMetrics, CommandStats, HighPass, Touchdown};
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
    /// Cut-off frequency (Hz) of the high-pass filter behind the chattering metric; NaN for
    /// a tenth of the Nyquist frequency, 1 / (20 dt).
    pub chatter_cutoff: f64,
}

/// Largest number of control periods a batch may ask for (keeps k dt exact in f64 terms of
/// the integer counter and guards against an accidental t_final / dt of 1e15).
pub const MAX_STEPS: u64 = 1 << 40;

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
            chatter_cutoff: f64::NAN,
        })
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
            e => (self.steps / e + 1 + u64::from(self.steps % e != 0)) as usize,
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

/// Where one case writes its recording; the slices are empty when nothing is recorded.
pub struct CaseBuffers<'a> {
    /// n_records x state dim.
    pub states: &'a mut [f64],
    /// n_records x D.
    pub controls: &'a mut [f64],
    /// n_records x (number of diagnostics x D).
    pub diagnostics: &'a mut [f64],
    /// state dim.
    pub final_state: &'a mut [f64],
}

/// Builds what the law sees at (t, x).
#[inline(always)]
fn law_input<const D: usize, P: Plant<D>>(
    plant: &P,
    reference: &Reference<D>,
    t: f64,
    dt: f64,
    x: &P::State,
) -> LawInput<D> {
    let (q, qd) = plant.coordinates(x);
    let r = reference.at(t);
    LawInput {
        t,
        dt,
        e: q - r.position,
        de: qd - r.velocity,
        reference: r,
        drift: plant.modelled_acceleration(t, x),
        inertia: plant.inertia(x),
    }
}

/// Writes record `slot`.
#[inline(always)]
fn record<const D: usize, S: State, L: ControlLaw<D>>(
    out: &mut CaseBuffers<'_>,
    slot: usize,
    x: &S,
    u: &SVector<f64, D>,
    law: &L,
    memory: &L::Memory,
    input: &LawInput<D>,
) {
    let nx = S::DIM;
    let nd = crate::control::diagnostic_width::<D, L>();
    out.states[slot * nx..(slot + 1) * nx].copy_from_slice(x.as_slice());
    out.controls[slot * D..(slot + 1) * D].copy_from_slice(u.as_slice());
    law.diagnostics(
        memory,
        input,
        &mut out.diagnostics[slot * nd..(slot + 1) * nd],
    );
}

/// Simulates one case and returns its metrics; the recording goes into `out`. `case` is the
/// global case index that keys the random streams.
#[allow(clippy::too_many_arguments)]
pub fn rollout<const D: usize, P, L, I>(
    plant: &P,
    law: &L,
    integrator: I,
    x0: &P::State,
    reference: &Reference<D>,
    disturbance: &Disturbance<D>,
    cfg: &SimConfig,
    case: u64,
    mut out: CaseBuffers<'_>,
) -> CaseMetrics<D>
where
    P: Plant<D>,
    L: ControlLaw<D>,
    I: Integrator,
{
    let recording = cfg.record_every > 0;
    let rng = disturbance_stream(cfg.seed, case);
    let h = cfg.dt / f64::from(cfg.substeps);
    let mut metrics = CaseMetrics::new();
    let mut stats = CommandStats::new(cfg.chatter_filter());

    let mut x = *x0;
    let m0 = plant.mass(&x);
    let mut input = law_input(plant, reference, 0.0, cfg.dt, &x);
    let mut memory = law.start(&input);
    let mut slot = 0usize;
    let mut next_record = 0u64;
    let tolerance = match cfg.settle {
        Tolerance::Absolute(v) => v,
        Tolerance::Relative(f) => f * input.e.norm(),
    };
    // compared squared: no square root per step
    let tolerance_sq = tolerance * tolerance;
    // the last control instant at which |e| was outside the tolerance, and the mass at the
    // instant after it (the settle instant, should the error stay inside from there on)
    let mut last_outside: Option<u64> = None;
    let mut settle_mass = m0;
    let mut was_outside = false;

    'periods: for k in 0..cfg.steps {
        let t = k as f64 * cfg.dt;
        let u = plant.actuate(&x, &law.command(&memory, &input));
        if !u.iter().all(|v| v.is_finite()) {
            metrics.diverged_at = Some(t);
            break;
        }
        if recording && k == next_record {
            record(&mut out, slot, &x, &u, law, &memory, &input);
            slot += 1;
            next_record += cfg.record_every;
        }
        stats.add(&u, &input.e, cfg.dt);
        if input.e.norm_squared() > tolerance_sq {
            last_outside = Some(k);
            was_outside = true;
        } else if was_outside {
            settle_mass = plant.mass(&x);
            was_outside = false;
        }

        let held = disturbance.draw(&rng, k, &u.component_div(&input.inertia));
        law.advance(&mut memory, &input);
        // RK4's two middle stages share a time: remember the last disturbance evaluated
        // (a pure function of time, so this changes no result).
        let last = Cell::new((f64::NAN, SVector::<f64, D>::zeros()));
        let f = |tau: f64, y: &P::State| {
            let (t_last, d_last) = last.get();
            let d = if tau == t_last {
                d_last
            } else {
                let d = disturbance.at(tau, &held);
                last.set((tau, d));
                d
            };
            plant.derivative(tau, y, &u, &d)
        };
        for j in 0..cfg.substeps {
            let tj = t + f64::from(j) * h;
            let next = integrator.step(&f, tj, &x, h);
            if metrics.touchdown.is_none() {
                if let (Some(z0), Some(z1)) = (plant.altitude(&x), plant.altitude(&next)) {
                    if z0 > 0.0 && z1 <= 0.0 {
                        let w = z0 / (z0 - z1);
                        let (q0, v0) = plant.coordinates(&x);
                        let (q1, v1) = plant.coordinates(&next);
                        metrics.touchdown = Some(Touchdown {
                            time: tj + w * h,
                            position: q0 + (q1 - q0) * w,
                            velocity: v0 + (v1 - v0) * w,
                        });
                    }
                }
            }
            x = next;
            if !plant.admissible(&x) {
                metrics.diverged_at = Some(tj + h);
                break 'periods;
            }
        }
        input = law_input(plant, reference, (k + 1) as f64 * cfg.dt, cfg.dt, &x);
    }

    if metrics.diverged_at.is_none() {
        // The command at t_final is recorded (it is what would be held next) but not applied.
        let u = plant.actuate(&x, &law.command(&memory, &input));
        if u.iter().all(|v| v.is_finite()) {
            if recording {
                record(&mut out, slot, &x, &u, law, &memory, &input);
                slot += 1;
            }
            out.final_state.copy_from_slice(x.as_slice());
            if input.e.norm_squared() <= tolerance_sq {
                if was_outside {
                    settle_mass = plant.mass(&x);
                }
                metrics.settle_time = last_outside.map_or(0.0, |k| (k + 1) as f64 * cfg.dt);
                if let (Some(m0), Some(ms)) = (m0, settle_mass) {
                    metrics.fuel_to_settle = m0 - ms;
                }
            }
            metrics.final_error = input.e;
            metrics.final_rate_error = input.de;
            if let (Some(m0), Some(m)) = (m0, plant.mass(&x)) {
                metrics.fuel_used = m0 - m;
            }
        } else {
            metrics.diverged_at = Some(cfg.t_final());
        }
    }
    stats.finish_into(&mut metrics);
    if metrics.diverged_at.is_some() {
        // A diverged case reads NaN from its divergence on, and is flagged in its metrics.
        let nx = P::State::DIM;
        let nd = crate::control::diagnostic_width::<D, L>();
        out.states[slot * nx..].fill(f64::NAN);
        out.controls[slot * D..].fill(f64::NAN);
        out.diagnostics[slot * nd..].fill(f64::NAN);
        out.final_state.fill(f64::NAN);
    }
    metrics
}
