//! Reference trajectories the laws track.

use nalgebra::SVector;

use crate::error::{ParamError, ReadError, Validate, check, require};
use crate::lanes::{Gather, Real, add, scale, scale_by, select_vector, zeros};
use crate::params::{FromParams, Param, ParamSource, Schema};

const POSITION: Param = Param::axes("position").unit("q").doc("the target position");
const VELOCITY: Param = Param::axes("velocity")
    .unit("q/s")
    .optional()
    .doc("the target velocity (zero if absent)");
const T_END: Param = Param::scalar("t_end")
    .unit("s")
    .rule("t_end > 0")
    .doc("end of the cubic; afterwards the end point is held at rest (after = \"hold\") or extended at the end velocity (after = \"extend\")");
const C0: Param = Param::axes("c0").unit("q").doc("cubic coefficient of t^0");
const C1: Param = Param::axes("c1")
    .unit("q/s")
    .doc("cubic coefficient of t^1");
const C2: Param = Param::axes("c2")
    .unit("q/s^2")
    .doc("cubic coefficient of t^2");
const C3: Param = Param::axes("c3")
    .unit("q/s^3")
    .doc("cubic coefficient of t^3");

const AFTER: Param = Param::choice("after", After::NAMES)
    .doc("past t_end: \"hold\" the end point (at rest), or \"extend\" it at the end velocity");

crate::named! {
    /// What a cubic does past its end.
    pub enum After {
        /// The end point held, at rest.
        Hold => "hold",
        /// The end velocity kept: `p(t) = p(t_end) + p'(t_end) (t - t_end)`, a constant-velocity
        /// phase (a lander's terminal descent).
        Extend => "extend",
    }
}

crate::named! {
    /// The reference kinds at the Python boundary.
    pub enum ReferenceKind in "reference" {
        Constant => "constant": Schema::new(&[POSITION, VELOCITY]),
        Cubic => "cubic": Schema::new(&[T_END, C0, C1, C2, C3, AFTER]),
    }
}

/// The reference kinds' names.
pub const REFERENCE_KINDS: &[&str] = ReferenceKind::NAMES;

/// Reference position, velocity and acceleration at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefPoint<const D: usize, R = f64> {
    pub position: SVector<R, D>,
    pub velocity: SVector<R, D>,
    pub acceleration: SVector<R, D>,
}

/// A reference is chosen once per batch and evaluated per control instant. It is a small enum
/// rather than a generic parameter: the branch is the same at every step (perfectly predicted),
/// and a generic would multiply the number of monomorphised rollouts by the number of kinds.
/// The kind is shared by the lanes of a block; the coefficients are per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reference<const D: usize, R = f64> {
    /// A fixed target state: the law drives q to `position` and q' to `velocity` (seed
    /// 001 uses r_d = 0, v_d = 0).
    Constant {
        position: SVector<R, D>,
        velocity: SVector<R, D>,
    },
    /// `p(t) = c0 + c1 t + c2 t^2 + c3 t^3` per axis on `[0, t_end]`; afterwards the end point is
    /// held (zero velocity and acceleration), or extended at the end velocity (`after`, shared
    /// by a block).
    Cubic {
        coefficients: [SVector<R, D>; 4],
        t_end: R,
        after: After,
    },
}

impl<const D: usize> Default for Reference<D> {
    fn default() -> Self {
        Self::Constant {
            position: zeros(),
            velocity: zeros(),
        }
    }
}

impl<const D: usize, R: Real> Gather<R> for Reference<D, R> {
    type Case = Reference<D>;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self {
        let constant = |i: usize| match case(i) {
            Reference::Constant { position, velocity } => (position, velocity),
            Reference::Cubic { .. } => unreachable!("a block's references have one kind"),
        };
        let cubic = |i: usize| match case(i) {
            Reference::Cubic {
                coefficients,
                t_end,
                ..
            } => (coefficients, t_end),
            Reference::Constant { .. } => unreachable!("a block's references have one kind"),
        };
        match case(0) {
            Reference::Constant { .. } => Reference::Constant {
                position: Gather::gather(&|i| constant(i).0),
                velocity: Gather::gather(&|i| constant(i).1),
            },
            Reference::Cubic { after, .. } => Reference::Cubic {
                coefficients: Gather::gather(&|i| cubic(i).0),
                t_end: Gather::gather(&|i| cubic(i).1),
                after: *after,
            },
        }
    }

    fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
        match (a, b) {
            (Reference::Cubic { after: x, .. }, Reference::Cubic { after: y, .. }) => x == y,
            _ => std::mem::discriminant(a) == std::mem::discriminant(b),
        }
    }
}

