//! Lane types over x86-64 vector registers, one per instruction-set level: `Sse2<N>` (N
//! registers of 2 lanes), `Avx2<N>` (4 lanes each) and `Avx512<N>` (8 lanes each).
//!
//! [`Lanes<W>`](super::Lanes) leaves the vectorisation to the compiler, which does not always
//! find it inside a large kernel (it may gather across axes or mix register widths). These
//! types say it with intrinsics: each operation is one instruction per register, the same IEEE
//! operation in every lane as `f64`'s ([`Real`]'s contract): `min`/`max` are `minpd`/`maxpd`,
//! whose "second operand unless the first is smaller" is exactly `Real::min`; comparisons are
//! ordered and quiet; `is_finite` is `x - x == 0`; `mul_add` is `vfmadd` (AVX2, AVX-512) or
//! libm's `fma` per lane (SSE2, which has no fused multiply-add).
//!
//! The intrinsics need their level's target features; every method is `#[inline(always)]` and
//! the types are only used inside the kernels compiled for their level, which run only on CPUs
//! that have it (checked by [`crate::kernel::Level::resolve`]).

#![allow(unsafe_op_in_unsafe_fn, unused_unsafe)]

use std::arch::x86_64::*;
use std::fmt;
use std::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use super::{Mask, ROUNDER, Real};

