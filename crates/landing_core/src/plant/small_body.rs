//! A probe near a small body, in the body's rotating frame (seeds 000 and 002).
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

use super::{Plant, PlantModel};
use crate::actuator::{ActuatorSpec, CONTROL_DELAY, ENGINE_TIME_CONSTANT};
use crate::error::{ParamError, ReadError, Validate, check};
use crate::gravity::{GravityField, GravityModel};
use crate::lanes::{Gather, Real, add, filled, norm, scale_by};
use crate::navigation::{FILTER, Navigation, SENSOR};
use crate::params::{FromParams, Layout, Param, ParamSource};

pub type SmallBodyState<R = f64> = SVector<R, 6>;

/// A small body with the gravity field `G` (one case's, e.g. `SmallBody<PointMass>`, or a
/// block's, `SmallBody<PointMass<Lanes<W>>, Lanes<W>>`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallBody<G, R = f64> {
    pub gravity: G,
    /// Rotation rate of the body about its z axis, rad/s.
    pub omega: R,
    /// Per-axis limit on |u_i|, m/s^2; infinite for none.
    pub acceleration_limit: Vector3<R>,
    /// Limit on |u|, m/s^2; infinite for none.
    pub acceleration_magnitude_limit: R,
    /// Whether any case of the block has a magnitude limit (shared: a probe without one pays
    /// nothing for it).
    pub magnitude_limited: bool,
    /// The command's transport delay, whole control periods (an integer >= 0).
    pub control_delay: R,
    /// The thrusters' first-order lag time constant, s; 0 for none.
    pub engine_time_constant: R,
    /// The sensor and filter the law reads through (shared by a block); None for the true
    /// state.
    pub navigation: Option<Navigation<3, R>>,
}

impl<G> SmallBody<G> {
    pub fn new(gravity: G, omega: f64) -> Self {
        Self {
            gravity,
            omega,
            acceleration_limit: Vector3::repeat(f64::INFINITY),
            acceleration_magnitude_limit: f64::INFINITY,
            magnitude_limited: false,
            control_delay: 0.0,
            engine_time_constant: 0.0,
            navigation: None,
        }
    }
}

impl<R: Real, G: Gather<R>> Gather<R> for SmallBody<G, R> {
    type Case = SmallBody<G::Case, f64>;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self {
        Self {
            gravity: G::gather(&|i| &case(i).gravity),
            omega: Gather::gather(&|i| &case(i).omega),
            acceleration_limit: Gather::gather(&|i| &case(i).acceleration_limit),
            acceleration_magnitude_limit: Gather::gather(&|i| {
                &case(i).acceleration_magnitude_limit
            }),
            magnitude_limited: case(0).magnitude_limited,
            control_delay: Gather::gather(&|i| &case(i).control_delay),
            engine_time_constant: Gather::gather(&|i| &case(i).engine_time_constant),
            navigation: Gather::gather(&|i| &case(i).navigation),
        }
    }

    fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
        G::same_shape(&a.gravity, &b.gravity)
            && <Option<Navigation<3, R>>>::same_shape(&a.navigation, &b.navigation)
            && a.magnitude_limited == b.magnitude_limited
    }
}

impl<G, R: Real> SmallBody<G, R> {
    /// Coriolis and centrifugal accelerations of the rotating frame.
    #[inline(always)]
    pub fn frame_acceleration(&self, r: &Vector3<R>, v: &Vector3<R>) -> Vector3<R> {
        let w = self.omega;
        let w2 = w * w;
        Vector3::new(
            w * 2.0 * v[1] + w2 * r[0],
            -w * 2.0 * v[0] + w2 * r[1],
            R::zero(),
        )
    }
}

#[inline(always)]
fn split<R: Real>(x: &SmallBodyState<R>) -> (Vector3<R>, Vector3<R>) {
    (
        Vector3::new(x[0], x[1], x[2]),
        Vector3::new(x[3], x[4], x[5]),
    )
}