impl<const D: usize> Reference<D> {
    /// The cubic through `p0, v0` at 0 and `pt, vt` at `t_end` (seeds 000 and 002).
    pub fn cubic_from_boundary(
        p0: SVector<f64, D>,
        v0: SVector<f64, D>,
        pt: SVector<f64, D>,
        vt: SVector<f64, D>,
        t_end: f64,
    ) -> Result<Self, ParamError> {
        Ok(Self::Cubic {
            coefficients: cubic_coefficients(p0, v0, pt, vt, t_end)?,
            t_end,
            after: After::Hold,
        })
    }

    /// Position, velocity and acceleration at times `t`, each row-major (times x D), refusing
    /// a time at which the reference is not finite (a cubic far before 0 overflows).
    pub fn trajectory(&self, t: &[f64]) -> Result<[Vec<f64>; 3], ReadError> {
        let mut out = [(); 3].map(|_| Vec::with_capacity(t.len() * D));
        for (i, &ti) in t.iter().enumerate() {
            let pt = self.at(ti);
            let values = [&pt.position, &pt.velocity, &pt.acceleration];
            if values.iter().any(|v| v.iter().any(|x| !x.is_finite())) {
                return Err(ReadError::value(format!(
                    "t[{i}] = {ti} violates times at which the reference is finite"
                )));
            }
            for (o, v) in out.iter_mut().zip(values) {
                o.extend_from_slice(v.as_slice());
            }
        }
        Ok(out)
    }
}

/// The coefficients c0..c3 of the cubic through `p0, v0` at 0 and `pt, vt` at `t_end`.
pub fn cubic_coefficients<const D: usize>(
    p0: SVector<f64, D>,
    v0: SVector<f64, D>,
    pt: SVector<f64, D>,
    vt: SVector<f64, D>,
    t_end: f64,
) -> Result<[SVector<f64, D>; 4], ParamError> {
    require(t_end > 0.0, "T", t_end, "T > 0")?;
    let t = t_end;
    let c2 = (pt - p0) * (3.0 / (t * t)) - (v0 * 2.0 + vt) / t;
    let c3 = (p0 - pt) * (2.0 / (t * t * t)) + (v0 + vt) / (t * t);
    Ok([p0, v0, c2, c3])
}

/// [`cubic_coefficients`] for boundary states given as slices of 2 or 3 values (as a caller
/// outside Rust holds them): c0..c3, each as long as `p0`, or what is wrong with the input.
pub fn cubic_from_slices(
    p0: &[f64],
    v0: &[f64],
    pt: &[f64],
    vt: &[f64],
    t_end: f64,
) -> Result<[Vec<f64>; 4], ReadError> {
    let all = [("p0", p0), ("v0", v0), ("pT", pt), ("vT", vt)];
    for (name, v) in all {
        crate::error::finite(name, v)?;
    }
    let d = p0.len();
    if let Some((name, v)) = all[1..].iter().find(|(_, v)| v.len() != d) {
        let msg = format!("{name} has {} axes, p0 has {d}", v.len());
        return Err(ReadError::Value(msg));
    }
    crate::with_axes!(d, D => {
        let [a, b, c, e] = all.map(|(_, v)| SVector::<f64, D>::from_column_slice(v));
        Ok(cubic_coefficients(a, b, c, e, t_end)?.map(|c| c.as_slice().to_vec()))
    }, d => Err(ReadError::Value(format!("p0 has {d} axes; 2 or 3 are supported"))))
}

impl<const D: usize, R: Real> Reference<D, R> {
    #[inline(always)]
    pub fn at(&self, t: f64) -> RefPoint<D, R> {
        match *self {
            Self::Constant { position, velocity } => RefPoint {
                position,
                velocity,
                acceleration: zeros(),
            },
            Self::Cubic {
                coefficients: [c0, c1, c2, c3],
                t_end,
                after,
            } => {
                // before t_end the cubic at t, after it the end point held, per lane
                let before = R::splat(t).simd_le(t_end);
                let tt = R::select(before, R::splat(t), t_end);
                // c0 + (c1 + (c2 + c3 t) t) t
                let position = add(&c2, &scale_by(&c3, tt));
                let position = add(&c1, &scale_by(&position, tt));
                let position = add(&c0, &scale_by(&position, tt));
                let velocity = add(
                    &c1,
                    &scale_by(
                        &add(&scale(&c2, 2.0), &scale_by(&c3, R::splat(3.0) * tt)),
                        tt,
                    ),
                );
                let acceleration = add(&scale(&c2, 2.0), &scale_by(&c3, R::splat(6.0) * tt));
                let zero = zeros();
                match after {
                    After::Hold => RefPoint {
                        position,
                        velocity: select_vector(before, &velocity, &zero),
                        acceleration: select_vector(before, &acceleration, &zero),
                    },
                    After::Extend => RefPoint {
                        // the lanes before t_end keep the cubic's position as it is
                        position: select_vector(
                            before,
                            &position,
                            &add(&position, &scale_by(&velocity, R::splat(t) - t_end)),
                        ),
                        velocity,
                        acceleration: select_vector(before, &acceleration, &zero),
                    },
                }
            }
        }
    }
}