/// The register-level operations of one level.
macro_rules! level {
    (
        $ty:ident, $mask:ident, $reg:ty, $mreg:ty, $width:expr,
        set1: $set1:path, add: $add:path, sub: $sub:path, mul: $mul:path, div: $div:path,
        sqrt: $sqrt:path, fma: $fma:expr, min: $min:path, max: $max:path,
        and: $and:path, or: $or:path, xor: $xor:path, andnot: $andnot:path,
        slli: $slli:expr, srli: $srli:expr, cast_i: $cast_i:path, cast_d: $cast_d:path,
        set1_i: $set1_i:path, or_i: $or_i:path, and_i: $and_i:path,
        lt: $lt:expr, le: $le:expr, gt: $gt:expr, ge: $ge:expr, eq: $eq:expr,
        blend: $blend:expr, mand: $mand:expr, mor: $mor:expr, mxor: $mxor:expr, mnot: $mnot:expr,
        bits: $bits:expr, mtrue: $mtrue:expr, mfalse: $mfalse:expr,
        split: $split:path, scale2: $scale2:path, lookup16: $lookup16:path,
        add_shl48: $add_shl48:path, rows3: $rows3:path, cols3: $cols3:path,
        features: [$($features:literal)?] $(,)?
    ) => {
        /// N vector registers of lanes (see the module documentation).
        #[derive(Clone, Copy)]
        #[repr(C)]
        pub struct $ty<const N: usize>(pub [$reg; N]);

        /// The per-lane mask of the same level.
        #[derive(Clone, Copy)]
        #[repr(C)]
        pub struct $mask<const N: usize>(pub [$mreg; N]);

        impl<const N: usize> $ty<N> {
            pub const LANES: usize = $width * N;

            #[inline(always)]
            fn map(self, f: impl Fn($reg) -> $reg) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = f(self.0[k]);
                }
                Self(out)
            }

            #[inline(always)]
            fn zip(self, o: Self, f: impl Fn($reg, $reg) -> $reg) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = f(self.0[k], o.0[k]);
                }
                Self(out)
            }

            #[inline(always)]
            fn compare(self, o: Self, f: impl Fn($reg, $reg) -> $mreg) -> $mask<N> {
                let mut out = [$mfalse; N];
                for k in 0..N {
                    out[k] = f(self.0[k], o.0[k]);
                }
                $mask(out)
            }
        }

        // sin_cos, tanh and atan2 compiled once per lane type, out of line, with the level's
        // target features: inlined at every call site, each would carry its own copy, several
        // hundred instructions per register, and the kernels' compile time and size would grow
        // with every law. (exp and ln stay inline: independent calls of one step interleave,
        // and W1 calls them twenty times a step.)
        impl<const N: usize> $ty<N> {
            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn sin_cos_outlined(x: Self) -> (Self, Self) {
                super::math::sin_cos(x)
            }
            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn tanh_outlined(x: Self) -> Self {
                super::math::tanh(x)
            }
            $(#[target_feature(enable = $features)])?
            #[inline(never)]
            unsafe fn atan2_outlined(y: Self, x: Self) -> Self {
                super::math::atan2(y, x)
            }
        }

        impl<const N: usize> fmt::Debug for $ty<N> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_list()
                    .entries((0..Self::LANES).map(|i| self.lane(i)))
                    .finish()
            }
        }

        impl<const N: usize> PartialEq for $ty<N> {
            fn eq(&self, other: &Self) -> bool {
                (0..Self::LANES).all(|i| self.lane(i) == other.lane(i))
            }
        }

        impl<const N: usize> fmt::Debug for $mask<N> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.debug_list()
                    .entries((0..$width * N).map(|i| self.lane(i)))
                    .finish()
            }
        }

        impl<const N: usize> Mask for $mask<N> {
            const LANES: usize = $width * N;
            #[inline(always)]
            fn splat(value: bool) -> Self {
                Self([if value { $mtrue } else { $mfalse }; N])
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
                let mut lanes = $ty::<N>::splat(0.0);
                for i in 0..$width * N {
                    lanes.set_lane(i, if f(i) { 1.0 } else { 0.0 });
                }
                lanes.simd_gt($ty::<N>::splat(0.5))
            }
            #[inline(always)]
            fn lane(&self, i: usize) -> bool {
                let bits: u64 = unsafe { ($bits)(self.0[i / $width]) };
                (bits >> (i % $width)) & 1 == 1
            }
            #[inline(always)]
            fn any(self) -> bool {
                let mut acc = 0u64;
                for k in 0..N {
                    acc |= unsafe { ($bits)(self.0[k]) };
                }
                acc != 0
            }
            #[inline(always)]
            fn all(self) -> bool {
                let full = (1u64 << $width) - 1;
                let mut acc = full;
                for k in 0..N {
                    acc &= unsafe { ($bits)(self.0[k]) };
                }
                acc == full
            }
        }

        impl<const N: usize> BitAnd for $mask<N> {
            type Output = Self;
            #[inline(always)]
            fn bitand(self, o: Self) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = unsafe { ($mand)(self.0[k], o.0[k]) };
                }
                Self(out)
            }
        }

        impl<const N: usize> BitOr for $mask<N> {
            type Output = Self;
            #[inline(always)]
            fn bitor(self, o: Self) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = unsafe { ($mor)(self.0[k], o.0[k]) };
                }
                Self(out)
            }
        }

        impl<const N: usize> BitXor for $mask<N> {
            type Output = Self;
            #[inline(always)]
            fn bitxor(self, o: Self) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = unsafe { ($mxor)(self.0[k], o.0[k]) };
                }
                Self(out)
            }
        }

        impl<const N: usize> Not for $mask<N> {
            type Output = Self;
            #[inline(always)]
            fn not(self) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = unsafe { ($mnot)(self.0[k]) };
                }
                Self(out)
            }
        }

        level!(@binop $ty, Add, add, AddAssign, add_assign, $add, $set1);
        level!(@binop $ty, Sub, sub, SubAssign, sub_assign, $sub, $set1);
        level!(@binop $ty, Mul, mul, MulAssign, mul_assign, $mul, $set1);
        level!(@binop $ty, Div, div, DivAssign, div_assign, $div, $set1);

        impl<const N: usize> Neg for $ty<N> {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                // flip the sign bit, as f64's negation does (a subtraction from 0 would not
                // negate a zero)
                self.map(|a| unsafe { $xor(a, $set1(-0.0)) })
            }
        }

        impl<const N: usize> num_traits::Zero for $ty<N> {
            #[inline(always)]
            fn zero() -> Self {
                Self::splat(0.0)
            }
            fn is_zero(&self) -> bool {
                (0..Self::LANES).all(|i| self.lane(i) == 0.0)
            }
        }

        impl<const N: usize> num_traits::One for $ty<N> {
            #[inline(always)]
            fn one() -> Self {
                Self::splat(1.0)
            }
        }

        impl<const N: usize> Real for $ty<N> {
            type Mask = $mask<N>;
            const LANES: usize = $width * N;

            #[inline(always)]
            fn splat(value: f64) -> Self {
                Self([unsafe { $set1(value) }; N])
            }
            #[inline(always)]
            fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
                let mut out = Self::splat(0.0);
                for i in 0..$width * N {
                    out.set_lane(i, f(i));
                }
                out
            }
            #[inline(always)]
            fn lane(&self, i: usize) -> f64 {
                // SAFETY: the registers are N * WIDTH f64 in memory order
                unsafe { *(self.0.as_ptr() as *const f64).add(i) }
            }
            #[inline(always)]
            fn write_rows<const D: usize>(v: &[Self; D], out: &mut [f64], used: usize) {
                if D == 3 && used == $width * N {
                    let out = &mut out[..3 * $width * N];
                    for k in 0..N {
                        // SAFETY: `out` holds `3 WIDTH` values from `3 WIDTH k` on (the slice
                        // above is of `3 WIDTH N`)
                        let to = unsafe { out.as_mut_ptr().add(3 * $width * k) };
                        unsafe { ($rows3)(v[0].0[k], v[1].0[k], v[2].0[k], to) }
                    }
                } else {
                    super::write_rows_by_lane(v, out, used);
                }
            }
            #[inline(always)]
            fn read_rows<const D: usize>(rows: &[f64], used: usize) -> [Self; D] {
                if D == 3 && used == $width * N {
                    let rows = &rows[..3 * $width * N];
                    let mut v = [Self::splat(0.0); D];
                    for k in 0..N {
                        // SAFETY: `rows` holds `3 WIDTH` values from `3 WIDTH k` on (the slice
                        // above is of `3 WIDTH N`)
                        let from = unsafe { rows.as_ptr().add(3 * $width * k) };
                        let (x, y, z) = unsafe { ($cols3)(from) };
                        (v[0].0[k], v[1].0[k], v[2].0[k]) = (x, y, z);
                    }
                    v
                } else {
                    super::read_rows_by_lane(rows, used)
                }
            }
            #[inline(always)]
            fn set_lane(&mut self, i: usize, value: f64) {
                assert!(i < $width * N);
                // SAFETY: as for `lane`, and i is in bounds
                unsafe { *(self.0.as_mut_ptr() as *mut f64).add(i) = value }
            }
            #[inline(always)]
            fn abs(self) -> Self {
                self.map(|a| unsafe { $andnot($set1(-0.0), a) })
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                self.map(|a| unsafe { $sqrt(a) })
            }
            #[inline(always)]
            fn mul_add(self, a: Self, b: Self) -> Self {
                let mut out = self.0;
                for k in 0..N {
                    out[k] = unsafe { ($fma)(self.0[k], a.0[k], b.0[k]) };
                }
                Self(out)
            }
            #[inline(always)]
            fn min(self, other: Self) -> Self {
                self.zip(other, |a, b| unsafe { $min(a, b) })
            }
            #[inline(always)]
            fn max(self, other: Self) -> Self {
                self.zip(other, |a, b| unsafe { $max(a, b) })
            }
            #[inline(always)]
            fn copysign(self, sign: Self) -> Self {
                self.zip(sign, |a, s| unsafe {
                    let m = $set1(-0.0);
                    $or($andnot(m, a), $and(m, s))
                })
            }
            #[inline(always)]
            fn simd_lt(self, other: Self) -> $mask<N> {
                self.compare(other, |a, b| unsafe { ($lt)(a, b) })
            }
            #[inline(always)]
            fn simd_le(self, other: Self) -> $mask<N> {
                self.compare(other, |a, b| unsafe { ($le)(a, b) })
            }
            #[inline(always)]
            fn simd_gt(self, other: Self) -> $mask<N> {
                self.compare(other, |a, b| unsafe { ($gt)(a, b) })
            }
            #[inline(always)]
            fn simd_ge(self, other: Self) -> $mask<N> {
                self.compare(other, |a, b| unsafe { ($ge)(a, b) })
            }
            #[inline(always)]
            fn simd_eq(self, other: Self) -> $mask<N> {
                self.compare(other, |a, b| unsafe { ($eq)(a, b) })
            }
            #[inline(always)]
            fn select(mask: $mask<N>, a: Self, b: Self) -> Self {
                let mut out = a.0;
                for k in 0..N {
                    out[k] = unsafe { ($blend)(mask.0[k], a.0[k], b.0[k]) };
                }
                Self(out)
            }
            #[inline(always)]
            fn is_finite(self) -> $mask<N> {
                // x - x is +0 for finite x and NaN for an infinity or a NaN
                (self - self).simd_eq(Self::splat(0.0))
            }
            #[inline(always)]
            fn round_small(self) -> Self {
                (self + ROUNDER) - ROUNDER
            }
            #[inline(always)]
            fn pow2i(self) -> Self {
                self.map(|k| unsafe {
                    $cast_d(($slli)($cast_i($add(k, $set1(4_503_599_627_371_519.0)))))
                })
            }
            #[inline(always)]
            fn split_exponent(self) -> (Self, Self) {
                let mut e = self.0;
                let mut m = self.0;
                for k in 0..N {
                    (e[k], m[k]) = unsafe { ($split)(self.0[k]) };
                }
                (Self(e), Self(m))
            }
            #[inline(always)]
            fn scale2(self, k: Self) -> Self {
                self.zip(k, |a, b| unsafe { ($scale2)(a, b) })
            }
            #[inline(always)]
            fn lookup16(self, table: &[f64; 16]) -> Self {
                self.map(|a| unsafe { ($lookup16)(a, table) })
            }
            #[inline(always)]
            fn add_shl48(self, n: Self) -> Self {
                self.zip(n, |a, b| unsafe { ($add_shl48)(a, b) })
            }

            // SAFETY (the six below): as for the intrinsics, this type is used only inside
            // the kernels of its level, which run only on CPUs that have its features.
            #[inline(always)]
            fn sin(self) -> Self {
                self.sin_cos().0
            }
            #[inline(always)]
            fn cos(self) -> Self {
                self.sin_cos().1
            }
            #[inline(always)]
            fn sin_cos(self) -> (Self, Self) {
                unsafe { Self::sin_cos_outlined(self) }
            }
            #[inline(always)]
            fn tanh(self) -> Self {
                unsafe { Self::tanh_outlined(self) }
            }
            #[inline(always)]
            fn atan2(self, x: Self) -> Self {
                unsafe { Self::atan2_outlined(self, x) }
            }
        }
    };

    (@binop $ty:ident, $tr:ident, $f:ident, $atr:ident, $af:ident, $op:path, $set1:path) => {
        impl<const N: usize> $tr for $ty<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                self.zip(rhs, |a, b| unsafe { $op(a, b) })
            }
        }
        impl<const N: usize> $tr<f64> for $ty<N> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: f64) -> Self {
                self.map(|a| unsafe { $op(a, $set1(rhs)) })
            }
        }
        impl<const N: usize> $atr for $ty<N> {
            #[inline(always)]
            fn $af(&mut self, rhs: Self) {
                *self = $tr::$f(*self, rhs);
            }
        }
    };
}

