//! Events that end a case, and where inside an integrator step they happen.
//!
//! A lander touches down at the first crossing of its altitude through zero. The step's two
//! ends are known exactly (the integrator's states at t_j and t_j + h) together with the rates
//! of the coordinates there (the velocities are state components), so the trajectory over the
//! step is taken as the cubic Hermite interpolant of each coordinate: the classic dense output
//! of a one-step method, exact for motion of degree three or less (a drag-free fall under
//! constant thrust is a parabola: its touchdown is located to rounding), and within O(h^4) of
//! the integrated one otherwise. The crossing is the interpolant's root, bracketed in the step
//! and found by bisection to a relative 2^-44 of the step (under 1e-15 s at h = 1 ms); the
//! velocity at the event is the interpolant's derivative there. Every lane runs the same fixed
//! number of iterations, so the result is the same in any block and at any level.

use nalgebra::SVector;

use crate::lanes::Real;

/// An event a run may stop each case at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event {
    /// The first crossing of the altitude through zero, downwards (a lander's touchdown).
    Touchdown,
}

impl Event {
    /// The names the bindings and scenario files take, in the order of the variants.
    pub const NAMES: [&'static str; 1] = ["touchdown"];

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "touchdown" => Some(Self::Touchdown),
            _ => None,
        }
    }

    pub fn name(&self) -> &'static str {
        match self {
            Self::Touchdown => Self::NAMES[0],
        }
    }
}

/// Bisection steps: the bracket [0, 1] of the step's fraction shrinks to 2^-44.
const BISECTIONS: usize = 44;

/// The cubic Hermite interpolant over a step of length `h` of a coordinate with values `q0`,
/// `q1` and rates `v0`, `v1` at the step's ends, at the fraction `s` of the step, and its
/// rate there.
#[inline(always)]
fn hermite<R: Real>(q0: R, v0: R, q1: R, v1: R, h: R, s: R) -> (R, R) {
    let one = R::splat(1.0);
    let two = R::splat(2.0);
    let three = R::splat(3.0);
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = two * s3 - three * s2 + one;
    let h10 = s3 - two * s2 + s;
    let h01 = three * s2 - two * s3;
    let h11 = s3 - s2;
    let value = h00 * q0 + h10 * h * v0 + h01 * q1 + h11 * h * v1;
    let six = R::splat(6.0);
    let d00 = six * (s2 - s);
    let d10 = three * s2 - R::splat(4.0) * s + one;
    let d11 = three * s2 - two * s;
    let rate = (d00 * (q0 - q1)) / h + d10 * v0 + d11 * v1;
    (value, rate)
}

/// Where in a step of length `h` the coordinates `q` cross `q[axis] = 0` downwards: the
/// fraction `s` of the step (in (0, 1]), and the coordinates and their rates there. The lanes
/// of `crossing` have `q0[axis] > 0 >= q1[axis]`; the others' values are not used.
#[inline(always)]
pub(crate) fn locate_crossing<R: Real, const D: usize>(
    (q0, v0): (&SVector<R, D>, &SVector<R, D>),
    (q1, v1): (&SVector<R, D>, &SVector<R, D>),
    axis: usize,
    h: f64,
    crossing: R::Mask,
) -> (R, SVector<R, D>, SVector<R, D>) {
    let h = R::splat(h);
    let zero = R::zero();
    let half = R::splat(0.5);
    // the bracket: altitude above zero at lo, at or below it at hi
    let mut lo = zero;
    let mut hi = R::splat(1.0);
    let z = |s: R| hermite(q0[axis], v0[axis], q1[axis], v1[axis], h, s).0;
    for _ in 0..BISECTIONS {
        let mid = (lo + hi) * half;
        let below = z(mid).simd_le(zero) | !crossing;
        hi = R::select(below, mid, hi);
        lo = R::select(below, lo, mid);
    }
    // the first point of the bracket at or below the ground
    let s = hi;
    let mut q = SVector::<R, D>::zeros();
    let mut v = SVector::<R, D>::zeros();
    for c in 0..D {
        (q[c], v[c]) = hermite(q0[c], v0[c], q1[c], v1[c], h, s);
    }
    (s, q, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn a_parabola_is_located_to_rounding() {
        // z(t) = 1 + 2 t - 5 t^2 over [0, 1]: z(1) = -2, the root at (2 + sqrt(24)) / 10
        let at = |t: f64| Vector3::new(3.0 * t, -t, 1.0 + 2.0 * t - 5.0 * t * t);
        let rate = |t: f64| Vector3::new(3.0, -1.0, 2.0 - 10.0 * t);
        let (s, q, v) =
            locate_crossing::<f64, 3>((&at(0.0), &rate(0.0)), (&at(1.0), &rate(1.0)), 2, 1.0, true);
        let root = (2.0 + 24f64.sqrt()) / 10.0;
        assert!((s - root).abs() < 1e-12, "{s} {root}");
        assert!((q - at(root)).norm() < 1e-12);
        assert!((v - rate(root)).norm() < 1e-11);
    }

    #[test]
    fn the_event_names_read_back() {
        for name in Event::NAMES {
            assert_eq!(Event::from_name(name).map(|e| e.name()), Some(name));
        }
        assert_eq!(Event::from_name("landing"), None);
    }
}
