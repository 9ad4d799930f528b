use nalgebra::Vector3;

use super::GravityField;
use crate::error::{ParamError, require};

/// A point mass, `U = mu / r`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMass {
    /// Gravitational parameter G M, m^3/s^2.
    pub mu: f64,
}

impl PointMass {
    fn validate_fields(&self) -> Result<(), ParamError> {
        require(self.mu > 0.0, "mu", self.mu, "mu > 0")
    }
}

impl GravityField for PointMass {
    #[inline(always)]
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let r2 = r.norm_squared();
        r * (-self.mu / (r2 * r2.sqrt()))
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.validate_fields()
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<f64>) -> f64 {
        self.mu / r.norm()
    }
}
