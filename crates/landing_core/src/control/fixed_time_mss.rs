//! Fixed-time multiple-sliding-surface guidance (seed 001, eq. 15-25; SPEC 5 law 6).
//!
//! ```text
//! s1 = q - q_ref                                                  (eq. 15)
//! s2 = s1' + beta1 sig^q1(s1) + beta2 sig^q2(s1)                 (eq. 21)
//! ```
//! The law makes `s2' = -alpha1 sig^g1(s2) - alpha2 sig^g2(s2)` (eq. 26's reaching law), after
//! which `s1' = -beta1 sig^q1(s1) - beta2 sig^q2(s1)` (eq. 16) holds on s2 = 0.
//!
//! Two variants:
//! - `Printed` is eq. 25 as the seed prints it. It writes `s2'` with `s1'` replaced by the
//!   eq. 16 reaching law, which drops the terms `(beta1 q1 |s1|^(q1-1) + beta2 q2 |s1|^(q2-1)) s2`
//!   of the exact derivative (eq. 22 to 24): the cancellation is exact only on s2 = 0.
//!   The exponent `2 q1 - 1` is negative when q1 < 1/2; `|s1|` is then floored at `s1_floor`.
//! - `Exact` differentiates eq. 21 exactly, `s2' = s1'' + (beta1 q1 |s1|^(q1-1) + beta2 q2
//!   |s1|^(q2-1)) s1'` (eq. 22), so the reaching law holds everywhere. `|s1|^(q1-1)` is singular
//!   at s1 = 0; `|s1|` is floored at `s1_floor` there.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, require, require_axes};
use crate::math::sgn;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MssVariant {
    Printed,
    Exact,
}

impl MssVariant {
    pub const NAMES: [&'static str; 2] = ["printed", "exact"];

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "printed" => Some(Self::Printed),
            "exact" => Some(Self::Exact),
            _ => None,
        }
    }
}

/// Gains per axis, with the seed's symbols (`gamma1`, `gamma2` are its exponents g1, g2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedTimeMss<const D: usize> {
    pub beta1: SVector<f64, D>,
    pub beta2: SVector<f64, D>,
    pub q1: SVector<f64, D>,
    pub q2: SVector<f64, D>,
    pub alpha1: SVector<f64, D>,
    pub alpha2: SVector<f64, D>,
    pub gamma1: SVector<f64, D>,
    pub gamma2: SVector<f64, D>,
    pub variant: MssVariant,
    /// Floor on |s1| in the negative powers (the singularity guard), in units of q.
    pub s1_floor: f64,
}

/// The powers of one axis that the surfaces and the law share: with l = ln|s1|, one logarithm
/// and two exponentials give |s1|^q1 and |s1|^q2, and every other power of |s1| the law needs
/// is a product or quotient of those (SPEC 10: |s|^(2q-1) = (|s|^q)^2 / |s|).
#[derive(Clone, Copy, Debug)]
struct AxisPowers {
    /// |s1|
    abs: f64,
    /// |s1|^q1, |s1|^q2
    p1: f64,
    p2: f64,
    /// sgn(s1)
    sign: f64,
}

impl AxisPowers {
    #[inline(always)]
    fn new(s1: f64, q1: f64, q2: f64) -> Self {
        let abs = s1.abs();
        if abs == 0.0 {
            return Self {
                abs,
                p1: 0.0,
                p2: 0.0,
                sign: 0.0,
            };
        }
        let l = abs.ln();
        Self {
            abs,
            p1: (q1 * l).exp(),
            p2: (q2 * l).exp(),
            sign: sgn(s1),
        }
    }
}

/// `sig^g1(s) * a1 + sig^g2(s) * a2` with one logarithm.
#[inline(always)]
fn two_sig(s: f64, a1: f64, g1: f64, a2: f64, g2: f64) -> f64 {
    let abs = s.abs();
    if abs == 0.0 {
        return 0.0;
    }
    let l = abs.ln();
    sgn(s) * (a1 * (g1 * l).exp() + a2 * (g2 * l).exp())
}

impl<const D: usize> FixedTimeMss<D> {
    #[inline(always)]
    fn powers(&self, i: usize, s1: f64) -> AxisPowers {
        AxisPowers::new(s1, self.q1[i], self.q2[i])
    }

