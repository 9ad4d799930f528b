//! The space-tethered satellite in its orbital plane (seed 003): two fidelities that
//! share one controller interface.
//!
//! Generalized coordinates `q = [phi, theta]`: `phi` is the in-plane angle of the line from the
//! main satellite to the sub-satellite's centre, measured from the local vertical (nadir)
//! towards the orbit's positive rotation sense; `theta` is the sub-satellite's attitude in the
//! same sense, zero when its attachment face looks at the main satellite across a vertical
//! tether. Both are angles in the orbital (Hill) frame, whose axes are x radial (up), y along
//! the orbital velocity, z along the orbit normal.
//!
//! The commands are the in-plane thrust `u_phi` (N, on the sub-satellite's centre,
//! perpendicular to that line, towards increasing phi) and the attitude torque `u_theta`
//! (N m), each saturated. The controller sees the inertia of seed eq. 17 in the actuators'
//! units: `M = diag(mu L0, m_s a^2 / 6)` with the reduced mass `mu = m_m m_s / (m_m + m_s)`.
//! The seed prints `M1 = mu L0`; the dynamics give `mu L0^2`, the moment of inertia about the
//! main satellite, which multiplies phi'' to give the thrust's moment `L0 u_phi`. Dividing that
//! row by the lever arm `L0` gives the seed's `mu L0` and keeps `u_phi` a force, so the plant's
//! `inertia` (q'' gains u_i / inertia_i) is the seed's M as printed: the 0.1 N limit then
//! allows phi'' up to 1.0e-4 rad/s^2, which is what the seed's 30 s manoeuvre needs.
//!
//! - [`TetheredSimplified`]: the rigid dumbbell of seed eq. 17, with the unknown terms f made
//!   explicit (gravity gradient, the tension's torque on the sub-satellite).
//! - [`TetheredFlexible`]: the validation plant, a lumped-mass tether in the Hill frame.

mod flexible;
mod names;
mod simplified;

pub use flexible::{
    NODE_COUNTS, NODES, NodeCount, TetheredFlexible, TetheredFlexible2, TetheredFlexible4,
    TetheredFlexible8, TetheredFlexible16,
};
pub use names::MAX_NODES;
pub use simplified::TetheredSimplified;

use nalgebra::Vector2;

use crate::error::{ParamError, ReadError, Validate, check, check_also, require};
use crate::lanes::Real;
use crate::params::{FromParams, Param, ParamSource};

crate::named! {
    /// The two models of the tethered satellite.
    pub enum Fidelity {
        /// The rigid dumbbell of seed eq. 17 ([`TetheredSimplified`]).
        Simplified => "simplified",
        /// The lumped-mass tether ([`TetheredFlexible`]).
        Flexible => "flexible",
    }
}

/// Earth's gravitational parameter, m^3/s^2 (WGS 84).
pub const MU_EARTH: f64 = 3.986_004_418e14;
/// Earth's equatorial radius, m (WGS 84).
pub const EARTH_RADIUS: f64 = 6_378_137.0;

/// The model's name.
pub const FIDELITY: Param = Param::choice("fidelity", Fidelity::NAMES)
    .doc("simplified: the rigid dumbbell of the tethered-satellite paper, eq. 17; flexible: the lumped-mass tether");
const MAIN_MASS: Param = Param::scalar("main_mass")
    .unit("kg")
    .rule("main_mass > 0")
    .doc("main satellite mass m_m");
const SUB_MASS: Param = Param::scalar("sub_mass")
    .unit("kg")
    .rule("sub_mass > 0")
    .doc("sub-satellite mass m_s");
const TETHER_LENGTH: Param = Param::scalar("tether_length")
    .unit("m")
    .rule("tether_length > 0")
    .doc("unstretched tether length L0");
const SIDE: Param = Param::scalar("side")
    .unit("m")
    .rule("side > 0")
    .also("side < tether_length")
    .doc("side a of the cubic sub-satellite; the tether is attached a/2 from its centre");
const ORBIT_ALTITUDE: Param = Param::scalar("orbit_altitude")
    .unit("m")
    .rule("orbit_altitude > -6378137 m")
    .also("a positive, finite mean motion sqrt(mu / (R + orbit_altitude)^3)")
    .doc("altitude of the main satellite's circular Earth orbit");
const THRUST_LIMIT: Param = Param::scalar("thrust_limit")
    .unit("N")
    .rule("thrust_limit > 0")
    .optional()
    .doc("limit on the in-plane thrust; None for none");
const TORQUE_LIMIT: Param = Param::scalar("torque_limit")
    .unit("N m")
    .rule("torque_limit > 0")
    .optional()
    .doc("limit on the attitude torque; None for thrust_limit * side / 2");

