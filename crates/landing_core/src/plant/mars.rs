//! Mars powered descent (seed 001 section III.A).
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
//!
//! A real engine is limited otherwise ([`MarsLander::engine`]): its thrust magnitude lies in
//! `[min_throttle T_max, T_max]` and points within `pointing_limit` of +z. The commanded force
//! is then projected onto that set: first onto the pointing cone (the Euclidean projection onto
//! a second-order cone: inside it the force is kept; in its polar cone it becomes zero; else it
//! goes to the nearest point of the boundary ray in its own vertical half-plane), then its
//! magnitude is clamped into the throttle range along the same direction (a zero force becomes
//! the minimum thrust straight up). Scaling keeps the direction, so both constraints hold after
//! the second step. The engine is always on, as in the convexified powered-descent problem
//! (Acikmese and Ploen 2007), whose lossless relaxation assumes it.

use nalgebra::{SVector, Vector3};

use super::{Plant, PlantModel};
use crate::actuator::{ActuatorSpec, CONTROL_DELAY, ENGINE_TIME_CONSTANT};
use crate::error::{ParamError, ReadError, Validate, check, check_axes, require};
use crate::gravity::{GRAVITY, GravityField, Uniform};
use crate::lanes::math::{INV_LN2_16, exp16};
use crate::lanes::{Gather, Real, filled, norm, zeros};
use crate::navigation::{FILTER, Navigation, SENSOR};
use crate::params::{Declared, FromParams, Param, ParamSource, Schema};

pub type MarsState<R = f64> = SVector<R, 7>;

/// Farthest a lander may be from the target, m (1e8 m, about 30 Mars radii: the plant's flat
/// surface and uniform gravity are meaningless far before). Beyond it a case is stopped and
/// flagged out of its domain.
pub const MAX_RANGE: f64 = 1e8;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarsLander<R = f64> {
    /// Specific impulse, s (225 s, seed reference [1]).
    pub isp: R,
    /// Effective cross-sectional areas perpendicular to x, y, z, m^2 (seed Table I).
    pub area: Vector3<R>,
    pub gravity: Uniform<R>,
    /// Standard gravity used in the rocket equation, m/s^2.
    pub g0: R,
    /// Whether the plant has drag; the guidance then models it too. Shared by a block.
    pub drag: bool,
    /// k_d of seed eq. 12, kg/m.
    pub drag_coefficient: R,
    /// h_d of seed eq. 12, 1/m (the seed's 0.0009; the underlying Mars model uses 0.00009).
    pub density_decay: R,
    /// Per-axis thrust limit |F_i| <= F_max, N; infinite for none.
    pub thrust_limit: Vector3<R>,
    /// Limit on |F|, N; infinite for none.
    pub thrust_magnitude_limit: R,
    /// The least |F| as a fraction of `thrust_magnitude_limit` (the engine is always on).
    pub min_throttle: R,
    /// Largest angle of F from +z, rad, in (0, pi/2]; pi/2 only forbids thrusting down.
    pub pointing_limit: R,
    /// Whether the engine's magnitude and pointing limits apply (any of them is set): shared by
    /// a block, so that a lander without them pays nothing for them.
    pub engine: bool,
    /// The command's transport delay, whole control periods (an integer >= 0).
    pub control_delay: R,
    /// The engine's first-order lag time constant, s; 0 for none.
    pub engine_time_constant: R,
    /// The sensor and filter the law reads through; None for the true state.
    pub navigation: Option<Navigation<3, R>>,
}

crate::gather_struct!(MarsLander<R> {
    lanes: [isp, area, gravity, g0, drag_coefficient, density_decay, thrust_limit,
            thrust_magnitude_limit, min_throttle, pointing_limit, control_delay,
            engine_time_constant, navigation],
    shared: [drag, engine],
});

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
            thrust_magnitude_limit: f64::INFINITY,
            min_throttle: 0.0,
            pointing_limit: std::f64::consts::FRAC_PI_2,
            engine: false,
            control_delay: 0.0,
            engine_time_constant: 0.0,
            navigation: None,
        }
    }
}