level!(
    Sse2, Sse2Mask, __m128d, __m128d, 2,
    set1: _mm_set1_pd, add: _mm_add_pd, sub: _mm_sub_pd, mul: _mm_mul_pd, div: _mm_div_pd,
    sqrt: _mm_sqrt_pd, fma: sse2_ops::fma, min: _mm_min_pd, max: _mm_max_pd,
    and: _mm_and_pd, or: _mm_or_pd, xor: _mm_xor_pd, andnot: _mm_andnot_pd,
    slli: |x| _mm_slli_epi64::<52>(x), srli: |x| _mm_srli_epi64::<52>(x), cast_i: _mm_castpd_si128,
    cast_d: _mm_castsi128_pd, set1_i: _mm_set1_epi64x, or_i: _mm_or_si128, and_i: _mm_and_si128,
    lt: |a, b| _mm_cmplt_pd(a, b),
    le: |a, b| _mm_cmple_pd(a, b),
    gt: |a, b| _mm_cmpgt_pd(a, b),
    ge: |a, b| _mm_cmpge_pd(a, b),
    eq: |a, b| _mm_cmpeq_pd(a, b),
    blend: |m, a, b| _mm_or_pd(_mm_and_pd(m, a), _mm_andnot_pd(m, b)),
    mand: |a, b| _mm_and_pd(a, b),
    mor: |a, b| _mm_or_pd(a, b),
    mxor: |a, b| _mm_xor_pd(a, b),
    mnot: |m| _mm_xor_pd(m, _mm_castsi128_pd(_mm_set1_epi64x(-1))),
    bits: |m| _mm_movemask_pd(m) as u64,
    mtrue: unsafe { _mm_castsi128_pd(_mm_set1_epi64x(-1)) },
    mfalse: unsafe { _mm_setzero_pd() },
    split: sse2_ops::split,
    scale2: sse2_ops::scale2,
    lookup16: sse2_ops::lookup16,
    add_shl48: sse2_ops::add_shl48,
    rows3: sse2_ops::rows3,
    cols3: sse2_ops::cols3,
    features: [],
);

