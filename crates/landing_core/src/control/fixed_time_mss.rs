//! Fixed-time multiple-sliding-surface guidance (seed 001, eq. 15-25).
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
use crate::error::{ParamError, ReadError, Validate, check, check_axes};
use crate::lanes::axes::{Axes, AxesMask};
use crate::lanes::math::PowLog;
use crate::lanes::{Mask, Real, filled, sub};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

crate::named! {
    /// Eq. 25 as printed, or with the exact derivative of s2.
    pub enum MssVariant {
        Printed => "printed",
        Exact => "exact",
    }
}

const BETA1: Param = Param::axes("beta1")
    .unit("(m^(1 - q1))/s")
    .rule("beta1 > 0")
    .doc("gain of the first reaching law's sig^q1 term (eq. 21)");
const BETA2: Param = Param::axes("beta2")
    .unit("(m^(1 - q2))/s")
    .rule("beta2 > 0")
    .doc("gain of the first reaching law's sig^q2 term (eq. 21)");
const Q1: Param = Param::axes("q1")
    .unit("1")
    .rule("0 < q1 < 1")
    .doc("exponent of the first reaching law, below 1");
const Q2: Param = Param::axes("q2")
    .unit("1")
    .rule("q2 > 1")
    .doc("exponent of the first reaching law, above 1");
const ALPHA1: Param = Param::axes("alpha1")
    .unit("(m/s)^(1 - gamma1)/s")
    .rule("alpha1 > 0")
    .doc("gain of the second reaching law's sig^gamma1 term (eq. 26)");
const ALPHA2: Param = Param::axes("alpha2")
    .unit("(m/s)^(1 - gamma2)/s")
    .rule("alpha2 > 0")
    .doc("gain of the second reaching law's sig^gamma2 term (eq. 26)");
const GAMMA1: Param = Param::axes("gamma1")
    .unit("1")
    .rule("0 < gamma1 < 1")
    .doc("exponent of the second reaching law (the Mars paper's g1), below 1");
const GAMMA2: Param = Param::axes("gamma2")
    .unit("1")
    .rule("gamma2 > 1")
    .doc("exponent of the second reaching law (the Mars paper's g2), above 1");
const VARIANT: Param = Param::choice("variant", MssVariant::NAMES)
    .doc("printed: eq. 25 as printed; exact: the exact derivative of s2");
const S1_FLOOR: Param = Param::scalar("s1_floor")
    .unit("m")
    .rule("s1_floor > 0")
    .doc("singularity guard: floor on |s1| wherever it is raised to a negative power");

/// Gains per axis, with the seed's symbols (`gamma1`, `gamma2` are its exponents g1, g2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FixedTimeMss<const D: usize, R = f64> {
    pub beta1: SVector<R, D>,
    pub beta2: SVector<R, D>,
    pub q1: SVector<R, D>,
    pub q2: SVector<R, D>,
    pub alpha1: SVector<R, D>,
    pub alpha2: SVector<R, D>,
    pub gamma1: SVector<R, D>,
    pub gamma2: SVector<R, D>,
    /// Shared by a block.
    pub variant: MssVariant,
    /// Floor on |s1| in the negative powers (the singularity guard), in units of q.
    pub s1_floor: R,
}

crate::gather_struct!(FixedTimeMss<const D: usize, R> {
    lanes: [beta1, beta2, q1, q2, alpha1, alpha2, gamma1, gamma2, s1_floor],
    shared: [variant],
});

/// The first surface's powers, shared by the second surface and the law, every axis side by
/// side ([`Axes`]): one logarithm ([`PowLog`]) and two exponentials give |s1|^q1 and |s1|^q2,
/// and every other power of |s1| the law needs is a product or quotient of those
/// (|s|^(2q-1) = (|s|^q)^2 / |s|). At s1 = 0 the logarithm is -inf and both powers are 0.
///
/// `sig^q(s) = sgn(s) |s|^q` is taken as `|s|^q` with the sign of s (`copysign`, one bitwise
/// operation where `sgn(s) *` takes two compares, two selects and a multiply): the same value
/// wherever s != 0, and a zero either way at s = 0, where the power is 0.
#[derive(Clone, Copy, Debug)]
struct Surfaces<R, const D: usize> {
    /// s1 = e and |s1|
    s1: Axes<R, D>,
    abs: Axes<R, D>,
    /// |s1|^q1, |s1|^q2
    p1: Axes<R, D>,
    p2: Axes<R, D>,
    /// s2 (eq. 21)
    s2: Axes<R, D>,
}