impl<R: Real, G: GravityField<R>> Plant<R, 3> for SmallBody<G, R> {
    type State = SmallBodyState<R>;

    #[inline(always)]
    fn coordinates(&self, x: &SmallBodyState<R>) -> (Vector3<R>, Vector3<R>) {
        split(x)
    }

    #[inline(always)]
    fn modelled_acceleration(&self, _t: f64, x: &SmallBodyState<R>) -> Vector3<R> {
        let (r, v) = split(x);
        add(
            &self.frame_acceleration(&r, &v),
            &self.gravity.acceleration(&r),
        )
    }

    #[inline(always)]
    fn inertia(&self, _x: &SmallBodyState<R>) -> Vector3<R> {
        filled(R::one())
    }

    #[inline(always)]
    fn actuate(&self, _x: &SmallBodyState<R>, a: &Vector3<R>) -> Vector3<R> {
        self.limit(a)
    }

    /// Clipped per axis, then scaled into the ball |u| <= the magnitude limit (1 ulp inside,
    /// so that rounding cannot put it outside): scaling towards 0 keeps the box's bounds, so
    /// both hold. (Not the Euclidean projection onto the box and ball together, which has no
    /// closed form; the same as it where only one of them binds.)
    #[inline(always)]
    fn limit(&self, a: &Vector3<R>) -> Vector3<R> {
        let l = &self.acceleration_limit;
        let mut u = *a;
        for i in 0..3 {
            u[i] = a[i].clamp(-l[i], l[i]);
        }
        if self.magnitude_limited {
            let n = norm(&u);
            let hi = self.acceleration_magnitude_limit;
            let s = R::select(
                n.simd_gt(hi),
                hi / n * R::splat(1.0 - f64::EPSILON),
                R::one(),
            );
            u = scale_by(&u, s);
        }
        u
    }

    #[inline(always)]
    fn actuator(&self) -> Option<ActuatorSpec<R>> {
        Some(ActuatorSpec {
            delay: self.control_delay,
            time_constant: self.engine_time_constant,
        })
    }

    #[inline(always)]
    fn navigation(&self) -> Option<&Navigation<3, R>> {
        self.navigation.as_ref()
    }

    #[inline(always)]
    fn derivative(
        &self,
        t: f64,
        x: &SmallBodyState<R>,
        u: &Vector3<R>,
        d: &Vector3<R>,
    ) -> SmallBodyState<R> {
        self.derivative_with_drift(t, x, u, d, &self.modelled_acceleration(t, x))
    }

    #[inline(always)]
    fn derivative_with_drift(
        &self,
        _t: f64,
        x: &SmallBodyState<R>,
        u: &Vector3<R>,
        d: &Vector3<R>,
        drift: &Vector3<R>,
    ) -> SmallBodyState<R> {
        let a = add(&add(drift, u), d);
        SmallBodyState::from([x[3], x[4], x[5], a[0], a[1], a[2]])
    }
}

impl<G: GravityModel> PlantModel<3> for SmallBody<G> {
    type At<R: Real> = SmallBody<G::At<R>, R>;
    // Wide, like the Mars lander (the other three-axis plant): the laws of three-axis plants
    // are then compiled for three lane types, not five. Measured against narrow blocks in one
    // run (BENCHMARKS.md): W5 (Mamdani law) 111 ms instead of 160, W3 22.2 ms instead of 19.9.
    type Blocks = crate::kernel::Wide;
    const STATE_NAMES: &'static [&'static str] = &["x", "y", "z", "vx", "vy", "vz"];
    const CONTROL_NAMES: &'static [&'static str] = &["ux", "uy", "uz"];
}