impl<R: Real> MarsLander<R> {
    /// The engine's projection of a commanded force `f` (see the module's comment): onto the
    /// cone within `pointing_limit` of +z, then into `[min_throttle, 1] T_max` in magnitude.
    #[inline(always)]
    pub fn engine_force(&self, f: &Vector3<R>) -> Vector3<R> {
        let zero = R::zero();
        let (s, c) = (self.pointing_limit.sin(), self.pointing_limit.cos());
        let r = (f[0] * f[0] + f[1] * f[1]).sqrt();
        let z = f[2];
        let inside = (r * c).simd_le(z * s);
        let along = r * s + z * c; // the force's component along the cone's boundary ray
        let polar = along.simd_le(zero);
        // the boundary ray in the force's vertical half-plane: (s h/r, c); r > 0 off the axis
        let k = R::select(r.simd_gt(zero), along * s / r, zero);
        let projected = Vector3::new(k * f[0], k * f[1], along * c);
        let keep = |v: R, p: R| R::select(inside, v, R::select(polar, zero, p));
        let g = Vector3::new(
            keep(f[0], projected[0]),
            keep(f[1], projected[1]),
            keep(f[2], projected[2]),
        );
        let n = norm(&g);
        let (hi, lo) = (
            self.thrust_magnitude_limit,
            self.min_throttle * self.thrust_magnitude_limit,
        );
        // the throttle range: scaled along the force's own direction (1 ulp inside the bound,
        // so that rounding cannot put it outside); a zero force becomes the least thrust up
        let shrink = R::splat(1.0 - f64::EPSILON);
        let grow = R::splat(1.0 + f64::EPSILON);
        let scale = R::select(
            n.simd_gt(hi),
            hi / n * shrink,
            R::select(n.simd_lt(lo) & n.simd_gt(zero), lo / n * grow, R::one()),
        );
        let off = n.simd_le(zero) & lo.simd_gt(zero);
        Vector3::new(
            R::select(off, zero, g[0] * scale),
            R::select(off, zero, g[1] * scale),
            R::select(off, lo * grow, g[2] * scale),
        )
    }

    /// Drag acceleration at altitude `rz`, velocity `v` and mass `m`.
    #[inline(always)]
    pub fn drag_acceleration(&self, rz: R, v: &Vector3<R>, m: R) -> Vector3<R> {
        Prepared::new(self).drag(rz, v, R::one() / m)
    }

    /// The command's delay and the engine's lag.
    #[inline(always)]
    pub fn actuator_spec(&self) -> ActuatorSpec<R> {
        ActuatorSpec {
            delay: self.control_delay,
            time_constant: self.engine_time_constant,
        }
    }

    /// Effective exhaust velocity `c = Isp g_e`, m/s.
    #[inline(always)]
    pub fn exhaust_velocity(&self) -> R {
        self.isp * self.g0
    }
}

/// A lander with the reciprocals its derivative divides by: `1 / A_i` and `1 / (Isp g_e)`,
/// computed once when a block is gathered. A vector division costs a dozen multiplications
/// and the divider is the busiest unit of the W1 step; left in the derivative these four
/// divisions ran at every RK4 stage (LLVM did not hoist them out of the step loop), and
/// computing them here made W1 6 % faster (BENCHMARKS.md). Division is correctly rounded, so
/// `x * (1 / a)` has the same bits at every level and lane width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prepared<R> {
    lander: MarsLander<R>,
    inv_area: Vector3<R>,
    inv_exhaust_velocity: R,
    /// `-h_d 16/ln2`: the density `exp(-h_d rz)` is `exp16(density_16 rz)`, the exponential
    /// with the shorter reduction (`lanes::math::exp16`), 4 of its 30 operations fewer at each
    /// of the four evaluations per step.
    density_16: R,
}

impl<R: Real> Prepared<R> {
    #[inline(always)]
    pub fn new(lander: &MarsLander<R>) -> Self {
        let one = R::one();
        Self {
            lander: *lander,
            inv_area: Vector3::new(
                one / lander.area[0],
                one / lander.area[1],
                one / lander.area[2],
            ),
            inv_exhaust_velocity: one / lander.exhaust_velocity(),
            density_16: -lander.density_decay * INV_LN2_16,
        }
    }

