//! What the law sees: a sensor's measurement of the coordinates and their rates, and
//! optionally a Kalman filter between the sensor and the law.
//!
//! ```text
//! y_k   = [q_k; q'_k] + b + w_k + sigma n_k       the measurement at control instant k
//! w_0   = 0,  w_(k+1) = w_k + rho sqrt(dt) m_k    the random walk (rho: unit / sqrt(s))
//! ```
//!
//! per component of `[q; q']` (2 D components: the D coordinates, then their D rates), with
//! `n_k`, `m_k` independent standard normals drawn from the case's own counter-based stream
//! ([`crate::rng::streams::SENSOR`], counter `k D + j`): a case's measurements do not depend on
//! the thread count, the block or the chunking. `b` is a constant bias.
//!
//! The filter is the discrete Kalman filter of the per-axis double integrator with the
//! plant's model: between instants the acceleration is the command applied at t_k over the
//! inertia plus the plant's modelled acceleration at the estimate, held over the period, and
//! the unknown part is white, held over the period, of standard deviation `process_noise`
//! (the piecewise-constant white-noise acceleration model, Bar-Shalom, Li and Kirubarajan,
//! "Estimation with Applications to Tracking and Navigation", 2001, section 6.3.3):
//!
//! ```text
//! x = [q_i; q'_i],  F = [1 dt; 0 1],  G = [dt^2/2; dt],  Q = s_i^2 G G^T
//! predict   x- = F x + G a_k,           P- = F P F^T + Q
//! update    K = P- (P- + R)^-1,  x = x- + K (y - x-),  P = (I - K) P-
//! ```
//!
//! with `R = diag(sigma_q_i^2, sigma_q'_i^2)` (the white part only: the filter does not model
//! the bias or the walk). It starts from the first measurement, `x_0 = y_0`, `P_0 = R`. Where
//! the plant is the double integrator and the unknown acceleration is held white noise, this
//! is the optimal linear estimator and its covariance converges to the discrete Riccati
//! equation's solution (the tests check both).
//!
//! The law then reads the estimate in place of the true coordinates; its drift and inertia are
//! the plant's at the estimated coordinates (the other state components, a lander's mass, are
//! taken as known). The metrics, the events and the physics keep reading the true state.

use nalgebra::SVector;

use crate::error::{ParamError, ReadError};
use crate::lanes::{Mask, Real, add, div, dot, scale, sub};
use crate::metrics::NavigationMetrics;
use crate::params::{Layout, Param, ParamSource, Schema};
use crate::rng::{CaseStream, LanePairs, streams};

const STD: Param = Param::components("std")
    .per_case()
    .unit("units of q, then q/s")
    .rule("std >= 0")
    .doc("standard deviation of the white noise per component of [q, q'] (a scalar serves all)");
const BIAS: Param = Param::components("bias")
    .per_case()
    .unit("units of q, then q/s")
    .doc("constant bias per component of [q, q']");
const RANDOM_WALK: Param = Param::components("random_walk")
    .per_case()
    .unit("units of q/sqrt(s), then q/s/sqrt(s)")
    .rule("random_walk >= 0")
    .doc("random-walk density per component of [q, q']: the walk's variance grows as random_walk^2 t");
const PROCESS_NOISE: Param = Param::components("process_noise")
    .per_case()
    .unit("units of q/s^2")
    .rule("process_noise >= 0")
    .doc("standard deviation per axis of the unknown acceleration the filter assumes, held over each control period");

/// The sensor a plant carries (None: the law reads the true state).
pub const SENSOR: Param = Param::nested("sensor", Layout::Family("sensor"))
    .optional()
    .doc("the sensor between the plant and the law (landing.sensors.Noise); None for none");
/// The filter between the sensor and the law.
pub const FILTER: Param = Param::nested("filter", Layout::Family("filter"))
    .optional()
    .doc("the estimator between the sensor and the law (landing.sensors.KalmanFilter); None for none");

crate::named! {
    /// The sensors' kinds at the Python boundary.
    pub enum SensorKind in "sensor" {
        Noise => "noise": Schema::new(&[STD, BIAS, RANDOM_WALK]),
    }
}

crate::named! {
    /// The filters' kinds at the Python boundary.
    pub enum FilterKind in "filter" {
        Kalman => "kalman": Schema::new(&[PROCESS_NOISE]),
    }
}

