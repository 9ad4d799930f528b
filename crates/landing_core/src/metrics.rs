//! Per-case figures of merit, accumulated during a rollout without storing its history.

use nalgebra::SVector;

use crate::lanes::{Mask, Real, abs, add, mul, norm, scale, scale_by, select_vector, sub, zeros};

/// First crossing of the landing surface (altitude from positive to non-positive),
/// interpolated linearly within the integrator step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Touchdown<const D: usize> {
    pub time: f64,
    pub position: SVector<f64, D>,
    pub velocity: SVector<f64, D>,
}

/// Per-case figures of the navigation error `estimate - truth` (what the law read minus the
/// true coordinates and rates), for a plant with a sensor ([`crate::navigation`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NavigationMetrics<const D: usize> {
    /// At the case's last control instant (t_final, or the instant before its event).
    pub position_error: SVector<f64, D>,
    pub velocity_error: SVector<f64, D>,
    /// Root mean square over the control instants of |q_hat - q| and |q'_hat - q'|.
    pub position_rms: f64,
    pub velocity_rms: f64,
}

/// Why a case was stopped before t_final.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum Divergence {
    /// The law returned a NaN or infinite command.
    NonFiniteCommand = 1,
    /// A component of the applied command exceeded [`MAX_COMMAND`] in magnitude: beyond it the
    /// command statistics (sums of u^2 over up to 2^40 periods) could overflow.
    CommandOutOfRange = 2,
    /// The state became NaN or infinite.
    NonFiniteState = 3,
    /// The state left the plant's domain ([`crate::plant::Plant::in_domain`]): no mass left,
    /// beyond the plant's range, inside a singularity, or a component beyond [`MAX_STATE`] in
    /// magnitude (every plant's).
    OutOfDomain = 4,
    /// A metric accumulated over the run, or the final error's norm, is not finite (a safety
    /// net: the bounds on the command and the state make this impossible but for a reference
    /// beyond [`MAX_STATE`]).
    NonFiniteMetric = 5,
}

/// Largest magnitude of a command component that a case may apply (see
/// [`Divergence::CommandOutOfRange`]); 1e100 is far beyond any physical actuator, and its
/// square summed over 2^40 periods is still finite.
pub const MAX_COMMAND: f64 = 1e100;

/// Largest magnitude of a state component a case may reach, whatever the plant: beyond it a
/// finite state could give infinite errors and metrics (|e|^2 of a 1e200 m position overflows),
/// so the case stops there as [`Divergence::OutOfDomain`]. Like [`MAX_COMMAND`], far beyond any
/// physical plant (docs/parameters.md).
pub const MAX_STATE: f64 = 1e100;

impl Divergence {
    /// The reason codes' names, indexed by code (0: not diverged).
    pub const NAMES: [&'static str; 6] = [
        "none",
        "non_finite_command",
        "command_out_of_range",
        "non_finite_state",
        "out_of_domain",
        "non_finite_metric",
    ];

    pub fn code(self) -> u8 {
        self as u8
    }

    pub fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    pub fn from_code(code: u8) -> Option<Self> {
        [
            Self::NonFiniteCommand,
            Self::CommandOutOfRange,
            Self::NonFiniteState,
            Self::OutOfDomain,
            Self::NonFiniteMetric,
        ]
        .into_iter()
        .find(|d| d.code() == code)
    }
}

/// When and why a case was stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diverged {
    /// The control instant of a bad command, the end of the integrator step that left the
    /// domain, or t_final for a metric found non-finite at the end.
    pub time: f64,
    pub reason: Divergence,
}

