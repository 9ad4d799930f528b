//! Membership functions, with scikit-fuzzy's conventions at the corners (a shoulder, a = b or
//! b = c, is 1 on its flat side up to the corner and 0 outside [a, c]).

use crate::error::{ParamError, require};
use crate::lanes::Real;
use crate::params::schema::{Param, Schema};

/// A triangle's corners, as a fuzzy system's table gives them.
pub const TRIANGLE: Param = Param::components("values")
    .unit("units of the variable")
    .rule("corners in non-decreasing order")
    .doc("the corners a, b, c: feet a and c, peak b");
/// A trapezoid's corners.
pub const TRAPEZOID: Param = Param::components("values")
    .unit("units of the variable")
    .rule("corners in non-decreasing order")
    .doc("the corners a, b, c, d: feet a and d, shoulders b and c");

crate::named! {
    /// The membership functions' shapes, in a fuzzy system's table: each set is a pair
    /// (shape, corners).
    pub enum MembershipShape in "fuzzy" {
        Triangle => "triangle": Schema::new(&[TRIANGLE]),
        Trapezoid => "trapezoid": Schema::new(&[TRAPEZOID]),
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Membership {
    /// Triangle with feet a, c and peak b (a <= b <= c).
    Triangle(f64, f64, f64),
    /// Trapezoid with feet a, d and shoulders b, c (a <= b <= c <= d).
    Trapezoid(f64, f64, f64, f64),
}

impl Membership {
    /// The set's shape.
    pub fn shape(&self) -> MembershipShape {
        match self {
            Membership::Triangle(..) => MembershipShape::Triangle,
            Membership::Trapezoid(..) => MembershipShape::Trapezoid,
        }
    }

    /// The set's corners, in order.
    pub fn corners(&self) -> Vec<f64> {
        match *self {
            Membership::Triangle(a, b, c) => vec![a, b, c],
            Membership::Trapezoid(a, b, c, d) => vec![a, b, c, d],
        }
    }

    #[inline]
    pub fn eval(&self, x: f64) -> f64 {
        match *self {
            Membership::Triangle(a, b, c) => ramp_up(x, a, b).min(ramp_down(x, b, c)),
            Membership::Trapezoid(a, b, c, d) => ramp_up(x, a, b).min(ramp_down(x, c, d)),
        }
    }

    /// The membership of each lane of `x` (the same ramps as [`Membership::eval`], as selects).
    #[inline(always)]
    pub fn eval_lanes<R: Real>(&self, x: R) -> R {
        match *self {
            Membership::Triangle(a, b, c) => ramp_up_lanes(x, a, b).min(ramp_down_lanes(x, b, c)),
            Membership::Trapezoid(a, b, c, d) => {
                ramp_up_lanes(x, a, b).min(ramp_down_lanes(x, c, d))
            }
        }
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        let (name, rule) = (self.shape().name(), TRIANGLE.rule);
        let pts = self.corners();
        for w in pts.windows(2) {
            require(w[1] >= w[0], name, w[1], rule)?;
        }
        require(
            pts[pts.len() - 1] > pts[0],
            name,
            pts[0],
            "a non-empty support",
        )
    }
}

/// 0 left of a, 1 from b on, linear between (a step at a = b).
#[inline(always)]
fn ramp_up(x: f64, a: f64, b: f64) -> f64 {
    if x < a {
        0.0
    } else if x >= b {
        1.0
    } else {
        (x - a) / (b - a)
    }
}

/// 1 up to b, 0 right of c, linear between (a step at b = c).
#[inline(always)]
fn ramp_down(x: f64, b: f64, c: f64) -> f64 {
    if x > c {
        0.0
    } else if x <= b {
        1.0
    } else {
        (c - x) / (c - b)
    }
}

/// [`ramp_up`] per lane.
#[inline(always)]
fn ramp_up_lanes<R: Real>(x: R, a: f64, b: f64) -> R {
    let (a_, b_) = (R::splat(a), R::splat(b));
    R::select(
        x.simd_lt(a_),
        R::zero(),
        R::select(x.simd_ge(b_), R::one(), (x - a) / (b - a)),
    )
}

/// [`ramp_down`] per lane.
#[inline(always)]
fn ramp_down_lanes<R: Real>(x: R, b: f64, c: f64) -> R {
    let (b_, c_) = (R::splat(b), R::splat(c));
    R::select(
        x.simd_gt(c_),
        R::zero(),
        R::select(x.simd_le(b_), R::one(), (R::splat(c) - x) / (c - b)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangles_and_shoulders() {
        let t = Membership::Triangle(-5.0, -2.5, 0.0);
        assert_eq!(t.eval(-2.5), 1.0);
        assert_eq!(t.eval(-3.75), 0.5);
        assert_eq!(t.eval(0.0), 0.0);
        assert_eq!(t.eval(1.0), 0.0);
        let left = Membership::Triangle(-5.0, -5.0, -2.5);
        assert_eq!(left.eval(-5.0), 1.0);
        assert_eq!(left.eval(-6.0), 0.0);
        assert_eq!(left.eval(-3.75), 0.5);
        let trap = Membership::Trapezoid(0.0, 1.0, 2.0, 4.0);
        assert_eq!(trap.eval(1.5), 1.0);
        assert_eq!(trap.eval(3.0), 0.5);
        assert!(Membership::Triangle(1.0, 0.0, 2.0).validate().is_err());
    }
}