level!(
    Avx2, Avx2Mask, __m256d, __m256d, 4,
    set1: _mm256_set1_pd, add: _mm256_add_pd, sub: _mm256_sub_pd, mul: _mm256_mul_pd,
    div: _mm256_div_pd, sqrt: _mm256_sqrt_pd, fma: |a, b, c| _mm256_fmadd_pd(a, b, c), min: _mm256_min_pd, max: _mm256_max_pd,
    and: _mm256_and_pd, or: _mm256_or_pd, xor: _mm256_xor_pd, andnot: _mm256_andnot_pd,
    slli: |x| _mm256_slli_epi64::<52>(x), srli: |x| _mm256_srli_epi64::<52>(x), cast_i: _mm256_castpd_si256,
    cast_d: _mm256_castsi256_pd, set1_i: _mm256_set1_epi64x, or_i: _mm256_or_si256,
    and_i: _mm256_and_si256,
    lt: |a, b| _mm256_cmp_pd::<_CMP_LT_OQ>(a, b),
    le: |a, b| _mm256_cmp_pd::<_CMP_LE_OQ>(a, b),
    gt: |a, b| _mm256_cmp_pd::<_CMP_GT_OQ>(a, b),
    ge: |a, b| _mm256_cmp_pd::<_CMP_GE_OQ>(a, b),
    eq: |a, b| _mm256_cmp_pd::<_CMP_EQ_OQ>(a, b),
    blend: |m, a, b| _mm256_blendv_pd(b, a, m),
    mand: |a, b| _mm256_and_pd(a, b),
    mor: |a, b| _mm256_or_pd(a, b),
    mxor: |a, b| _mm256_xor_pd(a, b),
    mnot: |m| _mm256_xor_pd(m, _mm256_castsi256_pd(_mm256_set1_epi64x(-1))),
    bits: |m| _mm256_movemask_pd(m) as u64,
    mtrue: unsafe { _mm256_castsi256_pd(_mm256_set1_epi64x(-1)) },
    mfalse: unsafe { _mm256_setzero_pd() },
    split: avx2_ops::split,
    scale2: avx2_ops::scale2,
    lookup16: avx2_ops::lookup16,
    add_shl48: avx2_ops::add_shl48,
    rows3: avx2_ops::rows3,
    cols3: avx2_ops::cols3,
    features: ["avx2,fma,bmi1,bmi2,lzcnt,popcnt"],
);