/// Per-case figures of merit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CaseMetrics<const D: usize> {
    /// e(t_final) = q - q_ref; NaN if the case diverged.
    pub final_error: SVector<f64, D>,
    /// e'(t_final); NaN if the case diverged.
    pub final_rate_error: SVector<f64, D>,
    /// m(0) - m(t_final) for plants with mass, else NaN.
    pub fuel_used: f64,
    /// m(0) - m(settle_time): the propellant spent until the error settles (landing), for
    /// plants with mass; NaN if it does not settle.
    pub fuel_to_settle: f64,
    /// max over applied commands of |u| (Euclidean).
    pub peak_command: f64,
    /// max over applied commands of |u_i|, per axis.
    pub peak_command_axis: SVector<f64, D>,
    /// integral of |u| dt over the applied commands.
    pub control_effort: f64,
    /// First control instant from which |e| stays within the settle tolerance until t_final
    /// (0 if it always was; NaN if it is outside at t_final or the case diverged). The "time
    /// to track" of seed 000.
    pub settle_time: f64,
    /// Integral of |e_i| dt over the control periods (rectangle rule at the control instants),
    /// per axis: the integrated absolute tracking error.
    pub iae: SVector<f64, D>,
    /// Total variation of the applied command per unit time, sum_k |u_i(k+1) - u_i(k)| / T,
    /// per axis: how much the command moves (chattering moves it a lot).
    pub command_variation: SVector<f64, D>,
    /// Energy of the applied command above the chattering cut-off (a 2nd-order Butterworth
    /// high-pass, sum_k hp_i(k)^2) over its total energy (sum_k u_i(k)^2), per axis.
    pub high_frequency_share: SVector<f64, D>,
    /// The same share over all axes together.
    pub high_frequency_share_total: f64,
    pub touchdown: Option<Touchdown<D>>,
    /// The navigation error, for a plant with a sensor ([`crate::navigation`]).
    pub navigation: Option<NavigationMetrics<D>>,
    /// Set when the case was stopped before t_final: its metrics are those of the instant it
    /// stopped (final errors and fuel NaN).
    pub diverged: Option<Diverged>,
}

impl<const D: usize> Default for CaseMetrics<D> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const D: usize> CaseMetrics<D> {
    pub fn new() -> Self {
        Self {
            final_error: SVector::repeat(f64::NAN),
            final_rate_error: SVector::repeat(f64::NAN),
            fuel_used: f64::NAN,
            fuel_to_settle: f64::NAN,
            peak_command: 0.0,
            peak_command_axis: zeros(),
            control_effort: 0.0,
            settle_time: f64::NAN,
            iae: zeros(),
            command_variation: zeros(),
            high_frequency_share: SVector::repeat(f64::NAN),
            high_frequency_share_total: f64::NAN,
            touchdown: None,
            navigation: None,
            diverged: None,
        }
    }
}

/// How a metric column reads one case's metrics.
#[derive(Clone, Copy)]
pub enum Read<const D: usize> {
    /// A number per case (float64).
    Scalar(fn(&CaseMetrics<D>) -> f64),
    /// A number per case and axis (float64).
    Axes(fn(&CaseMetrics<D>) -> SVector<f64, D>),
    /// A flag per case (bool).
    Flag(fn(&CaseMetrics<D>) -> bool),
    /// A code per case (uint8).
    Code(fn(&CaseMetrics<D>) -> u8),
}

/// One metric column of a batch's output: declared once here, with its unit, and computed
/// from the cases' [`CaseMetrics`].
#[derive(Clone, Copy)]
pub struct Column<const D: usize> {
    pub name: &'static str,
    /// SI unit; "units of q" where it is the plant's generalized coordinate's (m for the
    /// landers, rad for the tethered satellite), "command units" the applied command's (N on
    /// the Mars lander, m/s^2 on the small body), "" for a flag or a code.
    pub unit: &'static str,
    pub doc: &'static str,
    pub read: Read<D>,
}

/// A column's values for every case: cases (x axes, row-major) values.
#[derive(Clone, Debug, PartialEq)]
pub enum ColumnValues {
    Scalar(Vec<f64>),
    Axes(Vec<f64>),
    Flag(Vec<bool>),
    Code(Vec<u8>),
}

impl<const D: usize> Column<D> {
    const fn new(name: &'static str, unit: &'static str, doc: &'static str, read: Read<D>) -> Self {
        Self {
            name,
            unit,
            doc,
            read,
        }
    }

    pub fn per_axis(&self) -> bool {
        matches!(self.read, Read::Axes(_))
    }

    /// The column over `cases`.
    pub fn values(&self, cases: &[CaseMetrics<D>]) -> ColumnValues {
        match self.read {
            Read::Scalar(f) => ColumnValues::Scalar(cases.iter().map(f).collect()),
            Read::Axes(f) => {
                let mut v = Vec::with_capacity(cases.len() * D);
                for m in cases {
                    v.extend_from_slice(f(m).as_slice());
                }
                ColumnValues::Axes(v)
            }
            Read::Flag(f) => ColumnValues::Flag(cases.iter().map(f).collect()),
            Read::Code(f) => ColumnValues::Code(cases.iter().map(f).collect()),
        }
    }
}