    /// s2 on axis i (eq. 21).
    #[inline(always)]
    fn s2_axis(&self, i: usize, p: &AxisPowers, ds1: f64) -> f64 {
        ds1 + p.sign * (self.beta1[i] * p.p1 + self.beta2[i] * p.p2)
    }

    /// Second sliding variable (eq. 21).
    pub fn s2(&self, input: &LawInput<D>) -> SVector<f64, D> {
        SVector::from_fn(|i, _| self.s2_axis(i, &self.powers(i, input.e[i]), input.de[i]))
    }

    /// `|s1|^e` for a negative exponent e, computed from the shared powers unless the guard
    /// applies (|s1| below the floor, where the power is taken at the floor).
    #[inline(always)]
    fn guarded(&self, p: &AxisPowers, shared: impl Fn() -> f64, e: f64) -> f64 {
        if p.abs >= self.s1_floor {
            shared()
        } else {
            self.s1_floor.powf(e)
        }
    }
}

impl<const D: usize> ControlLaw<D> for FixedTimeMss<D> {
    type Memory = ();
    const DIAGNOSTICS: &'static [&'static str] = &["s1", "s2"];

    fn start(&self, _input: &LawInput<D>) {}

    #[inline(always)]
    fn command(&self, _memory: &(), input: &LawInput<D>) -> SVector<f64, D> {
        let mut a = input.reference.acceleration - input.drift;
        for i in 0..D {
            let (b1, b2, q1, q2) = (self.beta1[i], self.beta2[i], self.q1[i], self.q2[i]);
            let p = self.powers(i, input.e[i]);
            let s2 = self.s2_axis(i, &p, input.de[i]);
            let cancel = match self.variant {
                // |s1|^(2q1-1), |s1|^(2q2-1), |s1|^(q1+q2-1); only the first can be singular
                MssVariant::Printed if p.abs > 0.0 => {
                    let inv = 1.0 / p.abs;
                    let e1 = 2.0 * q1 - 1.0;
                    let t1 = if e1 >= 0.0 {
                        p.p1 * p.p1 * inv
                    } else {
                        self.guarded(&p, || p.p1 * p.p1 * inv, e1)
                    };
                    p.sign
                        * (b1 * b1 * q1 * t1
                            + b2 * b2 * q2 * p.p2 * p.p2 * inv
                            + b1 * b2 * (q1 + q2) * p.p1 * p.p2 * inv)
                }
                MssVariant::Printed => 0.0,
                // |s1|^(q1-1) (singular, guarded) and |s1|^(q2-1)
                MssVariant::Exact => {
                    let t1 = self.guarded(&p, || p.p1 / p.abs, q1 - 1.0);
                    let t2 = if p.abs > 0.0 { p.p2 / p.abs } else { 0.0 };
                    -(b1 * q1 * t1 + b2 * q2 * t2) * input.de[i]
                }
            };
            let reach = -two_sig(
                s2,
                self.alpha1[i],
                self.gamma1[i],
                self.alpha2[i],
                self.gamma2[i],
            );
            a[i] += cancel + reach;
        }
        a
    }

    fn diagnostics(&self, _memory: &(), input: &LawInput<D>, out: &mut [f64]) {
        out[..D].copy_from_slice(input.e.as_slice());
        out[D..2 * D].copy_from_slice(self.s2(input).as_slice());
    }

    fn validate(&self) -> Result<(), ParamError> {
        require_axes(self.beta1.as_slice(), "beta1", "beta1 > 0", |v| v > 0.0)?;
        require_axes(self.beta2.as_slice(), "beta2", "beta2 > 0", |v| v > 0.0)?;
        require_axes(self.q1.as_slice(), "q1", "0 < q1 < 1", |v| {
            v > 0.0 && v < 1.0
        })?;
        require_axes(self.q2.as_slice(), "q2", "q2 > 1", |v| v > 1.0)?;
        require_axes(self.alpha1.as_slice(), "alpha1", "alpha1 > 0", |v| v > 0.0)?;
        require_axes(self.alpha2.as_slice(), "alpha2", "alpha2 > 0", |v| v > 0.0)?;
        require_axes(self.gamma1.as_slice(), "gamma1", "0 < gamma1 < 1", |v| {
            v > 0.0 && v < 1.0
        })?;
        require_axes(self.gamma2.as_slice(), "gamma2", "gamma2 > 1", |v| v > 1.0)?;
        require(
            self.s1_floor > 0.0,
            "s1_floor",
            self.s1_floor,
            "s1_floor > 0",
        )
    }
}
