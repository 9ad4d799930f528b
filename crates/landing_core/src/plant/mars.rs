//! Mars powered descent (seed 001 section III.A, SPEC 3.1).
//!
//! State `[rx, ry, rz, vx, vy, vz, m]` in the inertial frame at the target (crossrange,
//! downrange, altitude with z up):
//!
//! ```text
//! r' = v
//! v' = F/m + g + a_drag + a_p(t)
//! m' = -|F| / (Isp g_e)                                    (seed eq. 13)
//! a_drag_i = -k_d v_i |v_i| exp(-h_d rz) / (A_i m)          (seed eq. 12, sign fixed)
//! ```
//!
//! The seed prints `v_i^2`, which pushes a falling lander down faster; drag opposes motion,
//! hence `v_i |v_i|`. The command is an acceleration `a`; the engine force `F = m a` is clipped
//! per axis to the thrust limit and held over the control period, so the acceleration it gives
//! follows the mass down within the period.

use nalgebra::{SVector, Vector3};

use super::Plant;
use crate::error::{ParamError, require, require_axes};
use crate::gravity::{GravityField, Uniform};

pub type MarsState = SVector<f64, 7>;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarsLander {
    /// Specific impulse, s (225 s, seed reference [1]).
    pub isp: f64,
    /// Effective cross-sectional areas perpendicular to x, y, z, m^2 (seed Table I).
    pub area: Vector3<f64>,
    pub gravity: Uniform,
    /// Standard gravity used in the rocket equation, m/s^2.
    pub g0: f64,
    /// Whether the plant has drag; the guidance then models it too.
    pub drag: bool,
    /// k_d of seed eq. 12, kg/m.
    pub drag_coefficient: f64,
    /// h_d of seed eq. 12, 1/m (the seed's 0.0009; the underlying Mars model uses 0.00009).
    pub density_decay: f64,
    /// Per-axis thrust limit |F_i| <= F_max, N; infinite for none.
    pub thrust_limit: Vector3<f64>,
}

impl Default for MarsLander {
    fn default() -> Self {
        Self {
            isp: 225.0,
            area: Vector3::new(6.0, 7.5, 8.7),
            gravity: Uniform { g0: 3.7114 },
            g0: 9.807,
            drag: true,
            drag_coefficient: 0.699,
            density_decay: 0.0009,
            thrust_limit: Vector3::repeat(f64::INFINITY),
        }
    }
}

impl MarsLander {
    /// Drag acceleration at altitude `rz`, velocity `v` and mass `m`.
    #[inline(always)]
    pub fn drag_acceleration(&self, rz: f64, v: &Vector3<f64>, m: f64) -> Vector3<f64> {
        if !self.drag {
            return Vector3::zeros();
        }
        let k = -self.drag_coefficient * (-self.density_decay * rz).exp() / m;
        Vector3::new(
            k * v[0] * v[0].abs() / self.area[0],
            k * v[1] * v[1].abs() / self.area[1],
            k * v[2] * v[2].abs() / self.area[2],
        )
    }

    /// Effective exhaust velocity `c = Isp g_e`, m/s.
    #[inline(always)]
    pub fn exhaust_velocity(&self) -> f64 {
        self.isp * self.g0
    }
}

#[inline(always)]
fn split(x: &MarsState) -> (Vector3<f64>, Vector3<f64>, f64) {
    (
        x.fixed_rows::<3>(0).into(),
        x.fixed_rows::<3>(3).into(),
        x[6],
    )
}