const NAN: f64 = f64::NAN;

impl<const D: usize> CaseMetrics<D> {
    /// The per-case metric columns, in output order. A new metric is its field above, its
    /// accumulation (in [`CommandStats`] or the rollout) and its line here.
    pub const COLUMNS: &'static [Column<D>] = &[
        Column::new(
            "final_position_error",
            "units of q",
            "|e(t_final)|, the norm of the tracking error at t_final",
            Read::Scalar(|m| m.final_error.norm()),
        ),
        Column::new(
            "final_velocity_error",
            "units of q/s",
            "|e'(t_final)|, the norm of the rate error",
            Read::Scalar(|m| m.final_rate_error.norm()),
        ),
        Column::new(
            "final_error",
            "units of q",
            "e(t_final) per axis",
            Read::Axes(|m| m.final_error),
        ),
        Column::new(
            "final_rate_error",
            "units of q/s",
            "e'(t_final) per axis",
            Read::Axes(|m| m.final_rate_error),
        ),
        Column::new(
            "fuel_used",
            "kg",
            "m(0) - m(t_final), for plants with mass (NaN otherwise)",
            Read::Scalar(|m| m.fuel_used),
        ),
        Column::new(
            "fuel_to_settle",
            "kg",
            "m(0) - m(settle_time): the propellant spent until the error settles (NaN if it does not, or the plant has no mass)",
            Read::Scalar(|m| m.fuel_to_settle),
        ),
        Column::new(
            "peak_command",
            "command units",
            "largest |u| applied, Euclidean (for the Mars lander, the peak thrust)",
            Read::Scalar(|m| m.peak_command),
        ),
        Column::new(
            "peak_command_axis",
            "command units",
            "largest |u_i| applied, per axis",
            Read::Axes(|m| m.peak_command_axis),
        ),
        Column::new(
            "control_effort",
            "command units s",
            "integral of |u| dt",
            Read::Scalar(|m| m.control_effort),
        ),
        Column::new(
            "settle_time",
            "s",
            "first control instant from which |e| stays within the settle tolerance until t_final (NaN if it is outside at t_final); the \"time to track\" of the fuzzy fast-terminal asteroid paper",
            Read::Scalar(|m| m.settle_time),
        ),
        Column::new(
            "iae",
            "units of q s",
            "integral of |e_i| dt over the run (rectangle rule at the control instants), summed over the axes",
            Read::Scalar(|m| m.iae.sum()),
        ),
        Column::new(
            "iae_axis",
            "units of q s",
            "integral of |e_i| dt, per axis",
            Read::Axes(|m| m.iae),
        ),
        Column::new(
            "chattering_variation",
            "command units/s",
            "total variation of the applied command per unit time, sum_k |u(k+1) - u(k)| / T, summed over the axes",
            Read::Scalar(|m| m.command_variation.sum()),
        ),
        Column::new(
            "chattering_variation_axis",
            "command units/s",
            "total variation of the applied command per unit time, per axis",
            Read::Axes(|m| m.command_variation),
        ),
        Column::new(
            "chattering_hf_share",
            "1",
            "share of the applied command's energy above the chattering cut-off (2nd-order Butterworth high-pass), all axes",
            Read::Scalar(|m| m.high_frequency_share_total),
        ),
        Column::new(
            "chattering_hf_share_axis",
            "1",
            "share of the applied command's energy above the chattering cut-off, per axis",
            Read::Axes(|m| m.high_frequency_share),
        ),
        Column::new(
            "touchdown_time",
            "s",
            "first crossing of the landing surface, interpolated within the step (NaN if none, or the plant has no surface)",
            Read::Scalar(|m| m.touchdown.map_or(NAN, |t| t.time)),
        ),
        Column::new(
            "touchdown_position",
            "units of q",
            "the position at touchdown",
            Read::Axes(|m| m.touchdown.map_or(SVector::repeat(NAN), |t| t.position)),
        ),
        Column::new(
            "touchdown_velocity",
            "units of q/s",
            "the velocity at touchdown",
            Read::Axes(|m| m.touchdown.map_or(SVector::repeat(NAN), |t| t.velocity)),
        ),
        Column::new(
            "touchdown_speed",
            "units of q/s",
            "the speed at touchdown",
            Read::Scalar(|m| m.touchdown.map_or(NAN, |t| t.velocity.norm())),
        ),
        Column::new(
            "navigation_position_rms",
            "units of q",
            "root mean square over the control instants of |q_hat - q|, the error of the position the law read (NaN without a sensor)",
            Read::Scalar(|m| m.navigation.map_or(NAN, |n| n.position_rms)),
        ),
        Column::new(
            "navigation_velocity_rms",
            "units of q/s",
            "root mean square over the control instants of |q'_hat - q'| (NaN without a sensor)",
            Read::Scalar(|m| m.navigation.map_or(NAN, |n| n.velocity_rms)),
        ),
        Column::new(
            "navigation_position_error",
            "units of q",
            "q_hat - q at the case's last control instant, per axis (NaN without a sensor)",
            Read::Axes(|m| {
                m.navigation
                    .map_or(SVector::repeat(NAN), |n| n.position_error)
            }),
        ),
        Column::new(
            "navigation_velocity_error",
            "units of q/s",
            "q'_hat - q' at the case's last control instant, per axis (NaN without a sensor)",
            Read::Axes(|m| {
                m.navigation
                    .map_or(SVector::repeat(NAN), |n| n.velocity_error)
            }),
        ),
        Column::new(
            "diverged",
            "",
            "whether the case was stopped before t_final (its final errors and fuel are then NaN)",
            Read::Flag(|m| m.diverged.is_some()),
        ),
        Column::new(
            "diverged_time",
            "s",
            "when the case was stopped (NaN if it was not)",
            Read::Scalar(|m| m.diverged.map_or(NAN, |d| d.time)),
        ),
        Column::new(
            "diverged_reason",
            "",
            "why: an index into landing.DIVERGENCE_REASONS (0: none)",
            Read::Code(|m| m.diverged.map_or(0, |d| d.reason.code())),
        ),
    ];

    /// Whether every accumulated statistic is finite (the ones that are NaN by definition, such
    /// as the settle time of a case that does not settle, are not looked at).
    pub fn accumulations_finite(&self) -> bool {
        self.peak_command.is_finite()
            && self.control_effort.is_finite()
            && self.peak_command_axis.iter().all(|v| v.is_finite())
            && self.iae.iter().all(|v| v.is_finite())
            && self.command_variation.iter().all(|v| v.is_finite())
            && !self.high_frequency_share.iter().any(|v| v.is_infinite())
            && !self.high_frequency_share_total.is_infinite()
    }
}