    /// Drag acceleration (seed eq. 12) at altitude `rz`, velocity `v` and `1 / m`.
    #[inline(always)]
    fn drag(&self, rz: R, v: &Vector3<R>, inv_m: R) -> Vector3<R> {
        let p = &self.lander;
        if !p.drag {
            return zeros();
        }
        let k = -p.drag_coefficient * exp16(self.density_16 * rz) * inv_m;
        Vector3::new(
            k * v[0] * v[0].abs() * self.inv_area[0],
            k * v[1] * v[1].abs() * self.inv_area[1],
            k * v[2] * v[2].abs() * self.inv_area[2],
        )
    }
}

impl<R: Real> Gather<R> for Prepared<R> {
    type Case = MarsLander;

    #[inline]
    fn gather<'a>(case: &dyn Fn(usize) -> &'a MarsLander) -> Self {
        Self::new(&MarsLander::<R>::gather(case))
    }

    fn same_shape(a: &MarsLander, b: &MarsLander) -> bool {
        <MarsLander<R> as Gather<R>>::same_shape(a, b)
    }
}

#[inline(always)]
fn split<R: Real>(x: &MarsState<R>) -> (Vector3<R>, Vector3<R>, R) {
    (
        Vector3::new(x[0], x[1], x[2]),
        Vector3::new(x[3], x[4], x[5]),
        x[6],
    )
}

#[inline(always)]
fn pack<R: Real>(v: &Vector3<R>, a: &Vector3<R>, mdot: R) -> MarsState<R> {
    MarsState::from([v[0], v[1], v[2], a[0], a[1], a[2], mdot])
}

impl<R: Real> Plant<R, 3> for Prepared<R> {
    type State = MarsState<R>;

    #[inline(always)]
    fn coordinates(&self, x: &MarsState<R>) -> (Vector3<R>, Vector3<R>) {
        let (r, v, _) = split(x);
        (r, v)
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, x: &MarsState<R>) -> Vector3<R> {
        let (r, v, m) = split(x);
        self.lander.gravity.acceleration(&r) + self.drag(r[2], &v, R::one() / m)
    }

    #[inline(always)]
    fn inertia(&self, x: &MarsState<R>) -> Vector3<R> {
        filled(x[6])
    }

    #[inline(always)]
    fn actuate(&self, x: &MarsState<R>, acceleration: &Vector3<R>) -> Vector3<R> {
        self.limit(&(acceleration * x[6]))
    }

    #[inline(always)]
    fn limit(&self, f: &Vector3<R>) -> Vector3<R> {
        if self.lander.engine {
            // validation keeps the per-axis limit off when the engine's limits are on
            return self.lander.engine_force(f);
        }
        let lim = &self.lander.thrust_limit;
        Vector3::new(
            f[0].clamp(-lim[0], lim[0]),
            f[1].clamp(-lim[1], lim[1]),
            f[2].clamp(-lim[2], lim[2]),
        )
    }

    #[inline(always)]
    fn actuator(&self) -> Option<ActuatorSpec<R>> {
        Some(self.lander.actuator_spec())
    }

    #[inline(always)]
    fn navigation(&self) -> Option<&Navigation<3, R>> {
        self.lander.navigation.as_ref()
    }

    #[inline(always)]
    fn derivative(&self, t: f64, x: &MarsState<R>, u: &Vector3<R>, d: &Vector3<R>) -> MarsState<R> {
        self.derivative_with_drift(t, x, u, d, &self.modelled_acceleration(t, x))
    }

    #[inline(always)]
    fn derivative_with_drift(
        &self,
        _t: f64,
        x: &MarsState<R>,
        u: &Vector3<R>,
        d: &Vector3<R>,
        drift: &Vector3<R>,
    ) -> MarsState<R> {
        let (_, v, m) = split(x);
        let inv_m = R::one() / m;
        let a = Vector3::new(
            u[0] * inv_m + drift[0] + d[0],
            u[1] * inv_m + drift[1] + d[1],
            u[2] * inv_m + drift[2] + d[2],
        );
        // |u| is the same at every stage of a period: the compiler computes it once per period
        let mdot = -norm(u) * self.inv_exhaust_velocity;
        pack(&v, &a, mdot)
    }