/// A sensor's error model and the optional filter: one case's (`R = f64`), or a block's with
/// each lane its case's values (every number may differ between cases; whether there is a
/// filter is the block's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Navigation<const D: usize, R = f64> {
    /// White-noise standard deviation of q and of q'.
    pub std: [SVector<R, D>; 2],
    pub bias: [SVector<R, D>; 2],
    pub random_walk: [SVector<R, D>; 2],
    /// The filter's process noise per axis, when there is a filter.
    pub process_noise: Option<SVector<R, D>>,
}

crate::gather_struct!(Navigation<const D: usize, R> {
    lanes: [std, bias, random_walk, process_noise],
    shared: [],
});

/// `values` checked against `p`'s rule (finite; >= 0 when it has a rule) and spread to `N`
/// values (a single one serves all): `what` says what the N are, for the message, and
/// `first` is the index a refusal names for `values[0]`.
fn spread<const N: usize>(
    p: &Param,
    values: &[f64],
    (what, first): (&str, usize),
) -> Result<SVector<f64, N>, ReadError> {
    let n = values.len();
    if n != 1 && n != N {
        return Err(ReadError::value(format!(
            "{} has {n} values; it takes one, or {N} ({what})",
            p.name
        )));
    }
    for (c, &v) in values.iter().enumerate() {
        if !v.is_finite() || (!p.rule.is_empty() && v < 0.0) {
            let rule = if p.rule.is_empty() { "finite" } else { p.rule };
            return Err(ParamError::new(p.name, v, rule).on_axis(first + c).into());
        }
    }
    Ok(SVector::from_fn(|i, _| values[if n == 1 { 0 } else { i }]))
}

/// `values` (one, or one per component of `[q, q']`) as the q and q' parts.
fn split<const D: usize>(p: &Param, values: &[f64]) -> Result<[SVector<f64, D>; 2], ReadError> {
    let what = format!("the {D} coordinates, then their rates");
    // 2 D values: a const generic 2 D is not expressible, so the two halves are read apart
    if values.len() == 2 * D {
        Ok([
            spread(p, &values[..D], (&what, 0))?,
            spread(p, &values[D..], (&what, D))?,
        ])
    } else if values.len() == 1 {
        let v = spread(p, values, (&what, 0))?;
        Ok([v, v])
    } else {
        Err(ReadError::value(format!(
            "{} has {} values; it takes one, or {} ({what})",
            p.name,
            values.len(),
            2 * D
        )))
    }
}

impl<const D: usize> Navigation<D> {
    /// The plant's `sensor` and `filter` tables, if it has a sensor. Every value is read
    /// before any is checked, so that a reading names each parameter it meets.
    pub fn read<S: ParamSource>(p: &mut S) -> Result<Option<Self>, ReadError> {
        let sensor = p.opt_nested(&SENSOR, |s| {
            let SensorKind::Noise = s.kind::<SensorKind>()?;
            Ok([
                s.case_components(&STD)?,
                s.case_components(&BIAS)?,
                s.case_components(&RANDOM_WALK)?,
            ])
        })?;
        let filter = p.opt_nested(&FILTER, |f| {
            let FilterKind::Kalman = f.kind::<FilterKind>()?;
            f.case_components(&PROCESS_NOISE)
        })?;
        let filter = filter
            .map(|v| spread::<D>(&PROCESS_NOISE, &v, ("one per axis", 0)))
            .transpose()
            .map_err(|e| e.context(FILTER.name))?;
        let sensor = sensor
            .map(|[std, bias, walk]| {
                Ok::<_, ReadError>((
                    split::<D>(&STD, &std)?,
                    split::<D>(&BIAS, &bias)?,
                    split::<D>(&RANDOM_WALK, &walk)?,
                ))
            })
            .transpose()
            .map_err(|e| e.context(SENSOR.name))?;
        let Some((std, bias, random_walk)) = sensor else {
            return match filter {
                Some(_) => Err(ReadError::value(
                    "filter needs a sensor (the filter estimates from its measurements)",
                )),
                None => Ok(None),
            };
        };
        if filter.is_some() {
            // R = diag(std^2) must be invertible for the update
            for (c, &s) in std[0].iter().chain(std[1].iter()).enumerate() {
                if s <= 0.0 {
                    let rule = "std > 0 on every component when there is a filter";
                    return Err(ParamError::new(STD.name, s, rule).on_axis(c).into());
                }
            }
        }
        Ok(Some(Self {
            std,
            bias,
            random_walk,
            process_noise: filter,
        }))
    }
}

/// A 2 x 2 symmetric covariance per axis: [[pp, pv], [pv, vv]].
#[derive(Clone, Copy, Debug)]
struct Covariance<const D: usize, R: Real> {
    pp: SVector<R, D>,
    pv: SVector<R, D>,
    vv: SVector<R, D>,
}