level!(
    Avx512, Avx512Mask, __m512d, __mmask8, 8,
    set1: _mm512_set1_pd, add: _mm512_add_pd, sub: _mm512_sub_pd, mul: _mm512_mul_pd,
    div: _mm512_div_pd, sqrt: _mm512_sqrt_pd, fma: |a, b, c| _mm512_fmadd_pd(a, b, c), min: _mm512_min_pd, max: _mm512_max_pd,
    and: _mm512_and_pd, or: _mm512_or_pd, xor: _mm512_xor_pd, andnot: _mm512_andnot_pd,
    slli: |x| _mm512_slli_epi64::<52>(x), srli: |x| _mm512_srli_epi64::<52>(x), cast_i: _mm512_castpd_si512,
    cast_d: _mm512_castsi512_pd, set1_i: _mm512_set1_epi64, or_i: _mm512_or_si512,
    and_i: _mm512_and_si512,
    lt: |a, b| _mm512_cmp_pd_mask::<_CMP_LT_OQ>(a, b),
    le: |a, b| _mm512_cmp_pd_mask::<_CMP_LE_OQ>(a, b),
    gt: |a, b| _mm512_cmp_pd_mask::<_CMP_GT_OQ>(a, b),
    ge: |a, b| _mm512_cmp_pd_mask::<_CMP_GE_OQ>(a, b),
    eq: |a, b| _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(a, b),
    blend: |m, a, b| _mm512_mask_blend_pd(m, b, a),
    mand: |a: __mmask8, b: __mmask8| a & b,
    mor: |a: __mmask8, b: __mmask8| a | b,
    mxor: |a: __mmask8, b: __mmask8| a ^ b,
    mnot: |m: __mmask8| !m,
    bits: |m: __mmask8| m as u64,
    mtrue: 0xFFu8,
    mfalse: 0u8,
    // IEEE 754 logB and the significand, and scaleB: exact, the same values as the bit
    // manipulations of the other levels where those are defined (positive normal inputs,
    // normal results)
    split: avx512_ops::split,
    scale2: avx512_ops::scale2,
    lookup16: avx512_ops::lookup16,
    add_shl48: avx512_ops::add_shl48,
    rows3: avx512_ops::rows3,
    cols3: avx512_ops::cols3,
    features: ["avx2,fma,bmi1,bmi2,lzcnt,popcnt,avx512f,avx512cd,avx512bw,avx512dq,avx512vl"],
);

/// SSE2's logB/significand and scaleB, as functions: a closure this large is not always
/// inlined, and out of line it would run without the level's instructions.
mod sse2_ops {
    use std::arch::x86_64::*;

