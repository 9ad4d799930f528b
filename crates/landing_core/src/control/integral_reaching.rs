//! Integral sliding surface with the exponential reaching law (seed 002 eq. 10-12), in a stable
//! form (docs/parameters.md, "Asteroid landing").
//!
//! With sigma = q - q_ref, the seed's surface s = -q' + int(q_ref'' + c1 sigma + c2 sigma')
//! gives s = 0 => sigma'' = +c1 sigma + c2 sigma', unstable for c1, c2 > 0. The stable form is
//!
//! ```text
//! s = -sigma' - I,   I' = c1 sigma + c2 sigma',   I(0) = 0
//! u = -A1 r - A2 r' - G + q_ref'' - c1 sigma - c2 sigma' + k s + eps sgn(s)     (cf. eq. 12)
//! ```
//!
//! so that s' = -k s - eps sgn(s) (plus the disturbance) and, on s = 0,
//! sigma'' + c2 sigma' + c1 sigma = 0. The plant's modelled acceleration is -(A1 r + A2 r' + G)
//! cancelled; the integral I is advanced once per control period.

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, ReadError, Validate, check_axes};
use crate::lanes::{Real, add, mul, neg, scale, sub, zeros};
use crate::math::{BOUNDARY_LAYER, SWITCH, Switch};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

pub(super) const C1: Param = Param::axes("c1")
    .unit("1/s^2")
    .rule("c1 > 0")
    .doc("gain of sigma in the integral, I' = c1 sigma + c2 sigma'");
pub(super) const C2: Param = Param::axes("c2")
    .unit("1/s")
    .rule("c2 > 0")
    .doc("gain of sigma' in the integral");
pub(super) const K: Param = Param::axes("k")
    .unit("1/s")
    .rule("k >= 0")
    .doc("rate of the exponential reaching law s' = -k s - ...");
const EPSILON: Param = Param::axes("epsilon")
    .unit("q/s^2")
    .rule("epsilon >= 0")
    .doc("switching gain of the reaching law");

/// The integral surface with gains c1, c2 and the exponential rate k, shared with the fuzzy
/// variable-rate law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegralSurface<const D: usize, R = f64> {
    pub c1: SVector<R, D>,
    pub c2: SVector<R, D>,
    pub k: SVector<R, D>,
}

crate::gather_struct!(IntegralSurface<const D: usize, R> { lanes: [c1, c2, k], shared: [] });

impl<const D: usize, R: Real> IntegralSurface<D, R> {
    #[inline(always)]
    pub fn s(&self, integral: &SVector<R, D>, input: &LawInput<D, R>) -> SVector<R, D> {
        sub(&neg(&input.de), integral)
    }

    /// The command without its switching term.
    #[inline(always)]
    pub fn smooth_part(&self, s: &SVector<R, D>, input: &LawInput<D, R>) -> SVector<R, D> {
        let a = sub(&input.reference.acceleration, &input.drift);
        let a = sub(&a, &mul(&self.c1, &input.e));
        let a = sub(&a, &mul(&self.c2, &input.de));
        add(&a, &mul(&self.k, s))
    }

    #[inline(always)]
    pub fn advance(&self, integral: &mut SVector<R, D>, input: &LawInput<D, R>) {
        *integral = add(
            integral,
            &scale(
                &add(&mul(&self.c1, &input.e), &mul(&self.c2, &input.de)),
                input.dt,
            ),
        );
    }
}

impl<const D: usize> Validate for IntegralSurface<D> {
    fn validate(&self) -> Result<(), ParamError> {
        check_axes(&C1, self.c1.as_slice(), |v| v > 0.0)?;
        check_axes(&C2, self.c2.as_slice(), |v| v > 0.0)?;
        check_axes(&K, self.k.as_slice(), |v| v >= 0.0)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegralExponentialReaching<const D: usize, R = f64> {
    pub surface: IntegralSurface<D, R>,
    pub epsilon: SVector<R, D>,
    pub switch: Switch<R>,
}

crate::gather_struct!(IntegralExponentialReaching<const D: usize, R> {
    lanes: [surface, epsilon, switch],
    shared: [],
});

impl<const D: usize, R: Real> ControlLaw<R, D> for IntegralExponentialReaching<D, R> {
    /// The integral I of the surface.
    type Memory = SVector<R, D>;
    const DIAGNOSTICS: &'static [&'static str] = &["s", "integral"];

    #[inline(always)]
    fn start(&self, _input: &LawInput<D, R>) -> SVector<R, D> {
        zeros()
    }

    #[inline(always)]
    fn command(&self, integral: &SVector<R, D>, input: &LawInput<D, R>) -> SVector<R, D> {
        let s = self.surface.s(integral, input);
        let smooth = self.surface.smooth_part(&s, input);
        let mut a = smooth;
        for i in 0..D {
            a[i] = smooth[i] + self.epsilon[i] * self.switch.apply(s[i]);
        }
        a
    }

    #[inline(always)]
    fn advance(&self, integral: &mut SVector<R, D>, input: &LawInput<D, R>) {
        self.surface.advance(integral, input);
    }

    #[inline(always)]
    fn diagnostics(&self, integral: &SVector<R, D>, input: &LawInput<D, R>, out: &mut [R]) {
        out[..D].copy_from_slice(self.surface.s(integral, input).as_slice());
        out[D..2 * D].copy_from_slice(integral.as_slice());
    }
}

impl<const D: usize> Validate for IntegralExponentialReaching<D> {
    fn validate(&self) -> Result<(), ParamError> {
        self.surface.validate()?;
        check_axes(&EPSILON, self.epsilon.as_slice(), |v| v >= 0.0)?;
        super::validate_switch(&self.switch)
    }
}

impl<const D: usize> FromParams for IntegralSurface<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            c1: p.axes(&C1)?,
            c2: p.axes(&C2)?,
            k: p.axes(&K)?,
        })
    }
}

impl<const D: usize> Declared for IntegralExponentialReaching<D> {
    const SCHEMA: Schema = Schema::new(&[C1, C2, K, EPSILON, SWITCH, BOUNDARY_LAYER]);
}

impl<const D: usize> FromParams for IntegralExponentialReaching<D> {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            surface: IntegralSurface::from_params(p)?,
            epsilon: p.axes(&EPSILON)?,
            switch: Switch::from_params(p)?,
        })
    }
}
