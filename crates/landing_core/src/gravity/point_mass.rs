use nalgebra::Vector3;

use super::{GravityField, GravityModel};
use crate::error::{ParamError, ReadError, Validate, check};
use crate::lanes::{Real, dot, scale_by};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

/// A point mass, `U = mu / r`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMass<R = f64> {
    /// Gravitational parameter G M, m^3/s^2.
    pub mu: R,
}

crate::gather_struct!(PointMass<R> { lanes: [mu], shared: [] });

impl Validate for PointMass {
    fn validate(&self) -> Result<(), ParamError> {
        check(&MU, self.mu, |v| v > 0.0)
    }
}

impl<R: Real> GravityField<R> for PointMass<R> {
    #[inline(always)]
    fn acceleration(&self, r: &Vector3<R>) -> Vector3<R> {
        let r2 = dot(r, r);
        scale_by(r, -self.mu / (r2 * r2.sqrt()))
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<R>) -> R {
        self.mu / dot(r, r).sqrt()
    }
}

impl GravityModel for PointMass {
    type At<R: Real> = PointMass<R>;
}

const MU: Param = Param::scalar("mu")
    .unit("m^3/s^2")
    .rule("mu > 0")
    .doc("gravitational parameter G M");

impl Declared for PointMass {
    const SCHEMA: Schema = Schema::new(&[MU]);
}

impl FromParams for PointMass {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self { mu: p.scalar(&MU)? })
    }
}