impl<G: Validate> Validate for SmallBody<G> {
    fn validate(&self) -> Result<(), ParamError> {
        check(&OMEGA, self.omega, |_| true)?;
        if self.acceleration_magnitude_limit != f64::INFINITY {
            check(
                &ACCELERATION_MAGNITUDE_LIMIT,
                self.acceleration_magnitude_limit,
                |v| v > 0.0,
            )?;
        }
        ActuatorSpec {
            delay: self.control_delay,
            time_constant: self.engine_time_constant,
        }
        .validate()?;
        for (i, &l) in self.acceleration_limit.iter().enumerate() {
            if l.is_nan() || l <= 0.0 {
                return Err(
                    ParamError::new(ACCELERATION_LIMIT.name, l, ACCELERATION_LIMIT.rule).on_axis(i),
                );
            }
        }
        self.gravity.validate()
    }
}

/// The nested gravity field (its kind picks the plant's type, in the registry).
pub const GRAVITY: Param = Param::nested("gravity", Layout::Family("gravity"))
    .doc("the body's gravity field (a landing.gravity field)");
const OMEGA: Param = Param::scalar("omega")
    .unit("rad/s")
    .doc("the body's rotation rate about z");
const ACCELERATION_LIMIT: Param = Param::axes("acceleration_limit")
    .unit("m/s^2")
    .rule("acceleration_limit > 0")
    .optional()
    .doc("per-axis limit on |u_i|; None for none");

const ACCELERATION_MAGNITUDE_LIMIT: Param = Param::scalar("acceleration_magnitude_limit")
    .unit("m/s^2")
    .rule("acceleration_magnitude_limit > 0")
    .optional()
    .doc("limit on |u| (after the per-axis one); None for none");

/// A small body's parameters, whatever its field.
pub const SMALL_BODY: &[Param] = &[
    GRAVITY,
    OMEGA,
    ACCELERATION_LIMIT,
    ACCELERATION_MAGNITUDE_LIMIT,
    CONTROL_DELAY,
    ENGINE_TIME_CONSTANT,
    SENSOR,
    FILTER,
];

impl<G: FromParams> FromParams for SmallBody<G> {
    /// The body's rotation and limit, and its field from the nested table `gravity` (whose kind
    /// the registry has matched with `G`).
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let magnitude = p.opt_scalar(&ACCELERATION_MAGNITUDE_LIMIT)?;
        Ok(Self {
            gravity: p.nested(&GRAVITY, G::from_params)?,
            omega: p.scalar(&OMEGA)?,
            acceleration_limit: p
                .opt_axes::<3>(&ACCELERATION_LIMIT)?
                .unwrap_or(Vector3::repeat(f64::INFINITY)),
            acceleration_magnitude_limit: magnitude.unwrap_or(f64::INFINITY),
            magnitude_limited: magnitude.is_some(),
            control_delay: p.opt_scalar(&CONTROL_DELAY)?.unwrap_or(0.0),
            engine_time_constant: p.opt_scalar(&ENGINE_TIME_CONSTANT)?.unwrap_or(0.0),
            navigation: Navigation::read(p)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{IntegratorKind, Stage};

    #[derive(Clone, Copy)]
    struct NoGravity;

    impl GravityField<f64> for NoGravity {
        fn acceleration(&self, _r: &Vector3<f64>) -> Vector3<f64> {
            Vector3::zeros()
        }
        fn potential(&self, _r: &Vector3<f64>) -> f64 {
            0.0
        }
    }

    fn advance<P: Plant<f64, 3, State = SmallBodyState>>(
        p: &P,
        x: &mut SmallBodyState,
        steps: usize,
        h: f64,
    ) {
        for k in 0..steps {
            let t = k as f64 * h;
            *x = IntegratorKind::Rk4.step(
                &|stage: Stage, y: &SmallBodyState| {
                    p.derivative(stage.time(t, h), y, &Vector3::zeros(), &Vector3::zeros())
                },
                x,
                h,
            );
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
        advance(&p, &mut x, 8000, 1.0);
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
        advance(&p, &mut x, 20_000, 1.0);
        assert!(
            ((jacobi(&x) - c0) / c0).abs() < 1e-9,
            "{} vs {c0}",
            jacobi(&x)
        );
    }
}