    /// Two lanes of `x`, `y`, `z` as rows: `x0 y0 z0 x1 y1 z1` ([`Real::write_rows`]).
    ///
    /// # Safety
    ///
    /// `out` is valid for writes of 6 values.
    #[inline(always)]
    pub(super) unsafe fn rows3(x: __m128d, y: __m128d, z: __m128d, out: *mut f64) {
        _mm_storeu_pd(out, _mm_unpacklo_pd(x, y));
        _mm_storeu_pd(out.add(2), _mm_shuffle_pd::<0b10>(z, x));
        _mm_storeu_pd(out.add(4), _mm_unpackhi_pd(y, z));
    }

    /// Two rows `x0 y0 z0 x1 y1 z1` as lanes of `x`, `y`, `z` ([`Real::read_rows`]).
    ///
    /// # Safety
    ///
    /// `rows` is valid for reads of 6 values.
    #[inline(always)]
    pub(super) unsafe fn cols3(rows: *const f64) -> (__m128d, __m128d, __m128d) {
        let (r0, r1, r2) = (
            _mm_loadu_pd(rows),
            _mm_loadu_pd(rows.add(2)),
            _mm_loadu_pd(rows.add(4)),
        );
        (
            _mm_shuffle_pd::<0b10>(r0, r1),
            _mm_shuffle_pd::<0b01>(r0, r2),
            _mm_shuffle_pd::<0b10>(r1, r2),
        )
    }

    /// SSE2 has no fused multiply-add: libm's `fma` per lane, correctly rounded as the
    /// instruction is (glibc runs the instruction where the processor has it).
    #[inline(always)]
    pub(super) unsafe fn fma(a: __m128d, b: __m128d, c: __m128d) -> __m128d {
        let (mut x, mut y, mut z) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        _mm_storeu_pd(x.as_mut_ptr(), a);
        _mm_storeu_pd(y.as_mut_ptr(), b);
        _mm_storeu_pd(z.as_mut_ptr(), c);
        _mm_set_pd(x[1].mul_add(y[1], z[1]), x[0].mul_add(y[0], z[0]))
    }

    #[inline(always)]
    pub(super) unsafe fn split(x: __m128d) -> (__m128d, __m128d) {
        let bits = _mm_castpd_si128(x);
        let biased = _mm_castsi128_pd(_mm_or_si128(
            _mm_set1_epi64x(0x4330_0000_0000_0000u64 as i64),
            _mm_srli_epi64::<52>(bits),
        ));
        let e = _mm_sub_pd(biased, _mm_set1_pd(4_503_599_627_371_519.0));
        let m = _mm_castsi128_pd(_mm_or_si128(
            _mm_and_si128(bits, _mm_set1_epi64x(0x000F_FFFF_FFFF_FFFF)),
            _mm_set1_epi64x(0x3FF0_0000_0000_0000),
        ));
        (e, m)
    }

    #[inline(always)]
    pub(super) unsafe fn scale2(a: __m128d, k: __m128d) -> __m128d {
        let two_k = _mm_castsi128_pd(_mm_slli_epi64::<52>(_mm_castpd_si128(_mm_add_pd(
            k,
            _mm_set1_pd(4_503_599_627_371_519.0),
        ))));
        _mm_mul_pd(a, two_k)
    }

    #[inline(always)]
    pub(super) unsafe fn lookup16(x: __m128d, table: &[f64; 16]) -> __m128d {
        let bits = _mm_castpd_si128(x);
        let i0 = (_mm_cvtsi128_si64(bits) & 15) as usize;
        let i1 = (_mm_cvtsi128_si64(_mm_unpackhi_epi64(bits, bits)) & 15) as usize;
        _mm_set_pd(table[i1], table[i0])
    }

    #[inline(always)]
    pub(super) unsafe fn add_shl48(a: __m128d, n: __m128d) -> __m128d {
        _mm_castsi128_pd(_mm_add_epi64(
            _mm_castpd_si128(a),
            _mm_slli_epi64::<48>(_mm_castpd_si128(n)),
        ))
    }
}

/// AVX2's logB/significand and scaleB, as functions: a closure this large is not always
/// inlined, and out of line it would run without the level's instructions.
mod avx2_ops {
    use std::arch::x86_64::*;

