//! `sin`, `cos`, `sin_cos` and `atan2` over [`Real`] lanes, branch-free (see
//! [`super::math`]).

use super::math::{estrin11, two_diff};
use super::{Mask, Real};

const FRAC_2_PI: f64 = std::f64::consts::FRAC_2_PI;
/// pi/2 in three pieces of 31, 32 and 28 significant bits and a 53-bit tail (fdlibm
/// `e_rem_pio2.c`'s pio2_1, pio2_2, pio2_3, pio2_3t; their sum is pi/2 within 2^-160).
/// For |k| <= 2^20 each `k * PIO2_i` is exact.
const PIO2_1: f64 = 1.5707963267341256; // 0x3FF921FB54400000
const PIO2_2: f64 = 6.077100506303966e-11; // 0x3DD0B4611A600000
const PIO2_3: f64 = 2.0222662487111665e-21; // 0x3BA3198A2E000000
const PIO2_3T: f64 = 8.4784276603689e-32; // 0x397B839A252049C1
/// 2^20 pi/2 (rounded down): below it the reduction is exact enough (|k| <= 2^20); above it,
/// the cold libm path.
const REDUCE_LIMIT: f64 = 1_647_099.0;

// sin(x) = x + x^3 S(z), z = x^2, |x| <= pi/4; minimax, weighted error 2^-57.9 of sin
// (fdlibm's S1..S6, refitted).
const SIN_S: [f64; 6] = [
    -0.1666666666666663,
    0.00833333333332184,
    -0.00019841269829358528,
    2.7557313538514234e-06,
    -2.5050734389256567e-08,
    1.5895433289228515e-10,
];
// cos(x) = 1 - z/2 + z^2 C(z), |x| <= pi/4; minimax, weighted error 2^-63.9 of cos
// (fdlibm's C1..C6, refitted).
const COS_C: [f64; 6] = [
    0.041666666666666595,
    -0.0013888888888873342,
    2.480158728900208e-05,
    -2.755731421703886e-07,
    2.08757053960285e-09,
    -1.1358749239858315e-11,
];

/// `(sin(x + y), cos(x + y))` for |x| <= pi/4 and |y| <= ulp(x)/2 (fdlibm `k_sin.c`, and
/// FreeBSD's `k_cos.c`, whose `w + ((1 - w) - hz)` recovers the rounding of `1 - z/2`).
#[inline(always)]
fn sin_cos_kernel<R: Real>(x: R, y: R) -> (R, R) {
    let z = x * x;
    let w = z * z;
    let v = z * x;
    let c = |x: f64| R::splat(x);
    let rs = (z * w).mul_add(
        z.mul_add(c(SIN_S[5]), c(SIN_S[4])),
        z.mul_add(z.mul_add(c(SIN_S[3]), c(SIN_S[2])), c(SIN_S[1])),
    );
    let sin = x - (((z * (y * 0.5 - v * rs)) - y) - v * SIN_S[0]);
    let rc = (w * w).mul_add(
        z.mul_add(z.mul_add(c(COS_C[5]), c(COS_C[4])), c(COS_C[3])),
        z * z.mul_add(z.mul_add(c(COS_C[2]), c(COS_C[1])), c(COS_C[0])),
    );
    let hz = z * 0.5;
    let one_hz = R::one() - hz;
    let cos = one_hz + (((R::one() - one_hz) - hz) + (z * rc - x * y));
    (sin, cos)
}