impl Plant<3> for MarsLander {
    type State = MarsState;
    const STATE_NAMES: &'static [&'static str] = &["rx", "ry", "rz", "vx", "vy", "vz", "m"];
    const CONTROL_NAMES: &'static [&'static str] = &["Fx", "Fy", "Fz"];

    #[inline(always)]
    fn coordinates(&self, x: &MarsState) -> (Vector3<f64>, Vector3<f64>) {
        let (r, v, _) = split(x);
        (r, v)
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, x: &MarsState) -> Vector3<f64> {
        let (r, v, m) = split(x);
        self.gravity.acceleration(&r) + self.drag_acceleration(r[2], &v, m)
    }

    #[inline(always)]
    fn inertia(&self, x: &MarsState) -> Vector3<f64> {
        Vector3::repeat(x[6])
    }

    #[inline(always)]
    fn actuate(&self, x: &MarsState, acceleration: &Vector3<f64>) -> Vector3<f64> {
        let f = acceleration * x[6];
        let lim = &self.thrust_limit;
        Vector3::new(
            f[0].clamp(-lim[0], lim[0]),
            f[1].clamp(-lim[1], lim[1]),
            f[2].clamp(-lim[2], lim[2]),
        )
    }

    #[inline(always)]
    fn derivative(&self, _t: f64, x: &MarsState, u: &Vector3<f64>, d: &Vector3<f64>) -> MarsState {
        let (r, v, m) = split(x);
        let a = u / m + self.gravity.acceleration(&r) + self.drag_acceleration(r[2], &v, m) + d;
        let mdot = -u.norm() / self.exhaust_velocity();
        MarsState::from([v[0], v[1], v[2], a[0], a[1], a[2], mdot])
    }

    #[inline(always)]
    fn admissible(&self, x: &MarsState) -> bool {
        x.iter().all(|v| v.is_finite()) && x[6] > 0.0
    }

    #[inline(always)]
    fn mass(&self, x: &MarsState) -> Option<f64> {
        Some(x[6])
    }

    #[inline(always)]
    fn altitude(&self, x: &MarsState) -> Option<f64> {
        Some(x[2])
    }

    fn check_initial(&self, x: &MarsState) -> Result<(), ParamError> {
        for (i, v) in x.iter().enumerate() {
            require(true, "x0", *v, "finite values").map_err(|e| e.on_axis(i))?;
        }
        require(x[6] > 0.0, "x0", x[6], "mass x0[6] > 0").map_err(|e| e.on_axis(6))
    }

    fn validate(&self) -> Result<(), ParamError> {
        require(self.isp > 0.0, "isp", self.isp, "isp > 0")?;
        require_axes(self.area.as_slice(), "area", "area > 0", |a| a > 0.0)?;
        require(
            self.gravity.g0 >= 0.0,
            "gravity",
            self.gravity.g0,
            "gravity >= 0",
        )?;
        require(self.g0 > 0.0, "g0", self.g0, "g0 > 0")?;
        require(
            self.drag_coefficient >= 0.0,
            "drag_coefficient",
            self.drag_coefficient,
            "drag_coefficient >= 0",
        )?;
        require(
            self.density_decay >= 0.0,
            "density_decay",
            self.density_decay,
            "density_decay >= 0",
        )?;
        for (i, &l) in self.thrust_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(ParamError::new("thrust_limit", l, "thrust_limit > 0").on_axis(i));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drag_opposes_motion_and_matches_the_formula() {
        let p = MarsLander::default();
        let v = Vector3::new(100.0, -15.0, -75.0);
        let a = p.drag_acceleration(1500.0, &v, 1905.0);
        for i in 0..3 {
            assert!(
                a[i] * v[i] < 0.0,
                "axis {i}: drag {} velocity {}",
                a[i],
                v[i]
            );
        }
        // hand computation for x: 0.699 * 100^2 * exp(-0.0009 * 1500) / (6.0 * 1905)
        let ax = 0.699 * 1.0e4 * (-1.35f64).exp() / (6.0 * 1905.0);
        assert!((a[0] + ax).abs() < 1e-15);
        let off = MarsLander { drag: false, ..p };
        assert_eq!(off.drag_acceleration(1500.0, &v, 1905.0), Vector3::zeros());
    }

    #[test]
    fn actuator_scales_by_mass_and_clips_per_axis() {
        let p = MarsLander {
            thrust_limit: Vector3::repeat(50_000.0),
            ..Default::default()
        };
        let x = MarsState::from([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 2000.0]);
        let f = p.actuate(&x, &Vector3::new(10.0, -40.0, 30.0));
        assert_eq!(f, Vector3::new(20_000.0, -50_000.0, 50_000.0));
    }

    #[test]
    fn validation_names_the_parameter() {
        let p = MarsLander {
            isp: -1.0,
            ..Default::default()
        };
        assert_eq!(p.validate().unwrap_err().param, "isp");
        let p = MarsLander {
            area: Vector3::new(1.0, 0.0, 1.0),
            ..Default::default()
        };
        let e = p.validate().unwrap_err();
        assert_eq!((e.param, e.axis), ("area", Some(1)));
        assert!(MarsLander::default().validate().is_ok());
    }
}