    /// Four lanes of `x`, `y`, `z` as rows, `x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3`
    /// ([`Real::write_rows`]): three in-lane shuffles pair the values, a lane permute and a
    /// blend put the pairs in place.
    ///
    /// # Safety
    ///
    /// `out` is valid for writes of 12 values.
    #[inline(always)]
    pub(super) unsafe fn rows3(x: __m256d, y: __m256d, z: __m256d, out: *mut f64) {
        let xy = _mm256_shuffle_pd::<0b0000>(x, y); // x0 y0 x2 y2
        let zx = _mm256_shuffle_pd::<0b1010>(z, x); // z0 x1 z2 x3
        let yz = _mm256_shuffle_pd::<0b1111>(y, z); // y1 z1 y3 z3
        _mm256_storeu_pd(out, _mm256_permute2f128_pd::<0x20>(xy, zx));
        _mm256_storeu_pd(out.add(4), _mm256_blend_pd::<0b1100>(yz, xy));
        _mm256_storeu_pd(out.add(8), _mm256_permute2f128_pd::<0x31>(zx, yz));
    }

    /// Four rows `x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3` as lanes of `x`, `y`, `z`
    /// ([`Real::read_rows`]): [`rows3`]'s steps undone, a blend and a lane permute pairing the
    /// values, three in-lane shuffles parting them.
    ///
    /// # Safety
    ///
    /// `rows` is valid for reads of 12 values.
    #[inline(always)]
    pub(super) unsafe fn cols3(rows: *const f64) -> (__m256d, __m256d, __m256d) {
        let (r0, r1, r2) = (
            _mm256_loadu_pd(rows),
            _mm256_loadu_pd(rows.add(4)),
            _mm256_loadu_pd(rows.add(8)),
        );
        let xy = _mm256_blend_pd::<0b1100>(r0, r1); // x0 y0 x2 y2
        let zx = _mm256_permute2f128_pd::<0x21>(r0, r2); // z0 x1 z2 x3
        let yz = _mm256_blend_pd::<0b1100>(r1, r2); // y1 z1 y3 z3
        (
            _mm256_shuffle_pd::<0b1010>(xy, zx),
            _mm256_shuffle_pd::<0b0101>(xy, yz),
            _mm256_shuffle_pd::<0b1010>(zx, yz),
        )
    }

    #[inline(always)]
    pub(super) unsafe fn split(x: __m256d) -> (__m256d, __m256d) {
        let bits = _mm256_castpd_si256(x);
        let biased = _mm256_castsi256_pd(_mm256_or_si256(
            _mm256_set1_epi64x(0x4330_0000_0000_0000u64 as i64),
            _mm256_srli_epi64::<52>(bits),
        ));
        let e = _mm256_sub_pd(biased, _mm256_set1_pd(4_503_599_627_371_519.0));
        let m = _mm256_castsi256_pd(_mm256_or_si256(
            _mm256_and_si256(bits, _mm256_set1_epi64x(0x000F_FFFF_FFFF_FFFF)),
            _mm256_set1_epi64x(0x3FF0_0000_0000_0000),
        ));
        (e, m)
    }

    #[inline(always)]
    pub(super) unsafe fn scale2(a: __m256d, k: __m256d) -> __m256d {
        let two_k = _mm256_castsi256_pd(_mm256_slli_epi64::<52>(_mm256_castpd_si256(
            _mm256_add_pd(k, _mm256_set1_pd(4_503_599_627_371_519.0)),
        )));
        _mm256_mul_pd(a, two_k)
    }

    #[inline(always)]
    pub(super) unsafe fn lookup16(x: __m256d, table: &[f64; 16]) -> __m256d {
        let i = _mm256_and_si256(_mm256_castpd_si256(x), _mm256_set1_epi64x(15));
        _mm256_i64gather_pd::<8>(table.as_ptr(), i)
    }

    #[inline(always)]
    pub(super) unsafe fn add_shl48(a: __m256d, n: __m256d) -> __m256d {
        _mm256_castsi256_pd(_mm256_add_epi64(
            _mm256_castpd_si256(a),
            _mm256_slli_epi64::<48>(_mm256_castpd_si256(n)),
        ))
    }
}

/// AVX-512's own exact instructions for IEEE 754 logB and the significand (getexp, getmant)
/// and scaleB (scalef): where the other levels' bit manipulations are defined (positive normal
/// inputs, normal results) they give the same values.
mod avx512_ops {
    use std::arch::x86_64::*;

