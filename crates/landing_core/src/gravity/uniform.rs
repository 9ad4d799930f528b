use nalgebra::Vector3;

use super::{GravityField, GravityModel};
use crate::error::{ParamError, Validate, check};
use crate::lanes::Real;
use crate::params::Param;

/// Uniform field `g = (0, 0, -g0)` of a flat planet near its surface (Mars descent, seed 001).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uniform<R = f64> {
    pub g0: R,
}

crate::gather_struct!(Uniform<R> { lanes: [g0], shared: [] });

/// The field's strength, as the Mars lander's table gives it.
pub const GRAVITY: Param = Param::scalar("gravity")
    .unit("m/s^2")
    .rule("gravity >= 0")
    .doc("Mars surface gravity, along -z");

impl Validate for Uniform {
    fn validate(&self) -> Result<(), ParamError> {
        check(&GRAVITY, self.g0, |v| v >= 0.0)
    }
}

impl<R: Real> GravityField<R> for Uniform<R> {
    #[inline(always)]
    fn acceleration(&self, _r: &Vector3<R>) -> Vector3<R> {
        Vector3::new(R::zero(), R::zero(), -self.g0)
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<R>) -> R {
        -self.g0 * r[2]
    }
}

impl GravityModel for Uniform {
    type At<R: Real> = Uniform<R>;
}
