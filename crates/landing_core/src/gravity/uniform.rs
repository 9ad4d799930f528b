use nalgebra::Vector3;

use super::GravityField;

/// Uniform field `g = (0, 0, -g0)` of a flat planet near its surface (Mars descent, seed 001).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uniform {
    pub g0: f64,
}

impl GravityField for Uniform {
    #[inline(always)]
    fn acceleration(&self, _r: &Vector3<f64>) -> Vector3<f64> {
        Vector3::new(0.0, 0.0, -self.g0)
    }

    fn validate(&self) -> Result<(), crate::error::ParamError> {
        crate::error::require(self.g0 >= 0.0, "gravity", self.g0, "gravity >= 0")
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<f64>) -> f64 {
        -self.g0 * r[2]
    }
}
