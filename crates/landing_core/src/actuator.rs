//! The actuator between the law and the plant's limits: a transport delay of whole control
//! periods and a first-order lag.
//!
//! ```text
//! c_k   = u_(k - n)        the command issued n periods earlier (n = control_delay);
//!                          before the first one arrives, the plant's limits applied to 0
//! F' = (c_k - F) / tau     over period k, c_k held (tau = engine_time_constant)
//! applied = limit(F)       the plant's limits, imposed on the lag's output
//! ```
//!
//! The command `u_k` is the plant's actuated command (already within its limits), so the lag
//! filters a force the engine may give. Over a period the lag has the exact solution
//! `F(t_k + s) = c_k + (F_k - c_k) exp(-s / tau)`, evaluated at each stage of the integrator:
//! no state is added to the plant and no integration error enters the lag. The convex limits
//! (a magnitude ball, a pointing cone, a per-axis box) hold on every convex combination of
//! two forces inside them, as `F` is; the minimum throttle does not (the combination of two
//! forces in an annulus can cross the hole), hence `limit` on the lag's output. The lag starts
//! in steady state, `F_0 = c_0`: the engine is running at the descent's start, as at powered
//! descent initiation. The delay's idle command is Simulink's Transport Delay default (an
//! initial output of 0), passed through the limits (the least thrust up for an always-on
//! engine).

use nalgebra::SVector;

use crate::error::{ParamError, check};
use crate::lanes::{Real, add, scale_by, sub};
use crate::params::Param;

/// Longest control delay, periods: the delay keeps one command per period of it per block.
const MAX_DELAY: f64 = 1000.0;
/// The delay, as every plant with an actuator declares it.
pub const CONTROL_DELAY: Param = Param::scalar("control_delay")
    .unit("periods")
    .rule("control_delay an integer in [0, 1000]")
    .optional()
    .doc("the command's transport delay in whole control periods; None for none");
/// The lag's time constant, as every plant with an actuator declares it.
pub const ENGINE_TIME_CONSTANT: Param = Param::scalar("engine_time_constant")
    .unit("s")
    .rule("engine_time_constant >= 0")
    .optional()
    .doc("the engine's first-order lag time constant; None (or 0) for none");

/// A plant's actuator dynamics over lanes of cases.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ActuatorSpec<R> {
    /// Delay in whole control periods per lane (an integer value, >= 0).
    pub delay: R,
    /// Lag time constant per lane, s; 0 for none.
    pub time_constant: R,
}

impl ActuatorSpec<f64> {
    /// Checks one case's delay and time constant against their declared rules.
    pub fn validate(&self) -> Result<(), ParamError> {
        check(&CONTROL_DELAY, self.delay, |v| {
            (0.0..=MAX_DELAY).contains(&v) && v.fract() == 0.0
        })?;
        check(&ENGINE_TIME_CONSTANT, self.time_constant, |v| {
            (0.0..=f64::MAX).contains(&v)
        })
    }
}

/// The lag over one control period: the held input `c`, the lag's output `p` at the period's
/// start `t0`, and `1 / tau` (lanes without a lag have `tau = 0` and follow `c`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lag<const D: usize, R: Real> {
    c: SVector<R, D>,
    p: SVector<R, D>,
    inv_tau: R,
    lags: R::Mask,
    t0: f64,
}

impl<const D: usize, R: Real> Lag<D, R> {
    /// The lag's output at time `t` of the period (before the limits).
    #[inline(always)]
    pub(crate) fn at(&self, t: f64) -> SVector<R, D> {
        let w = R::select(
            self.lags,
            (R::splat(self.t0 - t) * self.inv_tau).exp(),
            R::zero(),
        );
        add(&self.c, &scale_by(&sub(&self.p, &self.c), w))
    }
}

/// The actuator's memory for a block of cases.
pub(crate) struct Actuator<const D: usize, R: Real> {
    // commands of the last `ring.len()` periods, period k at k % len; only with a delay
    ring: Vec<SVector<R, D>>,
    // per lane, its delay in periods
    delay: Vec<u64>,
    idle: SVector<R, D>,
    inv_tau: R,
    lags: R::Mask,
    any_lag: bool,
    // the lag's output at the coming period's start (None before the first)
    output: Option<SVector<R, D>>,
}

