//! Gravity fields. Sign convention (SPEC 3.2): the potential U is positive for a point mass
//! (U = +mu/r), and the field is its gradient, g = grad U, so gravity always attracts.

mod uniform;

pub use uniform::Uniform;

use nalgebra::Vector3;

pub trait GravityField: Copy + Send + Sync {
    /// Field (acceleration) at `r`, m/s^2.
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64>;
    /// Potential at `r` with `acceleration = grad potential`, m^2/s^2.
    fn potential(&self, r: &Vector3<f64>) -> f64;
}
