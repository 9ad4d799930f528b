//! Scalar conventions shared by every law, over [`Real`] lanes.

use crate::error::ReadError;
use crate::lanes::{Gather, Real};
use crate::params::{FromParams, Param, ParamSource};

/// Sign with `sgn(0) = 0`.
///
/// `f64::signum` returns +-1 at +-0, which would make every switching law kick at the
/// equilibrium; the seeds (e.g. seed 001 eq. 17) define sgn(0) = 0.
#[inline(always)]
pub fn sgn<R: Real>(x: R) -> R {
    x.signum0()
}

/// `sig^a(x) = |x|^a sgn(x)` for a non-negative exponent (zero at zero).
#[inline(always)]
pub fn sig<R: Real>(x: R, a: R) -> R {
    sgn(x) * x.abs().powf(a)
}

/// Switching function of a sliding-mode law: `sign`, `sat(s/phi)` or `tanh(s/phi)`. The kind
/// is shared by a block; the boundary-layer width phi is per lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Switch<R = f64> {
    Sign,
    /// Boundary layer of width `phi`: `clamp(s/phi, -1, 1)`.
    Sat(R),
    /// `tanh(s/phi)`.
    Tanh(R),
}

crate::named! {
    /// The switching functions' names at the boundary.
    pub enum SwitchKind {
        Sign => "sign",
        Sat => "sat",
        Tanh => "tanh",
    }
}

/// The switching function's name.
pub const SWITCH: Param = Param::choice("switch", SwitchKind::NAMES)
    .doc("switching function: sign(s), sat(s / phi) = clamp(s / phi, -1, 1) or tanh(s / phi)");
/// Its boundary layer.
pub const BOUNDARY_LAYER: Param = Param::scalar("boundary_layer")
    .unit("units of s")
    .rule("boundary_layer > 0")
    .doc("boundary-layer width phi of sat and tanh (unused by sign)");

impl Switch {
    /// Boundary-layer width, if the switch has one.
    pub fn width(&self) -> Option<f64> {
        match *self {
            Switch::Sign => None,
            Switch::Sat(phi) | Switch::Tanh(phi) => Some(phi),
        }
    }
}

impl<R: Real> Switch<R> {
    #[inline(always)]
    pub fn apply(&self, s: R) -> R {
        match *self {
            Switch::Sign => s.signum0(),
            Switch::Sat(phi) => (s / phi).clamp(R::splat(-1.0), R::splat(1.0)),
            Switch::Tanh(phi) => (s / phi).tanh(),
        }
    }
}

impl<R: Real> Gather<R> for Switch<R> {
    type Case = Switch;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Switch) -> Self {
        let phi = |i: usize| match case(i) {
            Switch::Sign => 0.0,
            Switch::Sat(p) | Switch::Tanh(p) => *p,
        };
        match case(0) {
            Switch::Sign => Switch::Sign,
            Switch::Sat(_) => Switch::Sat(R::from_fn(phi)),
            Switch::Tanh(_) => Switch::Tanh(R::from_fn(phi)),
        }
    }

    fn same_shape(a: &Switch, b: &Switch) -> bool {
        std::mem::discriminant(a) == std::mem::discriminant(b)
    }
}

impl FromParams for Switch {
    /// `switch` ("sign", "sat" or "tanh") and its `boundary_layer` width.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let kind = p.choice::<SwitchKind>(&SWITCH)?;
        let phi = p.scalar(&BOUNDARY_LAYER)?;
        Ok(match kind {
            SwitchKind::Sign => Switch::Sign,
            SwitchKind::Sat => Switch::Sat(phi),
            SwitchKind::Tanh => Switch::Tanh(phi),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sgn_is_zero_at_zero_and_signed_elsewhere() {
        assert_eq!(sgn(0.0), 0.0);
        assert_eq!(sgn(-0.0), 0.0);
        assert_eq!(sgn(1e-300), 1.0);
        assert_eq!(sgn(-3.0), -1.0);
    }

    #[test]
    fn sig_matches_definition() {
        assert_eq!(sig(0.0, 0.5), 0.0);
        assert!((sig(-4.0, 0.5) + 2.0).abs() < 1e-15);
        assert!((sig(8.0, 1.0 / 3.0) - 2.0).abs() < 1e-15);
        // a = 0 reduces to sgn, including sgn(0) = 0
        assert_eq!(sig(0.0, 0.0), 0.0);
        assert_eq!(sig(-2.0, 0.0), -1.0);
    }

    #[test]
    fn switches() {
        assert_eq!(Switch::Sign.apply(-2.0), -1.0);
        assert_eq!(Switch::Sat(0.5).apply(0.1), 0.2);
        assert_eq!(Switch::Sat(0.5).apply(-7.0), -1.0);
        assert!((Switch::Tanh(2.0).apply(1.0) - 0.5f64.tanh()).abs() < 1e-15);
    }
}
