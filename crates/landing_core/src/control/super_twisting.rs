//! Super-twisting guidance (seed 001, eq. 46), the seed's baseline.
//!
//! `Printed` is eq. 46 with s = q - q_ref:
//! ```text
//! a = -(1/m) [ (B1/2) |s|^(-1/2) s' + B2 sgn(s) ] - g
//! ```
//! It is the time derivative of the super-twisting control `-B1 sig^(1/2)(s) - B2 int sgn(s)`,
//! applied to the acceleration of a second-order plant. `|s|^(-1/2)` is singular at s = 0;
//! `|s|` is floored at `s_floor` there. Where the seed cancels g, this cancels the plant's whole
//! modelled acceleration (g plus the modelled drag), like the fixed-time law it is compared with.
//!
//! `Standard` is the textbook super-twisting algorithm on the sliding variable
//! `sigma = s' + c s`, with its integral state w:
//! ```text
//! a = -drift + q_ref'' - c s' + (1/m) (-B1 sig^(1/2)(sigma) + w),   w' = -B2 sgn(sigma)
//! ```
//! The gains keep the seed's force units (divided by the inertia m, as in eq. 46), so the same
//! B1, B2 drive both variants.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check, check_axes};
use crate::lanes::{Real, add, mul, sub, zeros};
use crate::math::sgn;
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

crate::named! {
    /// Eq. 46 as printed, or the textbook algorithm.
    pub enum SuperTwistingVariant {
        Printed => "printed",
        Standard => "standard",
    }
}

const B1: Param = Param::axes("b1")
    .unit("N")
    .rule("b1 > 0")
    .doc("gain of the s' (printed) or sig^(1/2)(sigma) (standard) term, force units divided by the inertia");
const B2: Param = Param::axes("b2")
    .unit("N")
    .rule("b2 > 0")
    .doc("gain of sgn(s) (printed) or of the integral state's rate (standard), force units");
const VARIANT: Param = Param::choice("variant", SuperTwistingVariant::NAMES)
    .doc("printed: eq. 46 on s; standard: the textbook algorithm on sigma = s' + c s");
const C: Param = Param::axes("c")
    .unit("1/s")
    .rule("c > 0")
    .doc("slope of sigma in the standard variant");
const S_FLOOR: Param = Param::scalar("s_floor")
    .unit("m")
    .rule("s_floor > 0")
    .doc("singularity guard: floor on |s| in |s|^(-1/2) of the printed variant");

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SuperTwisting<const D: usize, R = f64> {
    pub b1: SVector<R, D>,
    pub b2: SVector<R, D>,
    /// Slope of the sliding variable of the standard variant.
    pub c: SVector<R, D>,
    /// Shared by a block.
    pub variant: SuperTwistingVariant,
    /// Floor on |s| in `|s|^(-1/2)` of the printed variant (the singularity guard).
    pub s_floor: R,
}

crate::gather_struct!(SuperTwisting<const D: usize, R> {
    lanes: [b1, b2, c, s_floor],
    shared: [variant],
});

impl<const D: usize, R: Real> SuperTwisting<D, R> {
    /// The sliding variable the law drives to zero: s itself (printed) or s' + c s (standard).
    #[inline(always)]
    pub fn sigma(&self, input: &LawInput<D, R>) -> SVector<R, D> {
        match self.variant {
            SuperTwistingVariant::Printed => input.e,
            SuperTwistingVariant::Standard => add(&input.de, &mul(&self.c, &input.e)),
        }
    }
}

impl<const D: usize, R: Real> ControlLaw<R, D> for SuperTwisting<D, R> {
    /// The integral state w of the standard variant, in force units.
    type Memory = SVector<R, D>;
    const DIAGNOSTICS: &'static [&'static str] = &["sigma", "w"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> SVector<R, D> {
        zeros()
    }

    #[inline(always)]
    fn command(&self, w: &SVector<R, D>, input: &LawInput<D, R>) -> SVector<R, D> {
        let mut a = sub(&input.reference.acceleration, &input.drift);
        for i in 0..D {
            let s = input.e[i];
            let ds = input.de[i];
            let m = input.inertia[i];
            a[i] += match self.variant {
                SuperTwistingVariant::Printed => {
                    let root = s.abs().max(self.s_floor).sqrt();
                    -(R::splat(0.5) * self.b1[i] * ds / root + self.b2[i] * sgn(s)) / m
                }
                SuperTwistingVariant::Standard => {
                    let sigma = ds + self.c[i] * s;
                    -self.c[i] * ds + (-self.b1[i] * sgn(sigma) * sigma.abs().sqrt() + w[i]) / m
                }
            };
        }
        a
    }

    #[inline(always)]
    fn advance(&self, w: &mut SVector<R, D>, input: &LawInput<D, R>) {
        if self.variant == SuperTwistingVariant::Standard {
            let sigma = self.sigma(input);
            for i in 0..D {
                w[i] -= R::splat(input.dt) * self.b2[i] * sgn(sigma[i]);
            }
        }
    }

    #[inline(always)]
    fn diagnostics(&self, w: &SVector<R, D>, input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(self.sigma(input).as_slice());
        out[D..2 * D].copy_from_slice(w.as_slice());
    }
}

impl<const D: usize> Validate for SuperTwisting<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&B1, self.b1.as_slice(), |v| v > 0.0)?;
        check_axes(&B2, self.b2.as_slice(), |v| v > 0.0)?;
        check_axes(&C, self.c.as_slice(), |v| v > 0.0)?;
        check(&S_FLOOR, self.s_floor, |v| v > 0.0)
    }
}

impl<const D: usize> Declared for SuperTwisting<D> {
    const SCHEMA: Schema = Schema::new(&[B1, B2, VARIANT, C, S_FLOOR]);
}

impl<const D: usize> FromParams for SuperTwisting<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            b1: p.axes(&B1)?,
            b2: p.axes(&B2)?,
            c: p.axes(&C)?,
            variant: p.choice(&VARIANT)?,
            s_floor: p.scalar(&S_FLOOR)?,
        })
    }
}