/// The navigation of a block of cases: the sensor's walk, the filter's estimate and
/// covariance, and the error statistics. It reads the true coordinates and rates and gives the
/// estimate; the block builds the law's input from it ([`crate::rollout`]).
pub(crate) struct Navigator<const D: usize, R: Real> {
    streams: Vec<CaseStream>,
    std: [SVector<R, D>; 2],
    bias: [SVector<R, D>; 2],
    // rho sqrt(dt)
    step: [SVector<R, D>; 2],
    walk: [SVector<R, D>; 2],
    // the filter: process noise variance, estimate, covariance
    filter: Option<(SVector<R, D>, Covariance<D, R>)>,
    estimate: [SVector<R, D>; 2],
    // the acceleration the filter predicts with over the coming period
    acceleration: SVector<R, D>,
    dt: f64,
    sum_sq: [R; 2],
    instants: R,
    error: [SVector<R, D>; 2],
}

impl<const D: usize, R: Real> Navigator<D, R> {
    /// The navigation of the block whose lane i is case `cases[i]`, at t = 0 where the true
    /// coordinates and rates are `(q, v)`: the first measurement taken, the error there counted.
    pub(crate) fn start(
        nav: &Navigation<D, R>,
        (seed, cases, dt): (u64, &[u64], f64),
        (q, v): (&SVector<R, D>, &SVector<R, D>),
    ) -> Self {
        let zero = crate::lanes::zeros();
        let root_dt = dt.sqrt();
        let std = nav.std;
        let mut n = Self {
            streams: cases
                .iter()
                .map(|&c| CaseStream::new(seed, streams::SENSOR, c))
                .collect(),
            std,
            bias: nav.bias,
            step: [
                scale(&nav.random_walk[0], root_dt),
                scale(&nav.random_walk[1], root_dt),
            ],
            walk: [zero; 2],
            filter: nav.process_noise.map(|s| {
                let q = SVector::from_fn(|i, _| s[i] * s[i]);
                // P_0 = R
                let r = |c: usize| SVector::from_fn(|i, _| std[c][i] * std[c][i]);
                (
                    q,
                    Covariance {
                        pp: r(0),
                        pv: zero,
                        vv: r(1),
                    },
                )
            }),
            estimate: [zero; 2],
            acceleration: zero,
            dt,
            sum_sq: [R::zero(); 2],
            instants: R::zero(),
            error: [zero; 2],
        };
        n.estimate = n.measure(0, q, v);
        n.count(R::Mask::splat(true), q, v);
        n
    }

    /// The measurement at instant k of the coordinates and rates `(q, v)`; advances the walk
    /// to instant k + 1.
    #[inline(always)]
    fn measure(&mut self, k: u64, q: &SVector<R, D>, v: &SVector<R, D>) -> [SVector<R, D>; 2] {
        // 4 D normals per instant: the white noise of [q, q'], then the walk's steps; each
        // lane's D blocks of four words (counters k D .. k D + D - 1), Box-Muller on every
        // lane at once (the lanes past the block's cases stay at 0)
        let mut pairs = [[LanePairs::<R>::new(); 2]; D];
        for (lane, s) in self.streams.iter().enumerate().take(R::LANES) {
            for (j, p) in pairs.iter_mut().enumerate() {
                let w = s.block(k * D as u64 + j as u64);
                p[0].set(lane, w[0], w[1]);
                p[1].set(lane, w[2], w[3]);
            }
        }
        let mut one = [[R::zero(); 4]; D];
        for (block, p) in one.iter_mut().zip(&pairs) {
            let ((z0, z1), (z2, z3)) = (p[0].normals(), p[1].normals());
            *block = [z0, z1, z2, z3];
        }
        let z = |c: usize| one[c / 4][c % 4];
        let mut white: [SVector<R, D>; 2] = [crate::lanes::zeros(); 2];
        let mut steps = white;
        for i in 0..D {
            white[0][i] = z(i);
            white[1][i] = z(D + i);
            steps[0][i] = z(2 * D + i);
            steps[1][i] = z(3 * D + i);
        }
        let truth = [*q, *v];
        let mut y = truth;
        for c in 0..2 {
            for i in 0..D {
                y[c][i] =
                    truth[c][i] + self.bias[c][i] + self.walk[c][i] + self.std[c][i] * white[c][i];
                self.walk[c][i] += self.step[c][i] * steps[c][i];
            }
        }
        y
    }

