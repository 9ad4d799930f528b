//! `exp`, `ln`, `pow` and `tanh` over [`Real`] lanes, branch-free (see [`super::math`]).

use super::math::estrin11;
use super::{Mask, Real};

/// ln 2 split for Cody-Waite reduction (fdlibm `e_exp.c`): `LN2_HI` has 32 significant bits,
/// so `k * LN2_HI` is exact for |k| < 2^21 and `x - k * LN2_HI` is exact (Sterbenz).
const LN2_HI: f64 = 0.6931471803691238; // 0x3FE62E42FEE00000
const LN2_LO: f64 = 1.9082149292705877e-10; // 0x3DEA39EF35793C76

/// exp's reduction is by ln2/16: `x = n ln2/16 + r` with `n = 16 k + j`, so that
/// `e^x = 2^k 2^(j/16) e^r` with |r| <= ln2/32 and `2^(j/16)` from a table. The splits of
/// ln2/16 are those of ln2 divided by 16 (exact), so `n * LN2_16_HI` is exact for |n| < 2^21
/// and `x - n * LN2_16_HI` is exact (Sterbenz: x and n ln2/16 are within a factor 2).
pub const INV_LN2_16: f64 = 16.0 * std::f64::consts::LOG2_E;
const LN2_16_HI: f64 = LN2_HI / 16.0;
const LN2_16_LO: f64 = LN2_LO / 16.0;

/// Beyond these, exp is +inf or rounds to 0; clamping keeps `k` within [-1077, 1024] so that
/// the two-step scaling below stays in the exponent range and overflow/underflow happen in
/// the last multiply, rounded once like libm.
const EXP_CLAMP_HI: f64 = 710.0;
const EXP_CLAMP_LO: f64 = -746.0;

/// `2^(j/16)` rounded to binary64, j = 0..15.
const EXP_T: [f64; 16] = [
    f64::from_bits(0x3ff0000000000000),
    f64::from_bits(0x3ff0b5586cf9890f),
    f64::from_bits(0x3ff172b83c7d517b),
    f64::from_bits(0x3ff2387a6e756238),
    f64::from_bits(0x3ff306fe0a31b715),
    f64::from_bits(0x3ff3dea64c123422),
    f64::from_bits(0x3ff4bfdad5362a27),
    f64::from_bits(0x3ff5ab07dd485429),
    f64::from_bits(0x3ff6a09e667f3bcd),
    f64::from_bits(0x3ff7a11473eb0187),
    f64::from_bits(0x3ff8ace5422aa0db),
    f64::from_bits(0x3ff9c49182a3f090),
    f64::from_bits(0x3ffae89f995ad3ad),
    f64::from_bits(0x3ffc199bdd85529c),
    f64::from_bits(0x3ffd5818dcfba487),
    f64::from_bits(0x3ffea4afa2a490da),
];

/// `(2^(j/16) - EXP_T[j]) / EXP_T[j]`, the table's rounding as a relative correction, so that
/// the table is in effect exact to about 2^-106.
const EXP_TAIL: [f64; 16] = [
    0.0,
    8.189317638195515e-17,
    -2.7939114859515733e-17,
    7.826573258636076e-17,
    3.3484623336251524e-17,
    3.750854201303127e-17,
    1.9572585293112036e-17,
    5.68648095791174e-17,
    -6.835808657661922e-17,
    -2.3591094770850053e-17,
    5.1548301170786783e-17,
    1.5341410053603723e-17,
    4.875160526227062e-17,
    1.685487290628973e-17,
    1.790126907604513e-17,
    -5.545065618639427e-17,
];

/// `EXP_T[j]` with `j` taken out of its exponent bits: adding `n << 48` to these bits (with
/// `n = 16 k + j`) gives the bits of `2^k EXP_T[j]` ([`Real::add_shl48`]), one integer add
/// instead of building `2^k` and multiplying.
const EXP_T_SHIFTED: [f64; 16] = {
    let mut out = [0.0; 16];
    let mut j = 0;
    while j < 16 {
        out[j] = f64::from_bits(EXP_T[j].to_bits() - ((j as u64) << 48));
        j += 1;
    }
    out
};

/// j as a double, to recover `k = (n - j) / 16` where the scaling cannot be done in the bits.
const EXP_J: [f64; 16] = [
    0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 14.0, 15.0,
];