/// The tethered satellite's parameters, both fidelities' (the simplified model skips the
/// tether's).
pub const TETHERED_SATELLITE: &[Param] = &[
    FIDELITY,
    MAIN_MASS,
    SUB_MASS,
    TETHER_LENGTH,
    SIDE,
    ORBIT_ALTITUDE,
    THRUST_LIMIT,
    TORQUE_LIMIT,
    flexible::NODES,
    flexible::TETHER_DENSITY,
    flexible::AXIAL_STIFFNESS,
    flexible::AXIAL_DAMPING,
];

/// Mean motion of a circular Earth orbit at `altitude` (m): `sqrt(mu / (R + h)^3)`, rad/s.
pub fn orbital_rate(altitude: f64) -> Result<f64, ParamError> {
    check(&ORBIT_ALTITUDE, altitude, |h| h > -EARTH_RADIUS)?;
    let r = EARTH_RADIUS + altitude;
    let rate = (MU_EARTH / (r * r * r)).sqrt();
    // beyond about 5e102 m, r^3 overflows and the orbit would not turn at all
    check_also(&ORBIT_ALTITUDE, altitude, rate > 0.0 && rate.is_finite())?;
    Ok(rate)
}

/// The parameters both fidelities share (seed Table 1 and the orbit of its section 4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TetherBody<R = f64> {
    /// Main satellite mass m_m, kg (seed: 1000 kg). It enters the controller's model (the
    /// reduced mass); in the plant the main satellite is the origin of the Hill frame.
    pub main_mass: R,
    /// Sub-satellite mass m_s, kg (seed: 10 kg).
    pub sub_mass: R,
    /// Unstretched tether length L0, m (seed: 100 m).
    pub length: R,
    /// Side a of the cubic sub-satellite, m (seed: 1 m); the tether is attached a/2 from its
    /// centre.
    pub side: R,
    /// Mean motion n of the main satellite's circular orbit, rad/s (500 km: 1.1068e-3).
    pub orbital_rate: R,
    /// Limit on |u_phi|, N (seed: 0.1 N); infinite for none.
    pub thrust_limit: R,
    /// Limit on |u_theta|, N m ([`TetherBody::default_torque_limit`] unless set).
    pub torque_limit: R,
}

crate::gather_struct!(TetherBody<R> {
    lanes: [main_mass, sub_mass, length, side, orbital_rate, thrust_limit, torque_limit],
    shared: [],
});

impl Default for TetherBody {
    fn default() -> Self {
        Self {
            main_mass: 1000.0,
            sub_mass: 10.0,
            length: 100.0,
            side: 1.0,
            orbital_rate: orbital_rate(500e3).expect("a valid altitude"),
            thrust_limit: 0.1,
            torque_limit: 0.1 * 0.5,
        }
    }
}

impl TetherBody {
    /// The torque limit when none is set: the thrust limit times the lever arm a/2, as if the
    /// attitude were steered by the same thrusters at the cube's faces (docs/parameters.md).
    pub fn default_torque_limit(side: f64, thrust_limit: f64) -> f64 {
        0.5 * side * thrust_limit
    }
}

impl<R: Real> TetherBody<R> {
    /// `M = diag(mu L0, m_s a^2 / 6)`: the seed's eq. 17 inertia in the actuators' units.
    #[inline(always)]
    pub fn inertia(&self) -> Vector2<R> {
        let mu = self.main_mass * self.sub_mass / (self.main_mass + self.sub_mass);
        Vector2::new(mu * self.length, self.moment_of_inertia())
    }

    /// The cube's moment of inertia about its centre, `m_s a^2 / 6`, kg m^2.
    #[inline(always)]
    pub fn moment_of_inertia(&self) -> R {
        self.sub_mass * self.side * self.side / 6.0
    }

    /// Thrust and torque for a commanded generalized acceleration, saturated.
    #[inline(always)]
    pub fn actuate(&self, acceleration: &Vector2<R>) -> Vector2<R> {
        self.actuate_with(&self.inertia(), acceleration)
    }

    /// [`Self::actuate`] with the inertia [`Self::inertia`] computed beforehand (the flexible
    /// tether's prepared block keeps it).
    #[inline(always)]
    pub(crate) fn actuate_with(&self, m: &Vector2<R>, acceleration: &Vector2<R>) -> Vector2<R> {
        Vector2::new(
            (acceleration[0] * m[0]).clamp(-self.thrust_limit, self.thrust_limit),
            (acceleration[1] * m[1]).clamp(-self.torque_limit, self.torque_limit),
        )
    }
}

impl TetherBody {
    /// The figures the Python layer shows: the controller's inertia, the orbital rate and the
    /// actuator limits.
    pub(crate) fn figures(&self) -> Vec<(&'static str, Vec<f64>)> {
        vec![
            ("inertia", self.inertia().as_slice().to_vec()),
            ("orbital_rate", vec![self.orbital_rate]),
            ("thrust_limit", vec![self.thrust_limit]),
            ("torque_limit", vec![self.torque_limit]),
        ]
    }
}

