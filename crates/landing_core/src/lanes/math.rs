//! Transcendental functions over [`Real`] lanes.
//!
//! PLACEHOLDER: per-lane libm until the branch-free polynomial versions land.

use super::Real;

#[inline(always)]
fn per_lane<R: Real>(x: R, f: impl Fn(f64) -> f64) -> R {
    R::from_fn(|i| f(x.lane(i)))
}

#[inline(always)]
pub fn exp<R: Real>(x: R) -> R {
    per_lane(x, f64::exp)
}
#[inline(always)]
pub fn ln<R: Real>(x: R) -> R {
    per_lane(x, f64::ln)
}
#[inline(always)]
pub fn pow<R: Real>(x: R, y: R) -> R {
    R::from_fn(|i| x.lane(i).powf(y.lane(i)))
}
#[inline(always)]
pub fn sin<R: Real>(x: R) -> R {
    per_lane(x, f64::sin)
}
#[inline(always)]
pub fn cos<R: Real>(x: R) -> R {
    per_lane(x, f64::cos)
}
#[inline(always)]
pub fn sin_cos<R: Real>(x: R) -> (R, R) {
    (sin(x), cos(x))
}
#[inline(always)]
pub fn tanh<R: Real>(x: R) -> R {
    per_lane(x, f64::tanh)
}
#[inline(always)]
pub fn atan2<R: Real>(y: R, x: R) -> R {
    R::from_fn(|i| y.lane(i).atan2(x.lane(i)))
}