    /// Holds the acceleration the filter predicts with over the coming period: the command
    /// applied at its start (`u`, in actuator units) over the inertia, plus the modelled
    /// acceleration, both as the law saw them.
    #[inline]
    pub(crate) fn hold(
        &mut self,
        u: &SVector<R, D>,
        inertia: &SVector<R, D>,
        drift: &SVector<R, D>,
    ) {
        self.acceleration = add(&div(u, inertia), drift);
    }

    /// Counts the navigation error at the instant just measured, in the lanes `live`.
    #[inline(always)]
    fn count(&mut self, live: R::Mask, q: &SVector<R, D>, v: &SVector<R, D>) {
        let e = [sub(&self.estimate[0], q), sub(&self.estimate[1], v)];
        for (c, ec) in e.iter().enumerate() {
            self.sum_sq[c] = R::select(live, self.sum_sq[c] + dot(ec, ec), self.sum_sq[c]);
            self.error[c] = crate::lanes::select_vector(live, ec, &self.error[c]);
        }
        self.instants = R::select(live, self.instants + R::one(), self.instants);
    }

    /// Control instant k, where the true coordinates and rates are `(q, v)`: the measurement,
    /// the filter's prediction and update (or the measurement as it is), and the error counted
    /// in the lanes `live`.
    #[inline(always)]
    pub(crate) fn advance(
        &mut self,
        k: u64,
        (q, v): (&SVector<R, D>, &SVector<R, D>),
        live: R::Mask,
    ) {
        let y = self.measure(k, q, v);
        self.estimate = match self.filter.as_mut() {
            None => y,
            Some((q, p)) => {
                let dt = R::splat(self.dt);
                let half_dt2 = R::splat(0.5 * self.dt * self.dt);
                let mut xq = self.estimate[0];
                let mut xv = self.estimate[1];
                for i in 0..D {
                    let a = self.acceleration[i];
                    // predict
                    let mq = xq[i] + xv[i] * dt + a * half_dt2;
                    let mv = xv[i] + a * dt;
                    let (g1, g2) = (half_dt2, dt);
                    let pp =
                        p.pp[i] + dt * (p.pv[i] + p.pv[i]) + dt * dt * p.vv[i] + q[i] * g1 * g1;
                    let pv = p.pv[i] + dt * p.vv[i] + q[i] * g1 * g2;
                    let vv = p.vv[i] + q[i] * g2 * g2;
                    // update: S = P- + R, K = P- S^-1
                    let (rq, rv) = (
                        self.std[0][i] * self.std[0][i],
                        self.std[1][i] * self.std[1][i],
                    );
                    let (s11, s12, s22) = (pp + rq, pv, vv + rv);
                    let inv_det = R::one() / (s11 * s22 - s12 * s12);
                    let k11 = (pp * s22 - pv * s12) * inv_det;
                    let k12 = (pv * s11 - pp * s12) * inv_det;
                    let k21 = (pv * s22 - vv * s12) * inv_det;
                    let k22 = (vv * s11 - pv * s12) * inv_det;
                    let (nq, nv) = (y[0][i] - mq, y[1][i] - mv);
                    xq[i] = mq + k11 * nq + k12 * nv;
                    xv[i] = mv + k21 * nq + k22 * nv;
                    // P = (I - K) P-, symmetric by construction up to rounding: its two
                    // off-diagonal terms averaged
                    let one = R::one();
                    p.pp[i] = (one - k11) * pp - k12 * pv;
                    let pv_a = (one - k11) * pv - k12 * vv;
                    let pv_b = -k21 * pp + (one - k22) * pv;
                    p.pv[i] = (pv_a + pv_b) * R::splat(0.5);
                    p.vv[i] = -k21 * pv + (one - k22) * vv;
                }
                [xq, xv]
            }
        };
        self.count(live, q, v);
    }

    /// The estimate the law reads at the coming instant, `[q_hat, q'_hat]`.
    #[inline]
    pub(crate) fn estimate(&self) -> &[SVector<R, D>; 2] {
        &self.estimate
    }

    /// Lane i's figures.
    pub(crate) fn metrics(&self, i: usize) -> NavigationMetrics<D> {
        let n = self.instants.lane(i);
        NavigationMetrics {
            position_error: SVector::from_fn(|c, _| self.error[0][c].lane(i)),
            velocity_error: SVector::from_fn(|c, _| self.error[1][c].lane(i)),
            position_rms: (self.sum_sq[0].lane(i) / n).sqrt(),
            velocity_rms: (self.sum_sq[1].lane(i) / n).sqrt(),
        }
    }
}