// exp(r) = 1 + r + r^2 Q(r), |r| <= ln2/32; minimax, weighted error 2^-56.3 of exp(r).
const EXP_Q: [f64; 5] = [
    0.49999999999999606,
    0.16666666664417865,
    0.041666666693093726,
    0.008333471924026418,
    0.0013888597217523644,
];

/// The reduction: `(kd, tmp)` with `kd = x 16/ln2 + ROUNDER` (the integer n in its low bits,
/// for the table lookups) and `e^x = 2^k T_j (1 + tmp)`, `T_j = EXP_T[j]`, for x in
/// [-746, 710].
///
/// fdlibm's reduction `x = n ln2/16 + hi - lo` with `hi` exact, then a polynomial. The
/// correction `lo` is applied at first order to the linear term only
/// (`e^(hi - lo) - 1 ~ hi - lo + r^2 Q(r)`), and the table's own rounding joins as the
/// relative tail, so `tmp` is accurate to about 2^-60 and the result's error is essentially
/// the rounding of the last `s + s tmp`.
#[inline(always)]
fn exp_reduce<R: Real>(x: R) -> (R, R) {
    let kd = x.mul_add(R::splat(INV_LN2_16), R::splat(super::ROUNDER));
    let n = kd - super::ROUNDER;
    // exact, fused or not: `n LN2_16_HI` is exact
    let hi = n.mul_add(R::splat(-LN2_16_HI), x);
    let neg_lo = n * -LN2_16_LO;
    let r = hi + neg_lo;
    let r2 = r * r;
    let q = exp_q(r, r2);
    let t = hi + r2.mul_add(q, neg_lo);
    (kd, t + kd.lookup16(&EXP_TAIL))
}

/// `2^k` and `n` for the `kd` of [`exp_reduce`], with `k = (n - j) / 16` exact.
#[inline(always)]
fn exp_k<R: Real>(kd: R) -> R {
    (kd - super::ROUNDER - kd.lookup16(&EXP_J)) * 0.0625
}

/// `(k, p, p_lo)` with `e^x = 2^k (p + p_lo)` to about 2^-58 relative, `p = fl(p + p_lo)`
/// in [0.98, 2.05], for x in [-746, 710]: for callers that want more than a double (tanh).
#[inline(always)]
fn exp_kernel<R: Real>(x: R) -> (R, R, R) {
    let (kd, tmp) = exp_reduce(x);
    let t = kd.lookup16(&EXP_T);
    let tt = t * tmp;
    let p = t + tt;
    // Fast2Sum: |t| > |tt|
    let p_lo = (t - p) + tt;
    (exp_k(kd), p, p_lo)
}

/// `e^x`, within 1 ulp of the correctly rounded result (0.55 ulp measured).
///
/// Overflows to +inf for x > 709.78..., underflows gradually through the subnormals to 0
/// (below -745.13...), `exp(-inf) = 0`, `exp(+inf) = +inf`, `exp(NaN) = NaN`.
///
/// A table of 16 powers `2^(j/16)` shortens the polynomial from degree 11 to 6 (the table
/// lookup is one instruction with AVX-512, a gather with AVX2). One reduction per call,
/// whatever the lanes hold: only the last scaling depends on the range, and the branch
/// between its two forms is the only one. A fast path and a general path, each with its own
/// kernel, made every call site twice as large (the extension compiled in 122 s instead of
/// 94); the general path out of line made W1 8 % slower than this form (register spills
/// around the never-taken calls). See BENCHMARKS.md.
#[inline(always)]
pub fn exp<R: Real>(x: R) -> R {
    // constant first: max/min return their second operand for a NaN, so NaN goes through.
    // Inside [-700, 700] the clamp changes nothing.
    let xc = R::splat(EXP_CLAMP_HI).min(R::splat(EXP_CLAMP_LO).max(x));
    let (kd, tmp) = exp_reduce(xc);
    if (x.simd_ge(R::splat(-700.0)) & x.simd_le(R::splat(700.0))).all() {
        scale_normal(kd, tmp)
    } else {
        scale_general(kd, tmp)
    }
}