impl Validate for TetherBody {
    fn validate(&self) -> Result<(), ParamError> {
        check(&MAIN_MASS, self.main_mass, |v| v > 0.0)?;
        check(&SUB_MASS, self.sub_mass, |v| v > 0.0)?;
        check(&TETHER_LENGTH, self.length, |v| v > 0.0)?;
        check(&SIDE, self.side, |v| v > 0.0)?;
        check_also(&SIDE, self.side, self.side < self.length)?;
        require(
            self.orbital_rate > 0.0,
            "orbital_rate",
            self.orbital_rate,
            "orbital_rate > 0",
        )?;
        for (param, v) in [
            (&THRUST_LIMIT, self.thrust_limit),
            (&TORQUE_LIMIT, self.torque_limit),
        ] {
            if v.is_nan() || v <= 0.0 {
                return Err(ParamError::new(param.name, v, param.rule));
            }
        }
        Ok(())
    }
}

impl FromParams for TetherBody {
    /// Table 1 and the orbit: the orbital rate from `orbit_altitude` (a circular Earth orbit);
    /// no limit where `thrust_limit` is absent, and the torque limit from the thrust limit
    /// where `torque_limit` is ([`TetherBody::default_torque_limit`]).
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let side = p.scalar(&SIDE)?;
        let thrust_limit = p.opt_scalar(&THRUST_LIMIT)?.unwrap_or(f64::INFINITY);
        Ok(Self {
            main_mass: p.scalar(&MAIN_MASS)?,
            sub_mass: p.scalar(&SUB_MASS)?,
            length: p.scalar(&TETHER_LENGTH)?,
            side,
            orbital_rate: orbital_rate(p.scalar(&ORBIT_ALTITUDE)?)?,
            thrust_limit,
            torque_limit: p
                .opt_scalar(&TORQUE_LIMIT)?
                .unwrap_or(Self::default_torque_limit(side, thrust_limit)),
        })
    }
}

/// Tension of a rigid tether holding the sub-satellite's centre at distance `rho` with the
/// line at angle `phi` turning at `dphi` in the Hill frame: the radial balance
/// `T = m_s rho ((dphi + n)^2 + n^2 (3 cos^2 phi - 1))` (centripetal plus gravity gradient),
/// floored at zero because a tether cannot push.
#[inline(always)]
pub fn rigid_tension<R: Real>(sub_mass: R, rho: R, n: R, phi: R, dphi: R) -> R {
    let c = phi.cos();
    let w = dphi + n;
    (sub_mass * rho * (w * w + n * n * (R::splat(3.0) * c * c - 1.0))).max(R::zero())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_motion_at_500_km() {
        // a 500 km circular orbit takes 94.6 minutes
        let n = orbital_rate(500e3).unwrap();
        let period = std::f64::consts::TAU / n;
        assert!((period / 60.0 - 94.6).abs() < 0.05, "{period}");
        assert_eq!(orbital_rate(-7e6).unwrap_err().param, "orbit_altitude");
    }

    #[test]
    fn inertia_is_the_seed_mass_matrix_in_actuator_units() {
        let b = TetherBody::default();
        let m = b.inertia();
        // mu = 1000 * 10 / 1010 kg, times L0 = 100 m; 10 * 1 / 6 kg m^2
        assert!((m[0] - 1000.0 * 10.0 / 1010.0 * 100.0).abs() < 1e-12);
        assert!((m[1] - 10.0 / 6.0).abs() < 1e-15);
        // a command inside the limits comes back as inertia times acceleration
        let u = b.actuate(&Vector2::new(5e-5, -0.01));
        assert!((u[0] - 5e-5 * m[0]).abs() < 1e-15 && (u[1] + 0.01 * m[1]).abs() < 1e-15);
        // and is clipped outside them
        assert_eq!(
            b.actuate(&Vector2::new(1.0, -1.0)),
            Vector2::new(0.1, -0.05)
        );
    }

    #[test]
    fn rigid_tension_is_three_n_squared_at_rest_and_never_negative() {
        let n = 1e-3;
        let t = rigid_tension(10.0, 100.0, n, 0.0, 0.0);
        assert!((t - 3.0 * n * n * 10.0 * 100.0).abs() < 1e-18);
        // spinning backwards at the orbital rate on the horizontal: gravity gradient pushes in
        assert_eq!(
            rigid_tension(10.0, 100.0, n, std::f64::consts::FRAC_PI_2, -n),
            0.0
        );
    }

    #[test]
    fn validation_names_the_parameter() {
        let b = TetherBody {
            side: 200.0,
            ..Default::default()
        };
        assert_eq!(b.validate().unwrap_err().rule, "side < tether_length");
        let b = TetherBody {
            torque_limit: 0.0,
            ..Default::default()
        };
        assert_eq!(b.validate().unwrap_err().param, "torque_limit");
        assert!(TetherBody::default().validate().is_ok());
    }
}