    /// Eight lanes of `x`, `y`, `z` as rows, `x0 y0 z0 x1 y1 z1 x2 y2 | z2 x3 ... | ... y7 z7`
    /// ([`Real::write_rows`]): each register of rows takes its `x` and `y` from one two-source
    /// permute and its `z` from a masked permute.
    ///
    /// # Safety
    ///
    /// `out` is valid for writes of 24 values.
    #[inline(always)]
    pub(super) unsafe fn rows3(x: __m512d, y: __m512d, z: __m512d, out: *mut f64) {
        // indices 0..8 pick from `x`, 8..16 from `y`; the lanes that take `z` are masked off
        let xy0 = _mm512_permutex2var_pd(x, _mm512_setr_epi64(0, 8, 0, 1, 9, 0, 2, 10), y);
        let xy1 = _mm512_permutex2var_pd(x, _mm512_setr_epi64(0, 3, 11, 0, 4, 12, 0, 5), y);
        let xy2 = _mm512_permutex2var_pd(x, _mm512_setr_epi64(13, 0, 6, 14, 0, 7, 15, 0), y);
        // z0 z1 into lanes 2 and 5; z2 z3 z4 into 0, 3 and 6; z5 z6 z7 into 1, 4 and 7
        let z0 = _mm512_setr_epi64(0, 0, 0, 0, 0, 1, 0, 0);
        let z1 = _mm512_setr_epi64(2, 0, 0, 3, 0, 0, 4, 0);
        let z2 = _mm512_setr_epi64(0, 5, 0, 0, 6, 0, 0, 7);
        let r0 = _mm512_mask_permutexvar_pd(xy0, 0b0010_0100, z0, z);
        let r1 = _mm512_mask_permutexvar_pd(xy1, 0b0100_1001, z1, z);
        let r2 = _mm512_mask_permutexvar_pd(xy2, 0b1001_0010, z2, z);
        _mm512_storeu_pd(out, r0);
        _mm512_storeu_pd(out.add(8), r1);
        _mm512_storeu_pd(out.add(16), r2);
    }

    /// Eight rows `x0 y0 z0 x1 y1 z1 x2 y2 | z2 x3 ... | ... y7 z7` as lanes of `x`, `y`, `z`
    /// ([`Real::read_rows`]): each takes its first lanes from the first two registers of rows
    /// by a two-source permute, its last from the third by a masked permute.
    ///
    /// # Safety
    ///
    /// `rows` is valid for reads of 24 values.
    #[inline(always)]
    pub(super) unsafe fn cols3(rows: *const f64) -> (__m512d, __m512d, __m512d) {
        let (r0, r1, r2) = (
            _mm512_loadu_pd(rows),
            _mm512_loadu_pd(rows.add(8)),
            _mm512_loadu_pd(rows.add(16)),
        );
        // indices 0..8 pick from `r0`, 8..16 from `r1`; the lanes masked in below from `r2`
        let x = _mm512_permutex2var_pd(r0, _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), r1);
        let y = _mm512_permutex2var_pd(r0, _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), r1);
        let z = _mm512_permutex2var_pd(r0, _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), r1);
        let x = _mm512_mask_permutexvar_pd(
            x,
            0b1100_0000,
            _mm512_setr_epi64(0, 0, 0, 0, 0, 0, 2, 5),
            r2,
        );
        let y = _mm512_mask_permutexvar_pd(
            y,
            0b1110_0000,
            _mm512_setr_epi64(0, 0, 0, 0, 0, 0, 3, 6),
            r2,
        );
        let z = _mm512_mask_permutexvar_pd(
            z,
            0b1110_0000,
            _mm512_setr_epi64(0, 0, 0, 0, 0, 1, 4, 7),
            r2,
        );
        (x, y, z)
    }

    #[inline(always)]
    pub(super) unsafe fn split(x: __m512d) -> (__m512d, __m512d) {
        (
            _mm512_getexp_pd(x),
            _mm512_getmant_pd::<_MM_MANT_NORM_1_2, _MM_MANT_SIGN_SRC>(x),
        )
    }

    #[inline(always)]
    pub(super) unsafe fn scale2(a: __m512d, k: __m512d) -> __m512d {
        _mm512_scalef_pd(a, k)
    }

    /// The table in two registers, indexed by the low four bits of each lane (vpermt2pd).
    #[inline(always)]
    pub(super) unsafe fn lookup16(x: __m512d, table: &[f64; 16]) -> __m512d {
        _mm512_permutex2var_pd(
            _mm512_loadu_pd(table.as_ptr()),
            _mm512_castpd_si512(x),
            _mm512_loadu_pd(table.as_ptr().add(8)),
        )
    }

    #[inline(always)]
    pub(super) unsafe fn add_shl48(a: __m512d, n: __m512d) -> __m512d {
        _mm512_castsi512_pd(_mm512_add_epi64(
            _mm512_castpd_si512(a),
            _mm512_slli_epi64::<48>(_mm512_castpd_si512(n)),
        ))
    }
}