/// Sine and cosine with one shared reduction, each within 1 ulp (0.76 ulp measured).
///
/// Reduction (Cody-Waite in three exact steps, fdlibm `e_rem_pio2.c`'s medium case without its
/// branches): `k = round(x 2/pi)`, `r = x - k pi/2` with pi/2 in the pieces above; every
/// product is exact and both subtractions that can round are TwoSums, so `r + r_lo` is
/// accurate to about 2^-100 absolutely, enough for the closest approach of a double to a
/// multiple of pi/2 in the range (about 2^-60). The quadrant `k mod 4` picks and signs the
/// kernel's values.
///
/// `sin(+-inf) = cos(+-inf) = NaN`, NaN propagates, `sin(-0) = -0`.
///
/// Cold path: lanes with |x| > 2^20 pi/2 (about 1.6e6) are recomputed by libm, one lane at a
/// time, behind a single `any()` test. The simulations' arguments are angles and phases, far
/// below that; the path exists so that the result stays correct there. It gives the same
/// bits on every path too, libm being the same function for every lane.
#[inline(always)]
pub fn sin_cos<R: Real>(x: R) -> (R, R) {
    let k = (x * FRAC_2_PI).round_small();
    let a = x - k * PIO2_1;
    let (b, eb) = two_diff(a, k * PIO2_2);
    let (c, ec) = two_diff(b, k * PIO2_3);
    // `c - nlo` rather than `c + lo`: the same value, but it keeps the sign of -0
    let nlo = k * PIO2_3T - (eb + ec);
    let r = c - nlo;
    let r_lo = (c - r) - nlo;
    let (s, co) = sin_cos_kernel(r, r_lo);

    // n = k mod 4 (k - 4 floor(k/4), floor by rounding k/4 - 3/8, never a tie)
    let n = k - ((k * 0.25) - 0.375).round_small() * 4.0;
    let odd = n.simd_eq(R::one()) | n.simd_eq(R::splat(3.0));
    let sin_neg = n.simd_ge(R::splat(2.0));
    let cos_neg = odd ^ sin_neg;
    let sv = R::select(odd, co, s);
    let cv = R::select(odd, s, co);
    let mut sin = R::select(sin_neg, -sv, sv);
    let mut cos = R::select(cos_neg, -cv, cv);

    let huge = x.abs().simd_gt(R::splat(REDUCE_LIMIT));
    if huge.any() {
        sin_cos_libm(x, huge, &mut sin, &mut cos);
    }
    (sin, cos)
}

/// The cold path of [`sin_cos`]: libm per lane for the lanes of `mask` (|x| > 2^20 pi/2 and
/// infinities).
#[cold]
#[inline(never)]
fn sin_cos_libm<R: Real>(x: R, mask: R::Mask, sin: &mut R, cos: &mut R) {
    for i in 0..R::LANES {
        if mask.lane(i) {
            let v = x.lane(i);
            sin.set_lane(i, f64::sin(v));
            cos.set_lane(i, f64::cos(v));
        }
    }
}

/// Sine, within 1 ulp; see [`sin_cos`] (the same cost: both kernels are needed to pick per
/// quadrant).
#[inline(always)]
pub fn sin<R: Real>(x: R) -> R {
    sin_cos(x).0
}

/// Cosine, within 1 ulp; see [`sin_cos`].
#[inline(always)]
pub fn cos<R: Real>(x: R) -> R {
    sin_cos(x).1
}

// atan(u) = u + u z P(z), z = u^2, |u| <= 7/16; minimax, weighted error 2^-57.7 of atan
// (the role of fdlibm's aT[], refitted).
const ATAN_P: [f64; 11] = [
    -0.3333333333333292,
    0.19999999999873752,
    -0.14285714272267222,
    0.11111110395277891,
    -0.0909088688034973,
    0.07691872308221541,
    -0.06661034743065077,
    0.05833327683012328,
    -0.049759288004344746,
    0.03651059570977132,
    -0.016265817263142465,
];

/// Constant angles as `HI + LO`, each `HI` a multiple of 2^-40 below 4, so that sums and
/// differences of `HI`s are exact and only the small `LO`s round.
const PIO4_HI: f64 = 0.7853981633970761;
const PIO4_LO: f64 = 3.7217737402433116e-13;
const ATAN_HALF_HI: f64 = 0.46364760900087276;
const ATAN_HALF_LO: f64 = -6.664619385128769e-14;
const PIO2_HI: f64 = 1.5707963267950618;
const PIO2_LO: f64 = -1.6513995372426591e-13;
const PI_HI: f64 = 3.1415926535901235;
const PI_LO: f64 = -3.3027990744853183e-13;