impl<const D: usize> Validate for Reference<D> {
    fn validate(&self) -> Result<(), ParamError> {
        match self {
            Self::Constant { position, velocity } => {
                for (i, v) in position.iter().enumerate() {
                    check(&POSITION, *v, |_| true).map_err(|e| e.on_axis(i))?;
                }
                for (i, v) in velocity.iter().enumerate() {
                    check(&VELOCITY, *v, |_| true).map_err(|e| e.on_axis(i))?;
                }
            }
            Self::Cubic {
                coefficients,
                t_end,
                ..
            } => {
                check(&T_END, *t_end, |v| v > 0.0)?;
                for c in coefficients {
                    for (i, v) in c.iter().enumerate() {
                        require(true, "coefficients", *v, "finite values")
                            .map_err(|e| e.on_axis(i))?;
                    }
                }
            }
        }
        Ok(())
    }
}

/// The references, read and validated for each axis count ([`crate::params::ByAxes`]).
pub struct References;

impl crate::params::ReadFor for References {
    type At<const D: usize> = Reference<D>;
    fn read<const D: usize>(p: &mut crate::params::Reader<'_>) -> Result<Reference<D>, ReadError> {
        crate::params::read_valid(p)
    }
}

impl<const D: usize> FromParams for Reference<D> {
    /// `constant` (position, optional velocity) or `cubic` (coefficients c0..c3, t_end).
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        match p.kind::<ReferenceKind>()? {
            ReferenceKind::Constant => Ok(Self::Constant {
                position: p.axes(&POSITION)?,
                velocity: p.opt_axes(&VELOCITY)?.unwrap_or_else(SVector::zeros),
            }),
            ReferenceKind::Cubic => Ok(Self::Cubic {
                coefficients: [p.axes(&C0)?, p.axes(&C1)?, p.axes(&C2)?, p.axes(&C3)?],
                t_end: p.scalar(&T_END)?,
                after: p.choice(&AFTER)?,
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn cubic_meets_its_boundary_conditions() {
        let p0 = Vector3::new(3200.0, 1300.0, 9000.0);
        let v0 = Vector3::new(-1.2, 0.2, -1.0);
        let pt = Vector3::new(2837.0, 928.1, 5708.0);
        let vt = Vector3::zeros();
        let r = Reference::cubic_from_boundary(p0, v0, pt, vt, 8000.0).unwrap();
        let a = r.at(0.0);
        let b = r.at(8000.0);
        assert!((a.position - p0).norm() < 1e-9 && (a.velocity - v0).norm() < 1e-12);
        assert!((b.position - pt).norm() < 1e-6 && (b.velocity - vt).norm() < 1e-9);
        // the acceleration is the derivative of the velocity (central difference)
        let h = 1e-3;
        let t = 1234.5;
        let fd = (r.at(t + h).velocity - r.at(t - h).velocity) / (2.0 * h);
        assert!((fd - r.at(t).acceleration).norm() < 1e-9);
        // past the end the end point is held
        let c = r.at(9000.0);
        assert!((c.position - pt).norm() < 1e-6 && c.velocity == Vector3::zeros());
    }

    #[test]
    fn an_extended_cubic_goes_on_at_its_end_velocity() {
        let p0 = Vector3::new(-2000.0, 1000.0, 1500.0);
        let v0 = Vector3::new(100.0, -15.0, -75.0);
        let pt = Vector3::new(0.0, 0.0, 10.0);
        let vt = Vector3::new(0.0, 0.0, -0.75);
        let Reference::Cubic {
            coefficients,
            t_end,
            ..
        } = Reference::cubic_from_boundary(p0, v0, pt, vt, 40.0).unwrap()
        else {
            unreachable!()
        };
        let r = Reference::Cubic {
            coefficients,
            t_end,
            after: After::Extend,
        };
        let held = Reference::Cubic {
            coefficients,
            t_end,
            after: After::Hold,
        };
        // before the end: the cubic itself, bit for bit
        for t in [0.0, 12.5, 39.99, 40.0] {
            assert_eq!(r.at(t).position, held.at(t).position);
        }
        // after it: a straight line at the end velocity, 0.75 m/s down, reaching 0 at t = 40 + 10 / 0.75
        let c = r.at(40.0 + 10.0 / 0.75);
        assert!(c.position.norm() < 1e-9, "{:?}", c.position);
        assert!((c.velocity - vt).norm() < 1e-12 && c.acceleration == Vector3::zeros());
    }
}
