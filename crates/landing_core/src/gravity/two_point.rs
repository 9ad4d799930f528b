//! Two mass points (seed 000 eq. 2, sign fixed: gravity attracts; SPEC 3.2).

use nalgebra::Vector3;

use super::GravityField;
use crate::error::{ParamError, require};

/// Newton's constant, m^3 / (kg s^2) (CODATA 2018).
pub const G: f64 = 6.6743e-11;

/// `U = sum_i G M_i / |r - r_i|`. The seed prints the gradient with the wrong sign and omits
/// where the mass points are; [`TwoPointMass::eros`] gives the documented defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TwoPointMass {
    /// Gravitational parameters G M_i, m^3/s^2.
    pub mu: [f64; 2],
    /// Positions of the mass points in the body frame, m.
    pub positions: [Vector3<f64>; 2],
}

impl TwoPointMass {
    /// 433 Eros as a dumbbell: M = 6.687e15 kg (the seed's "6.69e5 kg" is a typo) split in two
    /// halves at (+-d, 0, 0), d = a / sqrt(5) with a = 17.2 km, so that the dumbbell has the
    /// second moment M a^2 / 5 of a homogeneous ellipsoid of semi-axis a along x.
    pub fn eros() -> Self {
        let mu = G * 6.687e15 / 2.0;
        let d = 17_200.0 / 5f64.sqrt();
        Self {
            mu: [mu, mu],
            positions: [Vector3::new(d, 0.0, 0.0), Vector3::new(-d, 0.0, 0.0)],
        }
    }

    fn validate_fields(&self) -> Result<(), ParamError> {
        for (i, &m) in self.mu.iter().enumerate() {
            require(m > 0.0, "masses", m, "masses > 0").map_err(|e| e.on_axis(i))?;
        }
        for p in &self.positions {
            for (i, v) in p.iter().enumerate() {
                require(true, "positions", *v, "finite values").map_err(|e| e.on_axis(i))?;
            }
        }
        Ok(())
    }
}

impl GravityField for TwoPointMass {
    #[inline(always)]
    fn acceleration(&self, r: &Vector3<f64>) -> Vector3<f64> {
        let mut g = Vector3::zeros();
        for (mu, p) in self.mu.iter().zip(&self.positions) {
            let d = r - p;
            let d2 = d.norm_squared();
            g -= d * (mu / (d2 * d2.sqrt()));
        }
        g
    }

    fn validate(&self) -> Result<(), ParamError> {
        self.validate_fields()
    }

    #[inline(always)]
    fn potential(&self, r: &Vector3<f64>) -> f64 {
        self.mu
            .iter()
            .zip(&self.positions)
            .map(|(mu, p)| mu / (r - p).norm())
            .sum()
    }
}