    /// Positive mass, and within [`MAX_RANGE`] of the target: the flat, uniform-gravity model
    /// means nothing farther away.
    #[inline(always)]
    fn in_domain(&self, x: &MarsState<R>) -> R::Mask {
        let r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
        x[6].simd_gt(R::zero()) & r2.simd_le(R::splat(MAX_RANGE * MAX_RANGE))
    }

    #[inline(always)]
    fn mass(&self, x: &MarsState<R>) -> Option<R> {
        Some(x[6])
    }

    #[inline(always)]
    fn altitude(&self, x: &MarsState<R>) -> Option<R> {
        Some(x[2])
    }

    fn altitude_axis(&self) -> Option<usize> {
        Some(2)
    }
}

/// The one-case plant is its prepared form, the reciprocals computed per call.
impl<R: Real> Plant<R, 3> for MarsLander<R> {
    type State = MarsState<R>;

    fn coordinates(&self, x: &MarsState<R>) -> (Vector3<R>, Vector3<R>) {
        Prepared::new(self).coordinates(x)
    }

    fn modelled_acceleration(&self, t: f64, x: &MarsState<R>) -> Vector3<R> {
        Prepared::new(self).modelled_acceleration(t, x)
    }

    fn inertia(&self, x: &MarsState<R>) -> Vector3<R> {
        Prepared::new(self).inertia(x)
    }

    fn actuate(&self, x: &MarsState<R>, acceleration: &Vector3<R>) -> Vector3<R> {
        Prepared::new(self).actuate(x, acceleration)
    }

    fn limit(&self, f: &Vector3<R>) -> Vector3<R> {
        Prepared::new(self).limit(f)
    }

    fn actuator(&self) -> Option<ActuatorSpec<R>> {
        Prepared::new(self).actuator()
    }

    fn navigation(&self) -> Option<&Navigation<3, R>> {
        self.navigation.as_ref()
    }

    fn derivative(&self, t: f64, x: &MarsState<R>, u: &Vector3<R>, d: &Vector3<R>) -> MarsState<R> {
        Prepared::new(self).derivative(t, x, u, d)
    }

    fn in_domain(&self, x: &MarsState<R>) -> R::Mask {
        Prepared::new(self).in_domain(x)
    }

    fn mass(&self, x: &MarsState<R>) -> Option<R> {
        Prepared::new(self).mass(x)
    }

    fn altitude(&self, x: &MarsState<R>) -> Option<R> {
        Prepared::new(self).altitude(x)
    }

    fn altitude_axis(&self) -> Option<usize> {
        Some(2)
    }
}

impl PlantModel<3> for MarsLander {
    type At<R: Real> = Prepared<R>;
    type Blocks = crate::kernel::Wide;
    const STATE_NAMES: &'static [&'static str] = &["rx", "ry", "rz", "vx", "vy", "vz", "m"];
    const CONTROL_NAMES: &'static [&'static str] = &["Fx", "Fy", "Fz"];

    fn check_initial(&self, x: &[f64]) -> Result<(), ParamError> {
        for (i, v) in x.iter().enumerate() {
            require(true, "x0", *v, "finite values").map_err(|e| e.on_axis(i))?;
        }
        require(x[6] > 0.0, "x0", x[6], "mass x0[6] > 0").map_err(|e| e.on_axis(6))
    }
}

