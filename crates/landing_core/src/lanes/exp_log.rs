//! `exp`, `ln`, `pow` and `tanh` over [`Real`] lanes, branch-free (see [`super::math`]).

use super::math::{estrin10, estrin11};
use super::{Mask, Real};

/// ln 2 split for Cody-Waite reduction (fdlibm `e_exp.c`): `LN2_HI` has 32 significant bits,
/// so `k * LN2_HI` is exact for |k| < 2^21 and `x - k * LN2_HI` is exact (Sterbenz).
const LN2_HI: f64 = 0.6931471803691238; // 0x3FE62E42FEE00000
const LN2_LO: f64 = 1.9082149292705877e-10; // 0x3DEA39EF35793C76
const LOG2_E: f64 = std::f64::consts::LOG2_E;

/// Beyond these, exp is +inf or rounds to 0; clamping keeps `k` within [-1076, 1024] so that
/// the two-step scaling below stays in the exponent range and overflow/underflow happen in
/// the last multiply, rounded once like libm.
const EXP_CLAMP_HI: f64 = 710.0;
const EXP_CLAMP_LO: f64 = -746.0;

// exp(r) = 1 + r + r^2 Q(r), |r| <= ln2/2; minimax, weighted error 2^-57.8 of exp(r).
const EXP_Q: [f64; 10] = [
    0.5000000000000011,
    0.1666666666666644,
    0.04166666666652582,
    0.008333333333471667,
    0.0013888888944848972,
    0.0001984126956563193,
    2.480149177362678e-05,
    2.755752546472832e-06,
    2.76307337704345e-07,
    2.502163022406466e-08,
];

/// `(k, p, p_lo)` with `exp(x) = 2^k (p + p_lo)`, `p = fl(p + p_lo)`, for x in
/// [-746, 710].
///
/// fdlibm's reduction `x = k ln2 + hi - lo` with `hi` exact; then a polynomial instead of
/// fdlibm's rational form (no division). The correction `lo` is applied at first order to
/// the linear term only (`exp(hi - lo) ~ 1 + hi - lo + r^2 Q(r)`), so the last additions are
/// `hi - (lo - r^2 Q)` and `1 + t`, and the error of the result is essentially the rounding
/// of `1 + t`. `p_lo` is that rounding's error (Fast2Sum, |t| < 1), for callers that want
/// more than a double (tanh).
#[inline(always)]
fn exp_kernel<R: Real>(x: R) -> (R, R, R) {
    let k = (x * LOG2_E).round_small();
    let hi = x - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let r2 = r * r;
    let w = r2 * estrin10(r, r2, &EXP_Q);
    let t = hi - (lo - w);
    let p = t + 1.0;
    let p_lo = (R::one() - p) + t;
    (k, p, p_lo)
}

/// `e^x`, within 1 ulp of the correctly rounded result (0.88 ulp measured).
///
/// Overflows to +inf for x > 709.78..., underflows gradually through the subnormals to 0
/// (below -745.13...), `exp(-inf) = 0`, `exp(+inf) = +inf`, `exp(NaN) = NaN`.
///
/// One kernel per call, whatever the lanes hold: only the last scaling depends on the range,
/// and the branch between its two forms is the only one. A fast path and a general path,
/// each with its kernel, made every call site twice as large (the extension compiled in
/// 122 s instead of 94); the general path out of line made W1 8 % slower than this form
/// (register spills around the never-taken calls). See BENCHMARKS.md.
#[inline(always)]
pub fn exp<R: Real>(x: R) -> R {
    // constant first: max/min return their second operand for a NaN, so NaN goes through.
    // Inside [-700, 700] the clamp changes nothing.
    let xc = R::splat(EXP_CLAMP_HI).min(R::splat(EXP_CLAMP_LO).max(x));
    let (k, p, _) = exp_kernel(xc);
    if (x.simd_ge(R::splat(-700.0)) & x.simd_le(R::splat(700.0))).all() {
        // 2^k is a normal number by which p scales exactly: one factor gives the same bits
        // as the two below
        p.scale2(k)
    } else {
        // 2^k in two factors: `p 2^k1` is exact and normal, and the multiply by 2^k2 rounds
        // once, into the subnormals or to infinity when the result leaves the normal range.
        let k1 = k.max(R::splat(-1000.0)).min(R::splat(1000.0));
        (p * k1.pow2i()) * (k - k1).pow2i()
    }
}