/// A second-order Butterworth high-pass filter, discretised by the bilinear transform with
/// frequency prewarping (so the -3 dB point is exactly at the cut-off), in transposed direct
/// form II.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HighPass {
    b: [f64; 3],
    a: [f64; 2],
}

impl HighPass {
    /// Cut-off `hz` for samples every `dt` seconds (needs `hz < 1 / (2 dt)`).
    pub fn butterworth2(hz: f64, dt: f64) -> Self {
        let k = (std::f64::consts::PI * hz * dt).tan();
        let root2 = std::f64::consts::SQRT_2;
        let norm = 1.0 / (1.0 + root2 * k + k * k);
        Self {
            b: [norm, -2.0 * norm, norm],
            a: [2.0 * (k * k - 1.0) * norm, (1.0 - root2 * k + k * k) * norm],
        }
    }

    /// Filter state for an input that has been `x` forever (zero output).
    #[inline(always)]
    fn steady<const D: usize, R: Real>(&self, x: &SVector<R, D>) -> [SVector<R, D>; 2] {
        let z2 = scale(x, self.b[2]);
        [add(&scale(x, self.b[1]), &z2), z2]
    }

    /// One sample: the output and the next state.
    #[inline(always)]
    fn step<const D: usize, R: Real>(
        &self,
        z: &[SVector<R, D>; 2],
        x: &SVector<R, D>,
    ) -> (SVector<R, D>, [SVector<R, D>; 2]) {
        let y = add(&scale(x, self.b[0]), &z[0]);
        let z0 = add(&sub(&scale(x, self.b[1]), &scale(&y, self.a[0])), &z[1]);
        let z1 = sub(&scale(x, self.b[2]), &scale(&y, self.a[1]));
        (y, [z0, z1])
    }