impl Validate for MarsLander {
    fn validate(&self) -> Result<(), ParamError> {
        check(&ISP, self.isp, |v| v > 0.0)?;
        check_axes(&AREA, self.area.as_slice(), |a| a > 0.0)?;
        self.gravity.validate()?;
        check(&G0, self.g0, |v| v > 0.0)?;
        check(&DRAG_COEFFICIENT, self.drag_coefficient, |v| v >= 0.0)?;
        check(&DENSITY_DECAY, self.density_decay, |v| v >= 0.0)?;
        for (i, &l) in self.thrust_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(ParamError::new(THRUST_LIMIT.name, l, THRUST_LIMIT.rule).on_axis(i));
            }
        }
        if self.thrust_magnitude_limit != f64::INFINITY {
            // infinite is "none"
            check(&THRUST_MAGNITUDE_LIMIT, self.thrust_magnitude_limit, |v| {
                v > 0.0
            })?;
        }
        check(&MIN_THROTTLE, self.min_throttle, |v| {
            (0.0..1.0).contains(&v)
        })?;
        check(&POINTING_LIMIT, self.pointing_limit, |v| {
            v > 0.0 && v <= std::f64::consts::FRAC_PI_2
        })?;
        self.actuator_spec().validate()?;
        if self.min_throttle > 0.0 && self.thrust_magnitude_limit.is_infinite() {
            let rule = "min_throttle > 0 needs a thrust_magnitude_limit";
            return Err(ParamError::new(MIN_THROTTLE.name, self.min_throttle, rule));
        }
        if self.engine && self.thrust_limit.iter().any(|l| l.is_finite()) {
            let rule = "thrust_limit (per axis) not combined with thrust_magnitude_limit or pointing_limit";
            return Err(ParamError::new(
                THRUST_LIMIT.name,
                self.thrust_limit[0],
                rule,
            ));
        }
        Ok(())
    }
}

const ISP: Param = Param::scalar("isp")
    .unit("s")
    .rule("isp > 0")
    .doc("specific impulse");
const AREA: Param = Param::axes("area")
    .unit("m^2")
    .rule("area > 0")
    .doc("effective cross-sections perpendicular to x, y, z");
const DRAG: Param =
    Param::flag("drag").doc("whether the plant has drag (the guidance then models it)");
const THRUST_LIMIT: Param = Param::axes("thrust_limit")
    .unit("N")
    .rule("thrust_limit > 0")
    .optional()
    .doc("per-axis limit on |F_i|; None for unlimited");
const THRUST_MAGNITUDE_LIMIT: Param = Param::scalar("thrust_magnitude_limit")
    .unit("N")
    .rule("thrust_magnitude_limit > 0")
    .optional()
    .doc("limit on |F| (the engine's full thrust); None for unlimited");
const MIN_THROTTLE: Param = Param::scalar("min_throttle")
    .unit("1")
    .rule("0 <= min_throttle < 1")
    .optional()
    .doc("the least |F| as a fraction of thrust_magnitude_limit (the engine is always on)");
const POINTING_LIMIT: Param = Param::scalar("pointing_limit")
    .unit("rad")
    .rule("0 < pointing_limit <= pi/2")
    .optional()
    .doc("largest angle of the thrust from +z; None for any direction");
const DRAG_COEFFICIENT: Param = Param::scalar("drag_coefficient")
    .unit("kg/m")
    .rule("drag_coefficient >= 0")
    .doc("k_d of the Mars fixed-time guidance paper, eq. 12");
const DENSITY_DECAY: Param = Param::scalar("density_decay")
    .unit("1/m")
    .rule("density_decay >= 0")
    .doc("h_d of the Mars fixed-time guidance paper, eq. 12");
const G0: Param = Param::scalar("g0")
    .unit("m/s^2")
    .rule("g0 > 0")
    .doc("standard gravity in the rocket equation");

impl Declared for MarsLander {
    const SCHEMA: Schema = Schema::new(&[
        ISP,
        AREA,
        GRAVITY,
        DRAG,
        THRUST_LIMIT,
        THRUST_MAGNITUDE_LIMIT,
        MIN_THROTTLE,
        POINTING_LIMIT,
        CONTROL_DELAY,
        ENGINE_TIME_CONSTANT,
        SENSOR,
        FILTER,
        DRAG_COEFFICIENT,
        DENSITY_DECAY,
        G0,
    ]);
}

