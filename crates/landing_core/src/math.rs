//! Scalar conventions shared by every law (SPEC section 2).

/// Sign with `sgn(0) = 0`.
///
/// `f64::signum` returns +-1 at +-0, which would make every switching law kick at the
/// equilibrium; the seeds (e.g. seed 001 eq. 17) define sgn(0) = 0.
#[inline(always)]
pub fn sgn(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// `sig^a(x) = |x|^a sgn(x)` for a non-negative exponent (zero at zero).
#[inline(always)]
pub fn sig(x: f64, a: f64) -> f64 {
    debug_assert!(
        a >= 0.0,
        "sig with a negative exponent needs a guard: use sig_guarded"
    );
    sgn(x) * x.abs().powf(a)
}

/// `sig^a(x)` for any exponent. A negative exponent is singular at 0; there `|x|` is floored
/// at `floor > 0`, so the result stays finite (SPEC section 2: every guard is a named parameter).
#[inline(always)]
pub fn sig_guarded(x: f64, a: f64, floor: f64) -> f64 {
    if a >= 0.0 {
        sig(x, a)
    } else {
        sgn(x) * x.abs().max(floor).powf(a)
    }
}

/// `|x|^a` for any exponent, with the same floor as [`sig_guarded`] when `a < 0`.
#[inline(always)]
pub fn pow_guarded(x: f64, a: f64, floor: f64) -> f64 {
    if a >= 0.0 {
        x.abs().powf(a)
    } else {
        x.abs().max(floor).powf(a)
    }
}

/// Switching function of a sliding-mode law: `sign`, `sat(s/phi)` or `tanh(s/phi)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Switch {
    Sign,
    /// Boundary layer of width `phi`: `clamp(s/phi, -1, 1)`.
    Sat(f64),
    /// `tanh(s/phi)`.
    Tanh(f64),
}

impl Switch {
    #[inline(always)]
    pub fn apply(&self, s: f64) -> f64 {
        match *self {
            Switch::Sign => sgn(s),
            Switch::Sat(phi) => (s / phi).clamp(-1.0, 1.0),
            Switch::Tanh(phi) => (s / phi).tanh(),
        }
    }

    /// Boundary-layer width, if the switch has one.
    pub fn width(&self) -> Option<f64> {
        match *self {
            Switch::Sign => None,
            Switch::Sat(phi) | Switch::Tanh(phi) => Some(phi),
        }
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
    fn guarded_power_is_finite_at_zero() {
        let v = sig_guarded(0.0, -0.5, 1e-4);
        assert_eq!(v, 0.0);
        let v = sig_guarded(1e-12, -0.5, 1e-4);
        assert!((v - 100.0).abs() < 1e-9);
        assert!((pow_guarded(0.0, -0.5, 1e-4) - 100.0).abs() < 1e-9);
        assert!((pow_guarded(4.0, -0.5, 1e-4) - 0.5).abs() < 1e-15);
    }

    #[test]
    fn switches() {
        assert_eq!(Switch::Sign.apply(-2.0), -1.0);
        assert_eq!(Switch::Sat(0.5).apply(0.1), 0.2);
        assert_eq!(Switch::Sat(0.5).apply(-7.0), -1.0);
        assert!((Switch::Tanh(2.0).apply(1.0) - 0.5f64.tanh()).abs() < 1e-15);
    }
}