    /// Magnitude response at `hz` (for tests and documentation).
    pub fn gain(&self, hz: f64, dt: f64) -> f64 {
        use std::f64::consts::TAU;
        let w = TAU * hz * dt;
        let (c1, s1, c2, s2) = (w.cos(), -w.sin(), (2.0 * w).cos(), -(2.0 * w).sin());
        let num = (
            self.b[0] + self.b[1] * c1 + self.b[2] * c2,
            self.b[1] * s1 + self.b[2] * s2,
        );
        let den = (
            1.0 + self.a[0] * c1 + self.a[1] * c2,
            self.a[0] * s1 + self.a[1] * s2,
        );
        ((num.0 * num.0 + num.1 * num.1) / (den.0 * den.0 + den.1 * den.1)).sqrt()
    }
}

/// Accumulates the command and tracking-error statistics over the applied commands, per lane.
///
/// Every lane accumulates at every period; when cases stop, [`CommandStats::freeze`] keeps a
/// copy of their statistics at that instant, which is what they report. (Masking each
/// accumulation instead would cost a select per statistic and period, for an event that
/// happens to few cases, if any.)
#[derive(Clone, Copy, Debug)]
pub(crate) struct CommandStats<const D: usize, R: Real> {
    filter: HighPass,
    started: bool,
    now: Sums<D, R>,
    /// The sums of the stopped lanes, from the instant they stopped.
    frozen: Sums<D, R>,
    stopped: R::Mask,
}

#[derive(Clone, Copy, Debug)]
struct Sums<const D: usize, R: Real> {
    z: [SVector<R, D>; 2],
    last: SVector<R, D>,
    peak: R,
    peak_axis: SVector<R, D>,
    effort: R,
    iae: SVector<R, D>,
    variation: SVector<R, D>,
    high: SVector<R, D>,
    energy: SVector<R, D>,
    time: R,
}

impl<const D: usize, R: Real> Sums<D, R> {
    #[inline(always)]
    fn select(mask: R::Mask, a: &Self, b: &Self) -> Self {
        Self {
            z: [
                select_vector(mask, &a.z[0], &b.z[0]),
                select_vector(mask, &a.z[1], &b.z[1]),
            ],
            last: select_vector(mask, &a.last, &b.last),
            peak: R::select(mask, a.peak, b.peak),
            peak_axis: select_vector(mask, &a.peak_axis, &b.peak_axis),
            effort: R::select(mask, a.effort, b.effort),
            iae: select_vector(mask, &a.iae, &b.iae),
            variation: select_vector(mask, &a.variation, &b.variation),
            high: select_vector(mask, &a.high, &b.high),
            energy: select_vector(mask, &a.energy, &b.energy),
            time: R::select(mask, a.time, b.time),
        }
    }
}

impl<const D: usize, R: Real> CommandStats<D, R> {
    pub(crate) fn new(filter: HighPass) -> Self {
        let z = zeros();
        let sums = Sums {
            z: [z, z],
            last: z,
            peak: R::zero(),
            peak_axis: z,
            effort: R::zero(),
            iae: z,
            variation: z,
            high: z,
            energy: z,
            time: R::zero(),
        };
        Self {
            filter,
            started: false,
            now: sums,
            frozen: sums,
            stopped: R::Mask::splat(false),
        }
    }

    /// The command `u` applied over a period `dt` with the tracking error `e` at its start.
    /// Every case starts at the same instant, so the filter's steady-state start is taken for
    /// all lanes at the first call.
    #[inline(always)]
    pub(crate) fn add(&mut self, u: &SVector<R, D>, e: &SVector<R, D>, dt: f64) {
        let s = &mut self.now;
        let n = norm(u);
        let dtl = R::splat(dt);
        let abs_u = abs(u);
        for i in 0..D {
            s.peak_axis[i] = s.peak_axis[i].max(abs_u[i]);
        }
        s.peak = s.peak.max(n);
        s.effort += n * dtl;
        s.iae = add(&s.iae, &scale_by(&abs(e), dtl));
        s.time += dtl;
        if self.started {
            s.variation = add(&s.variation, &abs(&sub(u, &s.last)));
        } else {
            s.z = self.filter.steady(u);
            self.started = true;
        }
        let (y, z) = self.filter.step(&s.z, u);
        s.z = z;
        s.high = add(&s.high, &mul(&y, &y));
        s.energy = add(&s.energy, &mul(u, u));
        s.last = *u;
    }

    /// Keeps the statistics of the lanes in `stopping` as they are now.
    #[inline(always)]
    pub(crate) fn freeze(&mut self, stopping: R::Mask) {
        self.frozen = Sums::select(stopping, &self.now, &self.frozen);
        self.stopped = self.stopped | stopping;
    }

