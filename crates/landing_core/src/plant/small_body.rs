//! A probe near a small body, in the body's rotating frame (seeds 000 and 002; SPEC 3.2).
//!
//! State `[x, y, z, vx, vy, vz]`, rotation rate omega about z:
//!
//! ```text
//! x'' - 2 omega y' - omega^2 x = g_x + u_x + d_x
//! y'' + 2 omega x' - omega^2 y = g_y + u_y + d_y
//! z''                          = g_z + u_z + d_z
//! ```
//!
//! The command u is a control acceleration (both seeds command accelerations), optionally
//! limited per axis. The frame terms and the gravity field are the model the laws cancel.

use nalgebra::{SVector, Vector3};

use super::Plant;
use crate::error::{ParamError, require};
use crate::gravity::GravityField;

pub type SmallBodyState = SVector<f64, 6>;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallBody<G: GravityField> {
    pub gravity: G,
    /// Rotation rate of the body about its z axis, rad/s.
    pub omega: f64,
    /// Per-axis limit on |u_i|, m/s^2; infinite for none.
    pub acceleration_limit: Vector3<f64>,
}

impl<G: GravityField> SmallBody<G> {
    pub fn new(gravity: G, omega: f64) -> Self {
        Self {
            gravity,
            omega,
            acceleration_limit: Vector3::repeat(f64::INFINITY),
        }
    }

    /// Coriolis and centrifugal accelerations of the rotating frame.
    #[inline(always)]
    pub fn frame_acceleration(&self, r: &Vector3<f64>, v: &Vector3<f64>) -> Vector3<f64> {
        let w = self.omega;
        Vector3::new(
            2.0 * w * v[1] + w * w * r[0],
            -2.0 * w * v[0] + w * w * r[1],
            0.0,
        )
    }
}

#[inline(always)]
fn split(x: &SmallBodyState) -> (Vector3<f64>, Vector3<f64>) {
    (x.fixed_rows::<3>(0).into(), x.fixed_rows::<3>(3).into())
}

impl<G: GravityField> Plant<3> for SmallBody<G> {
    type State = SmallBodyState;
    const STATE_NAMES: &'static [&'static str] = &["x", "y", "z", "vx", "vy", "vz"];
    const CONTROL_NAMES: &'static [&'static str] = &["ux", "uy", "uz"];

    #[inline(always)]
    fn coordinates(&self, x: &SmallBodyState) -> (Vector3<f64>, Vector3<f64>) {
        split(x)
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, x: &SmallBodyState) -> Vector3<f64> {
        let (r, v) = split(x);
        self.frame_acceleration(&r, &v) + self.gravity.acceleration(&r)
    }

    #[inline(always)]
    fn inertia(&self, _x: &SmallBodyState) -> Vector3<f64> {
        Vector3::repeat(1.0)
    }

    #[inline(always)]
    fn actuate(&self, _x: &SmallBodyState, a: &Vector3<f64>) -> Vector3<f64> {
        let l = &self.acceleration_limit;
        Vector3::new(
            a[0].clamp(-l[0], l[0]),
            a[1].clamp(-l[1], l[1]),
            a[2].clamp(-l[2], l[2]),
        )
    }

    #[inline(always)]
    fn derivative(
        &self,
        t: f64,
        x: &SmallBodyState,
        u: &Vector3<f64>,
        d: &Vector3<f64>,
    ) -> SmallBodyState {
        let (_, v) = split(x);
        let a = self.modelled_acceleration(t, x) + u + d;
        SmallBodyState::from([v[0], v[1], v[2], a[0], a[1], a[2]])
    }

    fn validate(&self) -> Result<(), ParamError> {
        require(true, "omega", self.omega, "finite values")?;
        for (i, &l) in self.acceleration_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(
                    ParamError::new("acceleration_limit", l, "acceleration_limit > 0").on_axis(i),
                );
            }
        }
        self.gravity.validate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{Integrator, Rk4};

    #[derive(Clone, Copy)]
    struct NoGravity;

    impl GravityField for NoGravity {
        fn acceleration(&self, _r: &Vector3<f64>) -> Vector3<f64> {
            Vector3::zeros()
        }
        fn potential(&self, _r: &Vector3<f64>) -> f64 {
            0.0
        }
        fn validate(&self) -> Result<(), ParamError> {
            Ok(())
        }
    }

    #[test]
    fn a_point_at_rest_in_inertial_space_turns_backwards_in_the_body_frame() {
        // R fixed inertially; in the frame turning at omega about z it reads r(t) = Rz(-omega t) R,
        // which the Coriolis and centrifugal terms alone must reproduce.
        let w = 3.3118e-4;
        let p = SmallBody::new(NoGravity, w);
        let big_r = Vector3::new(3200.0, 1300.0, 9000.0);
        let mut x = SmallBodyState::from([
            big_r[0],
            big_r[1],
            big_r[2],
            w * big_r[1],
            -w * big_r[0],
            0.0,
        ]);
        let f =
            |t: f64, s: &SmallBodyState| p.derivative(t, s, &Vector3::zeros(), &Vector3::zeros());
        let h = 1.0;
        for k in 0..8000 {
            x = Rk4.step(&f, k as f64 * h, &x, h);
        }
        let th = w * 8000.0;
        let expect = Vector3::new(
            big_r[0] * th.cos() + big_r[1] * th.sin(),
            -big_r[0] * th.sin() + big_r[1] * th.cos(),
            big_r[2],
        );
        assert!(
            (Vector3::new(x[0], x[1], x[2]) - expect).norm() < 1e-6,
            "{x:?} vs {expect:?}"
        );
    }

    #[test]
    fn the_jacobi_integral_is_conserved_without_control() {
        // C = v^2/2 - omega^2 (x^2 + y^2)/2 - U is constant in a uniformly rotating frame
        let g = crate::gravity::PointMass { mu: 4.46e5 };
        let w = 3.3118e-4;
        let p = SmallBody::new(g, w);
        let jacobi = |s: &SmallBodyState| {
            let (r, v) = split(s);
            0.5 * v.norm_squared() - 0.5 * w * w * (r[0] * r[0] + r[1] * r[1]) - g.potential(&r)
        };
        let mut x = SmallBodyState::from([30_000.0, 1000.0, 5000.0, 0.5, 3.0, -0.2]);
        let c0 = jacobi(&x);
        let f =
            |t: f64, s: &SmallBodyState| p.derivative(t, s, &Vector3::zeros(), &Vector3::zeros());
        for k in 0..20_000 {
            x = Rk4.step(&f, k as f64, &x, 1.0);
        }
        assert!(
            ((jacobi(&x) - c0) / c0).abs() < 1e-9,
            "{} vs {c0}",
            jacobi(&x)
        );
    }
}