impl<const D: usize, R: Real> Actuator<D, R> {
    /// The actuator of a block whose lanes have `spec`; `idle` is what is applied before the
    /// first delayed command arrives. None when no lane delays or lags.
    pub(crate) fn new(spec: &ActuatorSpec<R>, idle: SVector<R, D>) -> Option<Self> {
        let delay: Vec<u64> = (0..R::LANES).map(|i| spec.delay.lane(i) as u64).collect();
        let longest = delay.iter().copied().max().unwrap_or(0);
        let tau = spec.time_constant;
        let lags = tau.simd_gt(R::zero());
        let any_lag = (0..R::LANES).any(|i| tau.lane(i) > 0.0);
        if longest == 0 && !any_lag {
            return None;
        }
        let ring = if longest > 0 {
            vec![idle; longest as usize + 1]
        } else {
            Vec::new()
        };
        Some(Self {
            ring,
            delay,
            idle,
            inv_tau: R::select(lags, R::one() / tau, R::zero()),
            lags,
            any_lag,
            output: None,
        })
    }

    /// The command that reaches the lag at instant k, `u` the one issued at k.
    fn delayed(&mut self, k: u64, u: &SVector<R, D>) -> SVector<R, D> {
        if self.ring.is_empty() {
            return *u;
        }
        let len = self.ring.len() as u64;
        self.ring[(k % len) as usize] = *u;
        let mut c = self.idle;
        for (i, &n) in self.delay.iter().enumerate() {
            if k >= n {
                let from = &self.ring[((k - n) % len) as usize];
                for a in 0..D {
                    c[a].set_lane(i, from[a].lane(i));
                }
            }
        }
        c
    }

    /// The start of period k at time `t`, `u` the command issued at k: the force the lag gives
    /// at the period's start (before the limits), and the lag over the period (None without a
    /// lag: the delayed command is then held as it is).
    pub(crate) fn begin(
        &mut self,
        k: u64,
        t: f64,
        u: &SVector<R, D>,
    ) -> (SVector<R, D>, Option<Lag<D, R>>) {
        let c = self.delayed(k, u);
        if !self.any_lag {
            return (c, None);
        }
        let p = *self.output.get_or_insert(c);
        let lag = Lag {
            c,
            p,
            inv_tau: self.inv_tau,
            lags: self.lags,
            t0: t,
        };
        (p, Some(lag))
    }

    /// The end of a period at time `t`: the lag's output there starts the next one.
    pub(crate) fn end(&mut self, lag: &Lag<D, R>, t: f64) {
        self.output = Some(lag.at(t));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector1;

    #[test]
    fn a_delay_of_n_periods_shifts_the_commands_by_n() {
        let spec = ActuatorSpec {
            delay: 3.0,
            time_constant: 0.0,
        };
        let mut a = Actuator::<1, f64>::new(&spec, Vector1::new(-1.0)).unwrap();
        let got: Vec<f64> = (0..8)
            .map(|k| a.begin(k, 0.0, &Vector1::new(k as f64 * 10.0)).0[0])
            .collect();
        assert_eq!(got, [-1.0, -1.0, -1.0, 0.0, 10.0, 20.0, 30.0, 40.0]);
    }

    #[test]
    fn the_lag_follows_its_exponential_and_starts_in_steady_state() {
        let spec = ActuatorSpec {
            delay: 0.0,
            time_constant: 0.5,
        };
        let mut a = Actuator::<1, f64>::new(&spec, Vector1::zeros()).unwrap();
        let (p, lag) = a.begin(0, 0.0, &Vector1::new(2.0));
        assert_eq!(p[0], 2.0);
        a.end(&lag.unwrap(), 0.1);
        // a step from 2 to 5 at t = 0.1: F = 5 - 3 exp(-(t - 0.1) / 0.5)
        let (p, lag) = a.begin(1, 0.1, &Vector1::new(5.0));
        assert_eq!(p[0], 2.0);
        let lag = lag.unwrap();
        for s in [0.0, 0.05, 0.1] {
            let want = 5.0 - 3.0 * (-s / 0.5f64).exp();
            assert!((lag.at(0.1 + s)[0] - want).abs() < 1e-15, "{s}");
        }
    }

    #[test]
    fn nothing_delayed_or_lagged_is_no_actuator() {
        let spec = ActuatorSpec {
            delay: 0.0,
            time_constant: 0.0,
        };
        assert!(Actuator::<3, f64>::new(&spec, SVector::zeros()).is_none());
    }
}