impl FromParams for MarsLander {
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let magnitude = p.opt_scalar(&THRUST_MAGNITUDE_LIMIT)?;
        let pointing = p.opt_scalar(&POINTING_LIMIT)?;
        Ok(Self {
            isp: p.scalar(&ISP)?,
            area: p.axes::<3>(&AREA)?,
            gravity: Uniform {
                g0: p.scalar(&GRAVITY)?,
            },
            g0: p.scalar(&G0)?,
            drag: p.flag(&DRAG)?,
            drag_coefficient: p.scalar(&DRAG_COEFFICIENT)?,
            density_decay: p.scalar(&DENSITY_DECAY)?,
            thrust_limit: p
                .opt_axes::<3>(&THRUST_LIMIT)?
                .unwrap_or(Vector3::repeat(f64::INFINITY)),
            thrust_magnitude_limit: magnitude.unwrap_or(f64::INFINITY),
            min_throttle: p.opt_scalar(&MIN_THROTTLE)?.unwrap_or(0.0),
            pointing_limit: pointing.unwrap_or(std::f64::consts::FRAC_PI_2),
            engine: magnitude.is_some() || pointing.is_some(),
            control_delay: p.opt_scalar(&CONTROL_DELAY)?.unwrap_or(0.0),
            engine_time_constant: p.opt_scalar(&ENGINE_TIME_CONSTANT)?.unwrap_or(0.0),
            navigation: Navigation::read(p)?,
        })
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

    /// A deterministic spread of forces: every direction, magnitudes from 0 to 3 T_max.
    fn forces(n: usize) -> impl Iterator<Item = Vector3<f64>> {
        (0..n).map(|k| {
            let u = (k as f64 * 0.618_033_988_749_895).fract();
            let v = (k as f64 * 0.754_877_666_246_693).fract();
            let w = (k as f64 * 0.569_840_290_998_053).fract();
            let (z, phi) = (2.0 * u - 1.0, std::f64::consts::TAU * v);
            let h = (1.0 - z * z).sqrt();
            Vector3::new(h * phi.cos(), h * phi.sin(), z) * (3.0 * 40_000.0 * w)
        })
    }

    #[test]
    fn the_engine_projection_meets_every_limit() {
        let p = MarsLander {
            thrust_magnitude_limit: 40_000.0,
            min_throttle: 0.3,
            pointing_limit: 0.35,
            engine: true,
            ..Default::default()
        };
        for f in forces(20_000).chain([Vector3::zeros(), Vector3::new(0.0, 0.0, -5.0)]) {
            let g = p.engine_force(&f);
            let n = g.norm();
            assert!(
                (12_000.0 * (1.0 - 1e-15)..=40_000.0 * (1.0 + 1e-15)).contains(&n),
                "{f:?} -> {g:?}"
            );
            let angle = (g[2] / n).clamp(-1.0, 1.0).acos();
            assert!(angle <= 0.35 + 1e-12, "{f:?} -> {g:?}: {angle}");
            // a force already allowed is kept
            let f_angle = (f[2] / f.norm()).acos();
            if f_angle < 0.35 && f.norm() > 12_000.0 && f.norm() < 40_000.0 {
                assert_eq!(g, f);
            }
        }
    }

    #[test]
    fn the_pointing_step_is_the_euclidean_projection_onto_the_cone() {
        // Moreau: p is the projection of f onto the cone K iff p in K, f - p in the polar cone
        // and <f - p, p> = 0; without magnitude limits the engine's force is that p
        let theta: f64 = 0.5;
        let p = MarsLander {
            pointing_limit: theta,
            engine: true,
            ..Default::default()
        };
        let (s, c) = theta.sin_cos();
        for f in forces(5_000) {
            let g = p.engine_force(&f);
            let q = f - g;
            let scale = f.norm().max(1.0);
            let (gr, qr) = (g.xy().norm(), q.xy().norm());
            assert!(gr * c <= g[2] * s + 1e-9 * scale, "p in K: {f:?} -> {g:?}");
            // the polar cone of K: the angle from -z at most pi/2 - theta
            assert!(
                qr * s <= -q[2] * c + 1e-9 * scale,
                "f - p in the polar cone: {f:?} -> {g:?}"
            );
            assert!(
                q.dot(&g).abs() <= 1e-9 * scale * scale,
                "orthogonal: {f:?} -> {g:?}"
            );
        }
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
