//! Integral sliding surface with the exponential reaching law (seed 002 eq. 10-12; SPEC 5
//! law 4), in the stable form SPEC section 5 fixes.
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
//! cancelled; the integral I is advanced once per control period (SPEC 2).

use nalgebra::SVector;

use super::{ControlLaw, LawInput};
use crate::error::{ParamError, require_axes};
use crate::math::Switch;

/// The integral surface with gains c1, c2 and the exponential rate k, shared with the fuzzy
/// variable-rate law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegralSurface<const D: usize> {
    pub c1: SVector<f64, D>,
    pub c2: SVector<f64, D>,
    pub k: SVector<f64, D>,
}

impl<const D: usize> IntegralSurface<D> {
    #[inline(always)]
    pub fn s(&self, integral: &SVector<f64, D>, input: &LawInput<D>) -> SVector<f64, D> {
        -input.de - integral
    }

    /// The command without its switching term.
    #[inline(always)]
    pub fn smooth_part(&self, s: &SVector<f64, D>, input: &LawInput<D>) -> SVector<f64, D> {
        input.reference.acceleration
            - input.drift
            - self.c1.component_mul(&input.e)
            - self.c2.component_mul(&input.de)
            + self.k.component_mul(s)
    }

    #[inline(always)]
    pub fn advance(&self, integral: &mut SVector<f64, D>, input: &LawInput<D>) {
        *integral +=
            (self.c1.component_mul(&input.e) + self.c2.component_mul(&input.de)) * input.dt;
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        require_axes(self.c1.as_slice(), "c1", "c1 > 0", |v| v > 0.0)?;
        require_axes(self.c2.as_slice(), "c2", "c2 > 0", |v| v > 0.0)?;
        require_axes(self.k.as_slice(), "k", "k >= 0", |v| v >= 0.0)
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegralExponentialReaching<const D: usize> {
    pub surface: IntegralSurface<D>,
    pub epsilon: SVector<f64, D>,
    pub switch: Switch,
}

impl<const D: usize> ControlLaw<D> for IntegralExponentialReaching<D> {
    /// The integral I of the surface.
    type Memory = SVector<f64, D>;
    const DIAGNOSTICS: &'static [&'static str] = &["s", "integral"];

    fn start(&self, _input: &LawInput<D>) -> SVector<f64, D> {
        SVector::zeros()
    }

    #[inline(always)]
    fn command(&self, integral: &SVector<f64, D>, input: &LawInput<D>) -> SVector<f64, D> {
        let s = self.surface.s(integral, input);
        let smooth = self.surface.smooth_part(&s, input);
        SVector::from_fn(|i, _| smooth[i] + self.epsilon[i] * self.switch.apply(s[i]))
    }

    #[inline(always)]
    fn advance(&self, integral: &mut SVector<f64, D>, input: &LawInput<D>) {
        self.surface.advance(integral, input);
    }

    fn diagnostics(&self, integral: &SVector<f64, D>, input: &LawInput<D>, out: &mut [f64]) {
        out[..D].copy_from_slice(self.surface.s(integral, input).as_slice());
        out[D..2 * D].copy_from_slice(integral.as_slice());
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.surface.validate()?;
        require_axes(self.epsilon.as_slice(), "epsilon", "epsilon >= 0", |v| {
            v >= 0.0
        })?;
        super::validate_switch(&self.switch)
    }
}