impl<const D: usize, R: Real> FixedTimeMss<D, R> {
    /// Both surfaces, the axes side by side: each step of the chain (logarithm, powers, s2,
    /// and the law's logarithm and powers after it) issues every axis's instructions together,
    /// which in blocks of 16 lanes hides the latency of one axis's chain behind the others'
    /// (W1 1.27x faster than axis after axis, BENCHMARKS.md). Lane by lane these are the same
    /// operations as axis after axis.
    #[inline(always)]
    fn surfaces(&self, input: &LawInput<D, R>) -> Surfaces<R, D> {
        let s1 = Axes::of(&input.e);
        let abs = s1.abs();
        let l = PowLog::of(abs);
        let p1 = l.pow(Axes::of(&self.q1));
        let p2 = l.pow(Axes::of(&self.q2));
        let s2 = Axes::of(&input.de)
            + (Axes::of(&self.beta1) * p1 + Axes::of(&self.beta2) * p2).copysign(s1);
        Surfaces {
            s1,
            abs,
            p1,
            p2,
            s2,
        }
    }

    /// Second sliding variable (eq. 21).
    #[inline(always)]
    pub fn s2(&self, input: &LawInput<D, R>) -> SVector<R, D> {
        self.surfaces(input).s2.vector()
    }
}

/// `|s1|^e` for an exponent e that may be negative: `shared` (computed from the shared powers)
/// where `use_shared` holds, the power of the floor elsewhere (|s1| below the floor, the
/// singularity guard). The floor's power is computed only when some lane needs it.
#[inline(always)]
fn guarded<R: Real, const D: usize>(
    floor: Axes<R, D>,
    use_shared: AxesMask<R::Mask, D>,
    shared: Axes<R, D>,
    e: Axes<R, D>,
) -> Axes<R, D> {
    if use_shared.all() {
        shared
    } else {
        Real::select(use_shared, shared, floor.powf(e))
    }
}

/// What the law derives from its gains, once per block ([`ControlLaw::Memory`]): the
/// coefficients of the printed variant's cancellation terms.
#[derive(Clone, Copy, Debug)]
pub struct MssConstants<const D: usize, R> {
    /// beta1^2 q1, beta2^2 q2, beta1 beta2 (q1 + q2)
    c11: SVector<R, D>,
    c22: SVector<R, D>,
    c12: SVector<R, D>,
    /// 2 q1 - 1, the one exponent that can be negative
    e1: SVector<R, D>,
}

