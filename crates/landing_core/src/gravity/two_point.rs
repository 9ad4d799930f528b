//! Two mass points (seed 000 eq. 2, sign fixed: gravity attracts).

use nalgebra::Vector3;

use super::{GravityField, GravityModel};
use crate::error::{ParamError, ReadError, Validate, check, require};
use crate::lanes::{Real, dot, scale_by, sub, zeros};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

/// Newton's constant, m^3 / (kg s^2) (CODATA 2018).
pub const G: f64 = 6.6743e-11;

/// `U = sum_i G M_i / |r - r_i|`. The seed prints the gradient with the wrong sign and omits
/// where the mass points are; [`TwoPointMass::eros`] gives the documented defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoPointMass<R = f64> {
    /// Gravitational parameters G M_i, m^3/s^2.
    pub mu: [R; 2],
    /// Positions of the mass points in the body frame, m.
    pub positions: [Vector3<R>; 2],
}

crate::gather_struct!(TwoPointMass<R> { lanes: [mu, positions], shared: [] });

impl TwoPointMass {
    /// 433 Eros as a dumbbell: M = 6.687e15 kg (the seed's "6.69e5 kg" is a typo) split in two
    /// halves at (+-d, 0, 0), d = a / sqrt(5) with a = 17.2 km, so that the dumbbell has the
    /// second moment M a^2 / 5 of a homogeneous ellipsoid of semi-axis a along x.
    pub fn eros() -> Self {
        Self::from_masses(
            [6.687e15 / 2.0; 2],
            [
                Vector3::new(17_200.0 / 5f64.sqrt(), 0.0, 0.0),
                Vector3::new(-17_200.0 / 5f64.sqrt(), 0.0, 0.0),
            ],
        )
    }

    /// The field of masses `m_i` (kg) at `positions`, with Newton's constant [`G`]:
    /// `mu_i = G m_i`.
    pub fn from_masses(masses: [f64; 2], positions: [Vector3<f64>; 2]) -> Self {
        Self::from_masses_with(G, masses, positions)
    }

    /// The same with another gravitational constant (m^3 / (kg s^2)).
    pub fn from_masses_with(g: f64, masses: [f64; 2], positions: [Vector3<f64>; 2]) -> Self {
        Self {
            mu: masses.map(|m| g * m),
            positions,
        }
    }
}

impl Validate for TwoPointMass {
    fn validate(&self) -> Result<(), ParamError> {
        // named as the user gives them (m1, m2, position1, position2); the field keeps G m_i
        const MU: [(&str, &Param); 2] = [("G m1", &M1), ("G m2", &M2)];
        for (&m, (name, param)) in self.mu.iter().zip(MU) {
            require(m > 0.0, name, m, param.rule)?;
        }
        for (p, param) in self.positions.iter().zip([&POSITION1, &POSITION2]) {
            for (i, v) in p.iter().enumerate() {
                check(param, *v, |_| true).map_err(|e| e.on_axis(i))?;
            }
        }
        Ok(())
    }
}

impl<R: Real> GravityField<R> for TwoPointMass<R> {
    #[inline(always)]
    fn acceleration(&self, r: &Vector3<R>) -> Vector3<R> {
        let mut g = zeros();
        for (mu, p) in self.mu.iter().zip(&self.positions) {
            let d = sub(r, p);
            let d2 = dot(&d, &d);
            g = sub(&g, &scale_by(&d, *mu / (d2 * d2.sqrt())));
        }
        g
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<R>) -> R {
        let mut u = R::zero();
        for (mu, p) in self.mu.iter().zip(&self.positions) {
            let d = r - p;
            u += *mu / dot(&d, &d).sqrt();
        }
        u
    }
}

impl GravityModel for TwoPointMass {
    type At<R: Real> = TwoPointMass<R>;
}

const M1: Param = Param::scalar("m1")
    .unit("kg")
    .rule("G m1 > 0")
    .doc("mass of the first point");
const M2: Param = Param::scalar("m2")
    .unit("kg")
    .rule("G m2 > 0")
    .doc("mass of the second point");
const POSITION1: Param = Param::axes("position1")
    .unit("m")
    .doc("position of the first point in the body frame");
const POSITION2: Param = Param::axes("position2")
    .unit("m")
    .doc("position of the second point in the body frame");
const G_PARAM: Param = Param::scalar("G")
    .unit("m^3/(kg s^2)")
    .doc("Newton's constant");

impl Declared for TwoPointMass {
    const SCHEMA: Schema = Schema::new(&[M1, M2, POSITION1, POSITION2, G_PARAM]);
}

impl FromParams for TwoPointMass {
    /// Masses `m1`, `m2` (kg) at `position1`, `position2` (m), with Newton's constant `G`.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let m = [p.scalar(&M1)?, p.scalar(&M2)?];
        let positions = [p.axes::<3>(&POSITION1)?, p.axes::<3>(&POSITION2)?];
        Ok(Self::from_masses_with(p.scalar(&G_PARAM)?, m, positions))
    }
}
