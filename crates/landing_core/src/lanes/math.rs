//! Transcendental functions over [`Real`] lanes: `exp`, `ln`, `pow`, `tanh`, and `PowLog` and
//! `exp16` for powers sharing one logarithm (written in `lanes/exp_log.rs`) and `sin`, `cos`, `sin_cos`, `atan2` (in `lanes/trig.rs`).
//!
//! Every function is a fixed sequence of the primitive operations of [`Real`] (IEEE `+ - * /`,
//! fused multiply-add, `sqrt`, comparisons, `select`, a few exact bit manipulations and exact
//! lookups in a 16-entry table): no libm (but for the baseline level's `fma`, correctly rounded
//! as the instruction is) and no branch on a lane's value (special
//! cases are masks and selects). So `f64` and every `Lanes<W>` give the same bits per lane, whatever the width or
//! the instruction-set level (SSE2, AVX2, AVX-512) the kernel was compiled for. The one
//! exception is documented at [`sin_cos`]: arguments beyond 2^20 pi/2 take a cold per-lane libm
//! path.
//!
//! The algorithms are the classic ones (fdlibm/musl: `e_exp.c`, `e_log.c`, `k_sin.c`,
//! `k_cos.c`, `e_rem_pio2.c`, `s_atan.c`, `e_atan2.c`; Cephes' `tanh`), rearranged to be
//! branch-free. The polynomial coefficients are our own minimax fits, produced by
//! `crates/landing_core/tools/fit_lane_math.py` (Remez exchange in mpmath, weighted by the
//! error each term contributes to the final result).
//!
//! Accuracy, measured against correctly rounded mpmath values (`tests/lane_math.rs` and a
//! denser search) and against glibc over millions of points: exp 0.67 ulp, ln 0.78, sin and
//! cos 0.76, tanh 0.72, atan2 1.41 (where b/a is just above a power of two; below 1
//! elsewhere), and pow 1.44 ulp where `|y ln x| <= 1`, growing with `|y ln x|` beyond
//! (documented there).

pub use super::exp_log::{INV_LN2_16, PowLog, exp, exp16, ln, pow, tanh};
pub use super::trig::{atan2, cos, sin, sin_cos};

use super::Real;

/// `c[0] + c[1] x + ... + c[10] x^10` by Estrin's scheme: a few more multiplies than Horner
/// but a dependency chain of 4 multiply-add levels instead of 10, which matters when calls
/// follow one another in the rollout's step.
#[inline(always)]
pub(super) fn estrin11<R: Real>(x: R, c: &[f64; 11]) -> R {
    let x2 = x * x;
    let x4 = x2 * x2;
    let x8 = x4 * x4;
    let k = |i: usize| R::splat(c[i]);
    let a0 = x.mul_add(k(1), k(0));
    let a1 = x.mul_add(k(3), k(2));
    let a2 = x.mul_add(k(5), k(4));
    let a3 = x.mul_add(k(7), k(6));
    let a4 = x.mul_add(k(9), k(8));
    let b0 = x2.mul_add(a1, a0);
    let b1 = x2.mul_add(a3, a2);
    let b2 = x2.mul_add(k(10), a4);
    x8.mul_add(b2, x4.mul_add(b1, b0))
}

/// `(a - b, e)` with `a - b = s + e` exactly (Knuth's TwoSum, valid whatever the magnitudes).
#[inline(always)]
pub(super) fn two_diff<R: Real>(a: R, b: R) -> (R, R) {
    let s = a - b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) - (b + bv))
}