impl<const D: usize, R: Real> ControlLaw<R, D> for FixedTimeMss<D, R> {
    type Memory = MssConstants<D, R>;
    const ADVANCES: bool = false;
    const DIAGNOSTICS: &'static [&'static str] = &["s1", "s2"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> MssConstants<D, R> {
        let (b1, b2, q1, q2) = (&self.beta1, &self.beta2, &self.q1, &self.q2);
        let mut k = MssConstants {
            c11: filled(R::zero()),
            c22: filled(R::zero()),
            c12: filled(R::zero()),
            e1: filled(R::zero()),
        };
        for i in 0..D {
            k.c11[i] = b1[i] * b1[i] * q1[i];
            k.c22[i] = b2[i] * b2[i] * q2[i];
            k.c12[i] = b1[i] * b2[i] * (q1[i] + q2[i]);
            k.e1[i] = R::splat(2.0) * q1[i] - 1.0;
        }
        k
    }

    #[inline(always)]
    fn command(&self, k: &MssConstants<D, R>, input: &LawInput<D, R>) -> SVector<R, D> {
        let Surfaces {
            s1,
            abs,
            p1,
            p2,
            s2,
        } = self.surfaces(input);
        let zero = Axes([R::zero(); D]);
        let floor = Axes([self.s1_floor; D]);
        let nonzero = abs.simd_gt(zero);
        let inv = Axes([R::one(); D]) / abs;
        let cancel = match self.variant {
            // beta1^2 q1 |s1|^(2q1-1) + beta2^2 q2 |s1|^(2q2-1)
            // + beta1 beta2 (q1+q2) |s1|^(q1+q2-1); only the first power can be singular
            MssVariant::Printed => {
                let e1 = Axes::of(&k.e1);
                let no_guard = e1.simd_ge(zero) | abs.simd_ge(floor);
                let t1 = guarded(floor, no_guard, p1 * p1 * inv, e1);
                let rest = (p2 * inv) * (Axes::of(&k.c22) * p2 + Axes::of(&k.c12) * p1);
                Real::select(nonzero, (Axes::of(&k.c11) * t1 + rest).copysign(s1), zero)
            }
            // |s1|^(q1-1) (singular, guarded) and |s1|^(q2-1)
            MssVariant::Exact => {
                let (q1, q2) = (Axes::of(&self.q1), Axes::of(&self.q2));
                let t1 = guarded(floor, abs.simd_ge(floor), p1 * inv, q1 - 1.0);
                let t2 = Real::select(nonzero, p2 * inv, zero);
                -(Axes::of(&self.beta1) * q1 * t1 + Axes::of(&self.beta2) * q2 * t2)
                    * Axes::of(&input.de)
            }
        };
        // the reaching law, -alpha1 sig^g1(s2) - alpha2 sig^g2(s2), with one logarithm
        let l2 = PowLog::of(s2.abs());
        let reach = -(Axes::of(&self.alpha1) * l2.pow(Axes::of(&self.gamma1))
            + Axes::of(&self.alpha2) * l2.pow(Axes::of(&self.gamma2)))
        .copysign(s2);
        (Axes::of(&sub(&input.reference.acceleration, &input.drift)) + (cancel + reach)).vector()
    }

    #[inline(always)]
    fn diagnostics(&self, _memory: &MssConstants<D, R>, input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(input.e.as_slice());
        out[D..2 * D].copy_from_slice(self.s2(input).as_slice());
    }
}

impl<const D: usize> Validate for FixedTimeMss<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&BETA1, self.beta1.as_slice(), |v| v > 0.0)?;
        check_axes(&BETA2, self.beta2.as_slice(), |v| v > 0.0)?;
        check_axes(&Q1, self.q1.as_slice(), |v| v > 0.0 && v < 1.0)?;
        check_axes(&Q2, self.q2.as_slice(), |v| v > 1.0)?;
        check_axes(&ALPHA1, self.alpha1.as_slice(), |v| v > 0.0)?;
        check_axes(&ALPHA2, self.alpha2.as_slice(), |v| v > 0.0)?;
        check_axes(&GAMMA1, self.gamma1.as_slice(), |v| v > 0.0 && v < 1.0)?;
        check_axes(&GAMMA2, self.gamma2.as_slice(), |v| v > 1.0)?;
        check(&S1_FLOOR, self.s1_floor, |v| v > 0.0)
    }
}

impl<const D: usize> Declared for FixedTimeMss<D> {
    const SCHEMA: Schema = Schema::new(&[
        BETA1, BETA2, Q1, Q2, ALPHA1, ALPHA2, GAMMA1, GAMMA2, VARIANT, S1_FLOOR,
    ]);
}

impl<const D: usize> FromParams for FixedTimeMss<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            beta1: p.axes(&BETA1)?,
            beta2: p.axes(&BETA2)?,
            q1: p.axes(&Q1)?,
            q2: p.axes(&Q2)?,
            alpha1: p.axes(&ALPHA1)?,
            alpha2: p.axes(&ALPHA2)?,
            gamma1: p.axes(&GAMMA1)?,
            gamma2: p.axes(&GAMMA2)?,
            variant: p.choice(&VARIANT)?,
            s1_floor: p.scalar(&S1_FLOOR)?,
        })
    }
}