/// 2^54, to bring a subnormal into the normal range before its exponent is read.
const TWO_54: f64 = 18_014_398_509_481_984.0;
const SQRT_2: f64 = std::f64::consts::SQRT_2;

// log(1+f) = 2s + s z L(z), s = f/(2+f), z = s^2, |s| <= 3 - 2 sqrt 2; minimax, weighted
// error 2^-59.5 of log(1+f) (fdlibm's Lg1..Lg7, refitted).
const LOG_L: [f64; 7] = [
    0.6666666666666734,
    0.39999999999417046,
    0.28571428741892535,
    0.222221986216384,
    0.18183561905134982,
    0.15314110405406978,
    0.14795368926688748,
];

/// Natural logarithm, within 1 ulp (0.78 ulp measured), subnormals included.
///
/// `ln(0) = -inf`, `ln(x < 0) = NaN`, `ln(+inf) = +inf`, `ln(NaN) = NaN`.
///
/// fdlibm `e_log.c`: `x = 2^e (1 + f)` with `sqrt(2)/2 < 1 + f < sqrt(2)`,
/// `log(1+f) = f - (f^2/2 - s (f^2/2 + R))` with `s = f/(2+f)` (the one division), which
/// keeps the leading term `f` exact and the rounding in small corrections.
#[inline(always)]
pub fn ln<R: Real>(x: R) -> R {
    // One kernel per call (see `exp`): with every lane positive, normal and finite, the
    // subnormal scaling and the special cases change nothing and are skipped.
    let normal = (x.simd_ge(R::splat(f64::MIN_POSITIVE)) & x.simd_le(R::splat(f64::MAX))).all();
    let (e, m) = if normal {
        x.split_exponent()
    } else {
        let tiny = x.simd_lt(R::splat(f64::MIN_POSITIVE));
        let xs = x * R::select(tiny, R::splat(TWO_54), R::one());
        let (e, m) = xs.split_exponent();
        (e - R::select(tiny, R::splat(54.0), R::zero()), m)
    };
    let y = ln_core(e, m);
    if normal {
        return y;
    }
    let y = R::select(x.simd_eq(R::splat(f64::INFINITY)), x, y);
    let y = R::select(x.simd_eq(R::zero()), R::splat(f64::NEG_INFINITY), y);
    // negative and NaN lanes
    R::select(x.simd_ge(R::zero()), y, R::splat(f64::NAN))
}

/// `ln(2^e m)` for `1 <= m < 2`: the fdlibm kernel.
#[inline(always)]
fn ln_core<R: Real>(e: R, m: R) -> R {
    let big = m.simd_gt(R::splat(SQRT_2));
    let m = R::select(big, m * 0.5, m);
    let e = R::select(big, e + 1.0, e);
    // exact: m is within a factor 2 of 1 (Sterbenz)
    let f = m - 1.0;
    let hfsq = (f * f) * 0.5;
    let s = f / (f + 2.0);
    let z = s * s;
    let w = z * z;
    // fdlibm's even/odd split of R(z) = z L(z): two independent Horner chains in w = z^2
    let t1 = w * (w * (w * LOG_L[5] + LOG_L[3]) + LOG_L[1]);
    let t2 = z * (w * (w * (w * LOG_L[6] + LOG_L[4]) + LOG_L[2]) + LOG_L[0]);
    let rz = t1 + t2;
    e * LN2_HI + (f - (hfsq - (s * (hfsq + rz) + e * LN2_LO)))
}