    /// The statistics of lane `i`.
    pub(crate) fn finish_lane(&self, i: usize, m: &mut CaseMetrics<D>) {
        let s = if self.stopped.lane(i) {
            &self.frozen
        } else {
            &self.now
        };
        m.peak_command = s.peak.lane(i);
        m.peak_command_axis = SVector::from_fn(|k, _| s.peak_axis[k].lane(i));
        m.control_effort = s.effort.lane(i);
        m.iae = SVector::from_fn(|k, _| s.iae[k].lane(i));
        let time = s.time.lane(i);
        if time > 0.0 {
            m.command_variation = SVector::from_fn(|k, _| s.variation[k].lane(i) / time);
        }
        let share = |h: f64, e: f64| if e > 0.0 { h / e } else { 0.0 };
        let high = SVector::<f64, D>::from_fn(|k, _| s.high[k].lane(i));
        let energy = SVector::<f64, D>::from_fn(|k, _| s.energy[k].lane(i));
        m.high_frequency_share = SVector::from_fn(|k, _| share(high[k], energy[k]));
        m.high_frequency_share_total = share(high.sum(), energy.sum());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector1;

    #[test]
    fn butterworth_response() {
        let dt = 0.01;
        let f = HighPass::butterworth2(5.0, dt);
        // -3 dB at the cut-off, unity near Nyquist, 12 dB per octave below
        assert!((f.gain(5.0, dt) - 0.5f64.sqrt()).abs() < 1e-12);
        assert!((f.gain(49.999, dt) - 1.0).abs() < 1e-6);
        assert!(f.gain(0.0, dt) < 1e-12);
        let r = f.gain(0.5, dt) / f.gain(1.0, dt);
        assert!((r - 0.25).abs() < 0.01, "{r}");
    }

    fn share_of(signal: impl Fn(f64) -> f64, hz: f64, dt: f64, n: usize) -> f64 {
        let mut s = CommandStats::<1, f64>::new(HighPass::butterworth2(hz, dt));
        for k in 0..n {
            s.add(&Vector1::new(signal(k as f64 * dt)), &Vector1::zeros(), dt);
        }
        let mut m = CaseMetrics::<1>::new();
        s.finish_lane(0, &mut m);
        m.high_frequency_share[0]
    }

    #[test]
    fn high_frequency_share_separates_slow_from_chattering() {
        let dt = 0.01;
        // a constant: no high-frequency energy, not even from the start-up transient
        assert!(share_of(|_| 3.0, 5.0, dt, 2000) < 1e-20);
        // a slow sine: |H(0.1 Hz)|^2 ~ (0.1/5)^4
        let slow = share_of(|t| (std::f64::consts::TAU * 0.1 * t).sin(), 5.0, dt, 20_000);
        assert!(slow < 1e-6, "{slow}");
        // sign chattering at Nyquist: all of it passes
        let fast = share_of(
            |t| {
                if ((t / dt).round() as i64) % 2 == 0 {
                    1.0
                } else {
                    -1.0
                }
            },
            5.0,
            dt,
            2000,
        );
        assert!((fast - 1.0).abs() < 1e-3, "{fast}");
        // half and half
        let mix = share_of(
            |t| {
                (std::f64::consts::TAU * 0.1 * t).sin()
                    + if ((t / dt).round() as i64) % 2 == 0 {
                        1.0
                    } else {
                        -1.0
                    }
            },
            5.0,
            dt,
            20_000,
        );
        assert!((mix - 2.0 / 3.0).abs() < 0.01, "{mix}");
    }

    #[test]
    fn variation_and_iae() {
        let mut s = CommandStats::<1, f64>::new(HighPass::butterworth2(5.0, 0.01));
        for (u, e) in [(0.0, 1.0), (2.0, -1.0), (1.0, 0.5), (1.0, 0.0)] {
            s.add(&Vector1::new(u), &Vector1::new(e), 0.5);
        }
        // a stopped case keeps what it had
        s.freeze(true);
        s.add(&Vector1::new(100.0), &Vector1::new(100.0), 0.5);
        let mut m = CaseMetrics::<1>::new();
        s.finish_lane(0, &mut m);
        assert_eq!(m.command_variation[0], 3.0 / 2.0);
        assert_eq!(m.iae[0], 2.5 * 0.5);
        assert_eq!(m.peak_command, 2.0);
    }
}
