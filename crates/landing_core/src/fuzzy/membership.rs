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

    /// The membership of each lane of `x`: the value [`Membership::eval`] gives, with one
    /// division per lane where the two ramps take two.
    ///
    /// Left of the peak or shoulder b the falling ramp is 1, and from b on the rising one is,
    /// so the smaller of the two is the ramp on the lane's side of b: the same division of the
    /// same operands, its quotient selected as [`Membership::eval`]'s ramps select it. (The
    /// divider is the slowest unit a fuzzy law uses: with one division W5 took 0.94 times as
    /// long, see BENCHMARKS.md.)
    #[inline(always)]
    pub fn eval_lanes<R: Real>(&self, x: R) -> R {
        // the rising ramp over [a, b], the falling one over [c, d]
        let (a, b, c, d) = match *self {
            Membership::Triangle(a, b, c) => (a, b, b, c),
            Membership::Trapezoid(a, b, c, d) => (a, b, c, d),
        };
        let left = x.simd_lt(R::splat(b));
        let q = R::select(left, x - a, R::splat(d) - x)
            / R::select(left, R::splat(b - a), R::splat(d - c));
        let rising = R::select(x.simd_lt(R::splat(a)), R::zero(), q);
        let falling = R::select(
            x.simd_gt(R::splat(d)),
            R::zero(),
            R::select(x.simd_le(R::splat(c)), R::one(), q),
        );
        R::select(left, rising, falling)
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

    /// `eval_lanes` has the bits of `eval`, the two ramps' definition, in every lane: inside,
    /// on every corner, outside, for triangles, shoulders, trapezoids and steps.
    #[test]
    fn the_lanes_have_the_bits_of_the_ramps() {
        use crate::lanes::Lanes;
        let sets = [
            Membership::Triangle(-5.0, -2.5, 0.0),
            Membership::Triangle(-5.0, -5.0, -2.5),
            Membership::Triangle(2.5, 5.0, 5.0),
            Membership::Triangle(-0.01, 0.0, 0.013),
            Membership::Triangle(-1.0, 0.3, 0.3),
            Membership::Trapezoid(0.0, 1.0, 2.0, 4.0),
            Membership::Trapezoid(-5.0, -5.0, -3.0, 0.3),
            Membership::Trapezoid(-0.5, 2.0, 5.0, 5.0),
            Membership::Trapezoid(-1.0, 0.5, 0.5, 3.0),
            Membership::Trapezoid(-1.0, -1.0, 2.0, 2.0),
        ];
        for set in sets {
            let corners = set.corners();
            let mut xs: Vec<f64> = (0..=400).map(|i| -6.0 + 12.0 * i as f64 / 400.0).collect();
            for &c in &corners {
                xs.extend([c, c.next_down(), c.next_up()]);
            }
            xs.extend([f64::INFINITY, f64::NEG_INFINITY]);
            for x in xs.chunks(8) {
                let lanes = Lanes::<8>(std::array::from_fn(|l| x[l % x.len()]));
                let got = set.eval_lanes(lanes);
                for (l, &x) in x.iter().enumerate() {
                    assert_eq!(got.0[l].to_bits(), set.eval(x).to_bits(), "{set:?} at {x}");
                }
            }
        }
    }
}