/// The angle of `(x, y)`, in [-pi, pi], within 1.5 ulp (1.41 ulp measured; below 1 ulp
/// except where b/a is a little above a power of two, see the quotient below), with libm's
/// conventions: `atan2(+-0, +0) = +-0`, `atan2(+-0, -0) = +-pi`, `atan2(+-y, -inf) = +-pi`,
/// `atan2(+-inf, +-inf) = +-pi/4, +-3pi/4`, `atan2(+-inf, x) = +-pi/2`, NaN propagates.
///
/// With `a = max(|x|, |y|)`, `b = min(|x|, |y|)`, `atan(b/a)` is reduced as fdlibm `s_atan.c`
/// does for its argument in [0, 1]: `atan(t) = atan(c) + atan((t - c)/(1 + c t))` with
/// c = 0, 1/2, 1 on t < 7/16, < 11/16, <= 1, written as `(b - c a)/(a + c b)` so that the one
/// division serves both the ratio and the reduction (and `b - c a` is exact, Sterbenz). Then
/// `atan2 = K + sigma atan(b/a)` with `K` in {0, pi/2, pi} and `sigma = +-1` by swap and
/// the sign of x (fdlibm `e_atan2.c`'s quadrants), `K + sigma atan(c)` summed exactly in the
/// `HI` parts, and the sign of y last.
#[inline(always)]
pub fn atan2<R: Real>(y: R, x: R) -> R {
    let ax = x.abs();
    let ay = y.abs();
    let swap = ay.simd_gt(ax);
    // selects rather than max/min, so that a NaN in either input reaches the division
    let a = R::select(swap, ay, ax);
    let b = R::select(swap, ax, ay);
    // scale by a power of two so that neither `a + b` overflows nor `a/2` loses a subnormal's
    // last bit (a b that underflows in the scaling has b/a < 2^-1400 anyway)
    let scale = R::select(
        a.simd_gt(R::splat(TWO_512)),
        R::splat(1.0 / TWO_64),
        R::splat(TWO_64),
    );
    let a = a * scale;
    let b = b * scale;
    // both infinite: the angle of (1, 1) (b == a: not when a is NaN)
    let both_inf = b.simd_eq(R::splat(f64::INFINITY)) & a.simd_eq(b);
    let a = R::select(both_inf, R::one(), a);
    let b = R::select(both_inf, R::one(), b);

    let mid = b.simd_gt(a * (7.0 / 16.0));
    let high = b.simd_gt(a * (11.0 / 16.0));
    let num = R::select(high, b - a, R::select(mid, b - a * 0.5, b));
    let den = R::select(high, a + b, R::select(mid, a + b * 0.5, a));
    // a = b = 0: u = 0/1
    let den = R::select(a.simd_eq(R::zero()), R::one(), den);
    // The rounding of this quotient is the largest error: half an ulp of u, which is a whole
    // ulp of the result where atan(u) lies just below a power of two that u is above (u a
    // little above 1/4, 1/8, ...). Carrying u's remainder (Dekker's product, with 1/den in
    // place of the division) brings the maximum from 1.4 to 0.7 ulp but makes atan2 about
    // 1.5 times as slow; not worth it here.
    let u = num / den;

    let xneg = R::one().copysign(x).simd_lt(R::zero());
    let sigma = R::select(swap ^ xneg, -R::one(), R::one());
    let k_hi = R::select(
        swap,
        R::splat(PIO2_HI),
        R::select(xneg, R::splat(PI_HI), R::zero()),
    );
    let k_lo = R::select(
        swap,
        R::splat(PIO2_LO),
        R::select(xneg, R::splat(PI_LO), R::zero()),
    );
    let c_hi = R::select(
        high,
        R::splat(PIO4_HI),
        R::select(mid, R::splat(ATAN_HALF_HI), R::zero()),
    );
    let c_lo = R::select(
        high,
        R::splat(PIO4_LO),
        R::select(mid, R::splat(ATAN_HALF_LO), R::zero()),
    );
    let hi = k_hi + sigma * c_hi;
    let lo = k_lo + sigma * c_lo;

    let v = sigma * u;
    let z = u * u;
    let tail = v + ((v * z) * estrin11(z, &ATAN_P) + lo);
    (hi + tail).copysign(y)
}

const TWO_64: f64 = 18_446_744_073_709_551_616.0;
const TWO_512: f64 = 1.340_780_792_994_259_7e154;