/// `2^k T_j (1 + tmp)` for the `(kd, tmp)` of a reduction, where the result is normal:
/// `s = 2^k T_j` from the bits, and scaling by it commutes with the roundings, so the same
/// bits as [`scale_general`].
#[inline(always)]
fn scale_normal<R: Real>(kd: R, tmp: R) -> R {
    let s = kd.lookup16(&EXP_T_SHIFTED).add_shl48(kd);
    s.mul_add(tmp, s)
}

/// `2^k T_j (1 + tmp)` for any k the clamps allow: 2^k in two factors, `p 2^k1` exact and
/// normal, and the multiply by 2^k2 rounding once, into the subnormals or to infinity when the
/// result leaves the normal range.
#[inline(always)]
fn scale_general<R: Real>(kd: R, tmp: R) -> R {
    let t = kd.lookup16(&EXP_T);
    let p = t.mul_add(tmp, t);
    let k = exp_k(kd);
    let k1 = k.max(R::splat(-1000.0)).min(R::splat(1000.0));
    (p * k1.pow2i()) * (k - k1).pow2i()
}

/// `Q(r)` of `e^r = 1 + r + r^2 Q(r)` (Estrin's scheme, `r2 = r^2`).
#[inline(always)]
fn exp_q<R: Real>(r: R, r2: R) -> R {
    let a0 = r.mul_add(R::splat(EXP_Q[1]), R::splat(EXP_Q[0]));
    let a1 = r.mul_add(R::splat(EXP_Q[3]), R::splat(EXP_Q[2]));
    r2.mul_add(r2.mul_add(R::splat(EXP_Q[4]), a1), a0)
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
    log_with::<false, R>(x)
}

/// `16 log2(x)`: the logarithm in the units [`exp16`] takes (see [`PowLog`]); the special
/// values as [`ln`]'s. `16 e` is exact and the logarithm of the significand is rounded once
/// more by the conversion: within 1.5 ulp.
#[inline(always)]
fn log16<R: Real>(x: R) -> R {
    log_with::<true, R>(x)
}

/// The logarithm, `ln x` or (`UNITS16`) `16 log2 x`, from `x = 2^e (1 + f)` and
/// `log(1+f) = f - (hfsq - sr)` (see [`ln_core`]); the special values are then set as
/// [`ln`]'s. (A flag rather than a closure: a closure is not always inlined, and out of line
/// it would run without the kernel's instruction set.)
#[inline(always)]
fn log_with<const UNITS16: bool, R: Real>(x: R) -> R {
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
    let (e, f, hfsq, sr) = ln_core(e, m);
    // `16 e` and `e LN2_HI` are exact
    let y = if UNITS16 {
        (f - (hfsq - sr)).mul_add(R::splat(INV_LN2_16), e * 16.0)
    } else {
        e.mul_add(
            R::splat(LN2_HI),
            f - (hfsq - e.mul_add(R::splat(LN2_LO), sr)),
        )
    };
    if normal {
        return y;
    }
    let y = R::select(x.simd_eq(R::splat(f64::INFINITY)), x, y);
    let y = R::select(x.simd_eq(R::zero()), R::splat(f64::NEG_INFINITY), y);
    // negative and NaN lanes
    R::select(x.simd_ge(R::zero()), y, R::splat(f64::NAN))
}

/// `ln(2^e m)` for `1 <= m < 2` as `(e', f, hfsq, sr)` with
/// `ln(2^e m) = e' ln2 + f - (hfsq - sr)`: the fdlibm kernel, `f` exact, `hfsq = f^2/2` and
/// `sr = s (f^2/2 + R)` the small corrections.
#[inline(always)]
fn ln_core<R: Real>(e: R, m: R) -> (R, R, R, R) {
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
    let c = |x: f64| R::splat(x);
    let t1 = w * w.mul_add(w.mul_add(c(LOG_L[5]), c(LOG_L[3])), c(LOG_L[1]));
    let t2 = w.mul_add(
        w.mul_add(w.mul_add(c(LOG_L[6]), c(LOG_L[4])), c(LOG_L[2])),
        c(LOG_L[0]),
    );
    let rz = z.mul_add(t2, t1);
    (e, f, hfsq, s * (hfsq + rz))
}

/// Beyond these (in [`exp16`]'s units, `16 log2` of the bounds of [`exp`]), `2^(x/16)` is
/// +inf or rounds to 0.
const EXP16_CLAMP_HI: f64 = 16.0 * 1025.0;
const EXP16_CLAMP_LO: f64 = -16.0 * 1076.0;
/// Inside this, every result is normal (|x/16| <= 1000).
const EXP16_FAST: f64 = 16_000.0;
/// ln2/16 rounded.
const LN2_16: f64 = std::f64::consts::LN_2 / 16.0;

