//! Second-degree spherical harmonics (seed 002 eq. 2-4).

use nalgebra::Vector3;

use super::{GravityField, GravityModel};
use crate::error::{ParamError, ReadError, Validate, check};
use crate::lanes::{Real, add, dot, scale_by, sub};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

/// `U = (mu/r) [1 + (R0/r)^2 (C20 (3 z^2/r^2 - 1)/2 + 3 C22 (x^2 - y^2)/r^2)]`.
///
/// Written as `U = mu/r + mu R0^2 P(r) / r^5` with the quadratic form
/// `P = C20 (2 z^2 - x^2 - y^2)/2 + 3 C22 (x^2 - y^2)`, so that
/// `g = grad U = -mu r / r^3 + mu R0^2 (grad P / r^5 - 5 P r / r^7)`. (The seed's eq. 4 writes
/// the field through attitude angles and is garbled in print; this is the gradient of its eq. 2
/// truncated at degree two, checked against finite differences of U in the tests.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Harmonic2<R = f64> {
    /// Gravitational parameter, m^3/s^2.
    pub mu: R,
    /// Reference radius, m.
    pub r0: R,
    pub c20: R,
    pub c22: R,
}

crate::gather_struct!(Harmonic2<R> { lanes: [mu, r0, c20, c22], shared: [] });

impl Harmonic2 {
    /// Seed 002 Table 2 (433 Eros): mu = 4.842e5 m^3/s^2, R0 = 1138.5 m, C20 = -0.043,
    /// C22 = 0.058.
    pub fn seed002() -> Self {
        Self {
            mu: 4.842e5,
            r0: 1138.5,
            c20: -0.043,
            c22: 0.058,
        }
    }
}

impl Validate for Harmonic2 {
    fn validate(&self) -> Result<(), ParamError> {
        check(&MU, self.mu, |v| v > 0.0)?;
        check(&R0, self.r0, |v| v > 0.0)?;
        check(&C20, self.c20, |_| true)?;
        check(&C22, self.c22, |_| true)
    }
}

impl<R: Real> Harmonic2<R> {
    #[inline(always)]
    fn form(&self, r: &Vector3<R>) -> R {
        let (x2, y2, z2) = (r[0] * r[0], r[1] * r[1], r[2] * r[2]);
        R::splat(0.5) * self.c20 * (z2 * 2.0 - x2 - y2) + R::splat(3.0) * self.c22 * (x2 - y2)
    }
}

impl<R: Real> GravityField<R> for Harmonic2<R> {
    #[inline(always)]
    fn acceleration(&self, r: &Vector3<R>) -> Vector3<R> {
        let r2 = dot(r, r);
        let inv = R::one() / r2.sqrt();
        let inv2 = inv * inv;
        let inv5 = inv2 * inv2 * inv;
        let grad_p = Vector3::new(
            (self.c22 * 6.0 - self.c20) * r[0],
            -(self.c20 + self.c22 * 6.0) * r[1],
            self.c20 * 2.0 * r[2],
        );
        let k = self.mu * self.r0 * self.r0;
        let monopole = scale_by(r, -self.mu * inv2 * inv);
        let quadrupole = sub(
            &scale_by(&grad_p, inv5),
            &scale_by(r, R::splat(5.0) * self.form(r) * inv5 * inv2),
        );
        add(&monopole, &scale_by(&quadrupole, k))
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<R>) -> R {
        let rn = dot(r, r).sqrt();
        let rn2 = rn * rn;
        self.mu / rn + self.mu * self.r0 * self.r0 * self.form(r) / (rn2 * rn2 * rn)
    }
}

impl GravityModel for Harmonic2 {
    type At<R: Real> = Harmonic2<R>;
}

const MU: Param = Param::scalar("mu")
    .unit("m^3/s^2")
    .rule("mu > 0")
    .doc("gravitational parameter G M");
const R0: Param = Param::scalar("r0")
    .unit("m")
    .rule("r0 > 0")
    .doc("reference radius R0 of the coefficients");
const C20: Param = Param::scalar("c20")
    .unit("1")
    .doc("second-degree zonal coefficient C20");
const C22: Param = Param::scalar("c22")
    .unit("1")
    .doc("second-degree sectoral coefficient C22");

impl Declared for Harmonic2 {
    const SCHEMA: Schema = Schema::new(&[MU, R0, C20, C22]);
}

impl FromParams for Harmonic2 {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        Ok(Self {
            mu: p.scalar(&MU)?,
            r0: p.scalar(&R0)?,
            c20: p.scalar(&C20)?,
            c22: p.scalar(&C22)?,
        })
    }
}
