//! Conventional nonsingular terminal sliding mode (seed 003, the baseline at the end of its
//! section 4, printed as eq. 47/48).
//!
//! ```text
//! s = e1 + (1/beta) sig^(gamma/alpha)(e2)
//! u = -M (beta (alpha/gamma) sig^(2 - gamma/alpha)(e2) + K sign(s))
//! ```
//! with e1 = q - q_d, e2 = q' - q_d'. It is Feng et al.'s NTSMC for a double integrator: with
//! r = gamma/alpha, s' = e2 + (r/beta) |e2|^(r-1) e2' and the law gives
//! `s' = -(r/beta) |e2|^(r-1) K sign(s)`, so s reaches 0 and then e1 follows
//! `e1' = -sig^(1/r)(beta e1)` to 0 in finite time. The commanded acceleration here is the
//! bracket (the plant's actuator multiplies by M), plus the reference acceleration and minus
//! the plant's modelled drift, both zero on the tethered satellite, where the law is the seed's.
//!
//! Singularity guard: the nonsingular form itself. Every power is non-negative when
//! `1 < gamma/alpha < 2` (the NTSMC's defining range, validated), so no floor is needed; a
//! ratio of 2 or more would make `|e2|^(2 - gamma/alpha)` singular and is refused.
//!
//! Meaningful on any fully actuated plant (it is a double-integrator law); on the landers the
//! drift cancellation makes it one.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check_also, check_axes};
use crate::lanes::axes::Axes;
use crate::lanes::math::PowLog;
use crate::lanes::{Real, sub};
use crate::math::sgn;
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

/// Gains per axis with the seed's symbols (seed: alpha = 1, beta = (0.05, 0.3),
/// gamma = (1.07, 1.1), K = 0.001).
const ALPHA: Param = Param::axes("alpha")
    .unit("1")
    .rule("alpha > 0")
    .doc("denominator of the surface's exponent gamma / alpha");
const BETA: Param = Param::axes("beta")
    .unit("s^(gamma/alpha) q^(1 - gamma/alpha)")
    .rule("beta > 0")
    .doc("the surface s = e1 + (1/beta) sig^(gamma/alpha)(e2)");
const GAMMA: Param = Param::axes("gamma")
    .unit("1")
    .rule("gamma > 0")
    .also("1 < gamma / alpha < 2")
    .doc(
        "numerator of the surface's exponent; the range of gamma / alpha is the singularity guard",
    );
const K: Param = Param::axes("k")
    .unit("q/s^2")
    .rule("k > 0")
    .doc("switching gain, in command units divided by the inertia");

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ntsmc<const D: usize, R = f64> {
    pub alpha: SVector<R, D>,
    pub beta: SVector<R, D>,
    pub gamma: SVector<R, D>,
    pub k: SVector<R, D>,
}

crate::gather_struct!(Ntsmc<const D: usize, R> { lanes: [alpha, beta, gamma, k], shared: [] });

impl<const D: usize, R: Real> Ntsmc<D, R> {
    /// (s, sig^(2 - r)(e2), r) with r = gamma / alpha, every axis at once ([`Axes`]: the same
    /// operations lane by lane as axis after axis, so the same bits): both powers of |e2| from
    /// one logarithm (at e2 = 0 it is -inf and both powers are 0, as 1 < r < 2).
    #[inline(always)]
    fn surfaces(&self, input: &LawInput<D, R>) -> (Axes<R, D>, Axes<R, D>, Axes<R, D>) {
        let r = Axes::of(&self.gamma) / Axes::of(&self.alpha);
        let e2 = Axes::of(&input.de);
        let l = PowLog::of(e2.abs());
        let sign = sgn(e2);
        let s = Axes::of(&input.e) + sign * l.pow(r) / Axes::of(&self.beta);
        (s, sign * l.pow(<Axes<R, D> as Real>::splat(2.0) - r), r)
    }

    /// The sliding variable s per axis.
    #[inline(always)]
    pub fn s(&self, input: &LawInput<D, R>) -> SVector<R, D> {
        self.surfaces(input).0.vector()
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for Ntsmc<D, R> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &["s"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), input: &LawInput<D, R>) -> SVector<R, D> {
        let (s, sig2r, r) = self.surfaces(input);
        let (beta, k) = (Axes::of(&self.beta), Axes::of(&self.k));
        let a = Axes::of(&sub(&input.reference.acceleration, &input.drift));
        (a - (beta / r * sig2r + k * sgn(s))).vector()
    }