/// `2^(x/16)`, the exponential in [`log16`]'s units: `e^y` is `exp16(y 16/ln2)`, so that
/// `e^(c y)` for a constant `c` is `exp16(c' y)` with `c' = c 16/ln2` ([`INV_LN2_16`]) folded
/// once (the Mars plant's density does this). The same
/// table and polynomial as [`exp`], with a shorter reduction: `x` is already in units of
/// ln2/16, so `n` is its nearest integer and `r = (x - n) ln2/16` (`x - n` exact), where
/// `exp` needs a product and a two-part subtraction. Within 0.6 ulp of `2^(x/16)` for the
/// `x` given.
#[inline(always)]
pub fn exp16<R: Real>(x: R) -> R {
    #[inline(always)]
    fn reduce<R: Real>(x: R) -> (R, R) {
        let kd = x + super::ROUNDER;
        let n = kd - super::ROUNDER;
        let r = (x - n) * LN2_16;
        let r2 = r * r;
        let q = exp_q(r, r2);
        (kd, r2.mul_add(q, r) + kd.lookup16(&EXP_TAIL))
    }
    if x.abs().simd_le(R::splat(EXP16_FAST)).all() {
        let (kd, tmp) = reduce(x);
        scale_normal(kd, tmp)
    } else {
        // NaN goes through the clamp (constant first)
        let xc = R::splat(EXP16_CLAMP_HI).min(R::splat(EXP16_CLAMP_LO).max(x));
        let (kd, tmp) = reduce(xc);
        scale_general(kd, tmp)
    }
}

/// The logarithm of a magnitude, kept for taking several powers of it: `x^q` for each `q`
/// costs a multiply and a short exponential (`PowLog::of(x).pow(q)`), which is how the
/// sliding-mode laws take `|s|^q1`, `|s|^q2` and the like.
///
/// The logarithm is held as `16 log2 x`, the units of the exponential's table reduction, so
/// that neither side multiplies by ln2 (see [`exp16`]). Accuracy: as [`pow`]'s.
#[derive(Clone, Copy, Debug)]
pub struct PowLog<R>(R);

impl<R: Real> PowLog<R> {
    /// The logarithm of `x >= 0` (`x = 0` gives powers 0 for q > 0, +inf for q < 0).
    #[inline(always)]
    pub fn of(x: R) -> Self {
        Self(log16(x))
    }

    /// `x^q`; NaN for `q = 0` at `x = 0` or `x = +inf` (use [`pow`] for libm's conventions).
    #[inline(always)]
    pub fn pow(self, q: R) -> R {
        exp16(q * self.0)
    }
}

/// `x^y` for `x >= 0`, as `2^(y log2 x)` ([`PowLog`]).
///
/// Conventions: `0^y = 0` for y > 0 and `+inf` for y < 0; `x^0 = 1` and `1^y = 1` for every
/// x and y, NaN included (as libm); `x < 0` gives NaN, even for an integral y (unlike libm:
/// the callers take powers of magnitudes only).
///
/// Accuracy: `log2 x` is rounded to a double before the multiply, so its relative error
/// (about 2^-53) becomes an absolute error of about `|y ln x| 2^-53` in the exponent and a
/// relative error of the same size in the result: the error grows like `|y ln x|` ulp
/// (measured against mpmath: at most 1.44 ulp where `|y ln x| <= 1`, and `1.14 (1 + |y ln x|)`
/// ulp overall; `tests/lane_math.rs` bounds it by `1 + 2 |y ln x|`). The logarithm is kept in
/// the exponential's reduction units ([`PowLog`]), which rounds it once more than `ln` and
/// costs about 0.25 |y ln x| ulp over `exp(y ln x)`, for a reduction 4 operations shorter
/// per power: 5 % of the W1 step (BENCHMARKS.md).
/// This is accepted for the controllers' `|s|^q` with moderate `q`; an exact `y ln x` would
/// need a double-double logarithm and product.
#[inline(always)]
pub fn pow<R: Real>(x: R, y: R) -> R {
    let r = PowLog::of(x).pow(y);
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