/// `x^y` for `x >= 0`, as `exp(y ln x)`.
///
/// Conventions: `0^y = 0` for y > 0 and `+inf` for y < 0; `x^0 = 1` and `1^y = 1` for every
/// x and y, NaN included (as libm); `x < 0` gives NaN, even for an integral y (unlike libm:
/// the callers take powers of magnitudes only).
///
/// Accuracy: `ln x` is rounded to a double before the multiply, so its relative error
/// (about 2^-53) becomes an absolute error of about `|y ln x| 2^-53` in the exponent and a
/// relative error of the same size in the result: the error grows like `|y ln x|` ulp
/// (measured: at most 1.2 ulp where `|y ln x| <= 1`, and `0.9 (1 + |y ln x|)` ulp overall).
/// This is accepted for the controllers' `|s|^q` with moderate `q`; an exact `y ln x` would
/// need a double-double logarithm and product.
#[inline(always)]
pub fn pow<R: Real>(x: R, y: R) -> R {
    let r = exp(y * ln(x));
    R::select(y.simd_eq(R::zero()) | x.simd_eq(R::one()), R::one(), r)
}

/// Below this |x|, tanh is the odd polynomial; at and above it, `1 - 2/(e^{2|x|} + 1)` with
/// `tanh >= 1/2`, where the subtraction from 1 no longer magnifies the error of the quotient.
const TANH_SPLIT: f64 = 0.5493061443340549; // ln(3)/2
/// tanh(20) rounds to 1 (1 - tanh(20) = 8.5e-18 < 2^-54).
const TANH_CLAMP: f64 = 20.0;

// tanh(x) = x + x z T(z), z = x^2, |x| <= ln(3)/2; minimax, weighted error 2^-59.1 of tanh.
const TANH_T: [f64; 11] = [
    -0.333333333333333,
    0.1333333333332658,
    -0.05396825396375242,
    0.021869488386315004,
    -0.008863232623144325,
    0.0035920924128950127,
    -0.0014555464447061706,
    0.0005884641599029624,
    -0.00023344413421909208,
    8.34238151272913e-05,
    -1.957153329445865e-05,
];

/// Hyperbolic tangent, odd, within 1 ulp (0.86 ulp measured); `tanh(+-inf) = +-1`.
///
/// Small |x|: an odd minimax polynomial (no cancellation near 0). Larger |x|: as Cephes'
/// `tanh`, `1 - 2/(e^{2|x|} + 1)`, with `e^{2|x|}` kept to more than a double (the `p_lo` of
/// the exp kernel) and `e + 1` as an exact sum, so that the one division is the main
/// rounding left.
#[inline(always)]
pub fn tanh<R: Real>(x: R) -> R {
    let ax = x.abs();
    let z = ax * ax;
    let small = ax + (ax * z) * estrin11(z, &TANH_T);

    // 2|x| as |2x|: the same value, but LLVM's SLP vectorizer scalarised part of the kernel
    // when fed `|x| * 2` (seen at AVX-512, Lanes<16>). A NaN lane is clamped here and takes
    // the small branch below.
    let xc = (x * 2.0).abs().min(R::splat(2.0 * TANH_CLAMP));
    let (k, p, p_lo) = exp_kernel(xc);
    let scale = k.pow2i();
    let e = p * scale;
    let e_lo = p_lo * scale;
    // d + d_lo = e^{2|x|} + 1, Fast2Sum since e >= 1
    let d = e + 1.0;
    let d_lo = ((e - d) + 1.0) + e_lo;
    let q = R::splat(2.0) / d;
    // 2/(d + d_lo) = q - corr to first order, with 1/d ~ q/2
    let corr = (q * q) * (d_lo * 0.5);
    // 1 - q with its rounding error (Fast2Sum, q <= 1/2), so that the quotient's own
    // rounding and the last addition are the only roundings left
    let s = R::one() - q;
    let s_err = (R::one() - s) - q;
    let large = s + (s_err + corr);

    let y = R::select(ax.simd_ge(R::splat(TANH_SPLIT)), large, small);
    y.copysign(x)
}