    #[inline(always)]
    fn diagnostics(&self, _memory: &(), input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(self.s(input).as_slice());
    }
}

impl<const D: usize> Validate for Ntsmc<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&ALPHA, self.alpha.as_slice(), |v| v > 0.0)?;
        check_axes(&BETA, self.beta.as_slice(), |v| v > 0.0)?;
        check_axes(&GAMMA, self.gamma.as_slice(), |v| v > 0.0)?;
        for i in 0..D {
            let r = self.gamma[i] / self.alpha[i];
            check_also(&GAMMA, self.gamma[i], r > 1.0 && r < 2.0).map_err(|e| e.on_axis(i))?;
        }
        check_axes(&K, self.k.as_slice(), |v| v > 0.0)
    }
}

impl<const D: usize> Declared for Ntsmc<D> {
    const SCHEMA: Schema = Schema::new(&[ALPHA, BETA, GAMMA, K]);
}

impl<const D: usize> FromParams for Ntsmc<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            alpha: p.axes(&ALPHA)?,
            beta: p.axes(&BETA)?,
            gamma: p.axes(&GAMMA)?,
            k: p.axes(&K)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::RefPoint;
    use nalgebra::Vector2;

    fn seed() -> Ntsmc<2> {
        Ntsmc {
            alpha: Vector2::repeat(1.0),
            beta: Vector2::new(0.05, 0.3),
            gamma: Vector2::new(1.07, 1.1),
            k: Vector2::repeat(0.001),
        }
    }

    fn input(e: [f64; 2], de: [f64; 2]) -> LawInput<2> {
        let zero = Vector2::zeros();
        LawInput {
            t: 0.0,
            dt: 0.01,
            e: Vector2::from(e),
            de: Vector2::from(de),
            reference: RefPoint {
                position: zero,
                velocity: zero,
                acceleration: zero,
            },
            drift: zero,
            inertia: Vector2::new(990.0, 10.0 / 6.0),
        }
    }

    #[test]
    fn command_matches_the_printed_law() {
        let law = seed();
        let inp = input([0.01, -0.02], [-2e-3, 0.05]);
        let a = law.command(&(), &inp);
        // by hand: s = e1 + (1/beta) |e2|^r sgn(e2), a = -(beta/r) |e2|^(2-r) sgn(e2) - K sgn(s)
        let s0 = 0.01 - (2e-3f64).powf(1.07) / 0.05;
        let a0 = (0.05 / 1.07) * (2e-3f64).powf(0.93) - 0.001 * s0.signum();
        let s1 = -0.02 + (0.05f64).powf(1.1) / 0.3;
        let a1 = -(0.3 / 1.1) * (0.05f64).powf(0.9) - 0.001 * s1.signum();
        assert!((a[0] - a0).abs() < 1e-15, "{} {}", a[0], a0);
        assert!((a[1] - a1).abs() < 1e-15, "{} {}", a[1], a1);
        assert!((law.s(&inp)[0] - s0).abs() < 1e-15);
    }

    #[test]
    fn sliding_variable_decreases_where_the_law_applies() {
        // on a double integrator, s' = e2 + (r/beta)|e2|^(r-1) a: negative for s > 0, e2 != 0
        let law = seed();
        let inp = input([0.02, 0.02], [0.01, 0.01]);
        let a = law.command(&(), &inp);
        for i in 0..2 {
            let r = law.gamma[i] / law.alpha[i];
            let e2: f64 = 0.01;
            let ds = e2 + r / law.beta[i] * e2.powf(r - 1.0) * a[i];
            assert!(ds < 0.0, "axis {i}: s' = {ds}");
        }
    }

    #[test]
    fn the_exponent_range_is_the_guard() {
        let mut law = seed();
        law.gamma[1] = 2.2;
        let e = law.validate().unwrap_err();
        assert_eq!(
            (e.param, e.rule, e.axis),
            ("gamma", "1 < gamma / alpha < 2", Some(1))
        );
        law.gamma[1] = 0.9;
        assert_eq!(law.validate().unwrap_err().rule, "1 < gamma / alpha < 2");
        assert!(seed().validate().is_ok());
        // at e2 = 0 every power is finite
        let a = seed().command(&(), &input([0.01, 0.0], [0.0, 0.0]));
        assert!(a.iter().all(|v| v.is_finite()));
    }
}
