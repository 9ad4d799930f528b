//! Lanes: the number type every plant, law, integrator and metric is written over.
//!
//! A block of cases runs in lockstep as struct-of-arrays: each real quantity of the model is a
//! [`Lanes<W>`], one `f64` per case, and each arithmetic operation acts on all lanes at once
//! (a vertical SIMD operation once the kernel is compiled for the CPU, see [`crate::kernel`]).
//! `f64` is the width-1 instance, the scalar path; both implement [`Real`] with the same IEEE
//! operation per lane, so a case gives the same bits whatever its lane, its block's width or
//! the instruction set the kernel was compiled for.
//!
//! Branches on data become masks: a comparison gives a [`Real::Mask`] and
//! [`Real::select`] picks per lane. The transcendental functions ([`math`]) are branch-free
//! polynomials built from the same primitive operations, never libm, so they too give the same
//! bits at every width and instruction-set level.
//!
//! A fused multiply-add is written out where one is meant ([`Real::mul_add`]: the polynomials
//! of the transcendentals, the integrators' updates): it is one instruction at the AVX2 and
//! AVX-512 levels and libm's correctly rounded `fma` per lane at the baseline level, which has
//! no such instruction, so a fused `a * b + c` gives the same bits everywhere. Rust never
//! contracts a written `a * b + c` on its own, so every other one is rounded twice at every
//! level.

pub mod axes;
mod exp_log;
pub mod gather;
pub mod math;
pub mod slots;
mod trig;
#[cfg(target_arch = "x86_64")]
pub mod x86;

pub use gather::Gather;

use std::fmt;
use std::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use nalgebra::{SMatrix, SVector};

/// 2^52 + 2^51: adding it to |x| < 2^51 rounds x to an integer (ties to even) in the low
/// mantissa bits, with plain IEEE additions at every instruction-set level.
pub(crate) const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// A per-lane boolean: `bool` for `f64`, a bit mask per lane for [`Lanes`].
pub trait Mask:
    Copy
    + Send
    + Sync
    + fmt::Debug
    + 'static
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitXor<Output = Self>
    + Not<Output = Self>
{
    const LANES: usize;
    fn splat(value: bool) -> Self;
    fn from_fn(f: impl FnMut(usize) -> bool) -> Self;
    fn lane(&self, i: usize) -> bool;
    /// Whether any lane is set.
    fn any(self) -> bool;
    /// Whether every lane is set.
    fn all(self) -> bool;
}

/// A real number per lane of a block of cases.
///
/// The physics is written once over this trait; `f64` (one case) and [`Lanes<W>`] (W cases)
/// implement it. Every method acts lane by lane.
pub trait Real:
    Copy
    + Send
    + Sync
    + fmt::Debug
    + PartialEq
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + num_traits::Zero
    + num_traits::One
{
    type Mask: Mask;
    /// Number of cases the value holds.
    const LANES: usize;

    fn splat(value: f64) -> Self;
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;
    fn lane(&self, i: usize) -> f64;
    fn set_lane(&mut self, i: usize, value: f64);
    /// Lanes `0..used` of the `D` values `v` written out as rows of `D` values each,
    /// `out[i D + c] = v[c].lane(i)`: the layout of a law's `(n, D)` arrays. A level may
    /// interleave whole registers with shuffles (the lanes' bits are copied, never computed).
    #[inline(always)]
    fn write_rows<const D: usize>(v: &[Self; D], out: &mut [f64], used: usize) {
        write_rows_by_lane(v, out, used);
    }
    /// The inverse of [`Real::write_rows`]: `v[c].lane(i) = rows[i D + c]` for the first
    /// `used` lanes (at least one), the lanes beyond repeating lane `used - 1` (a block's last
    /// case). A level may read whole registers and shuffle them (the bits are copied, never
    /// computed).
    #[inline(always)]
    fn read_rows<const D: usize>(rows: &[f64], used: usize) -> [Self; D] {
        read_rows_by_lane(rows, used)
    }

    fn abs(self) -> Self;
    fn sqrt(self) -> Self;
    /// `self * a + b` rounded once (IEEE 754's fusedMultiplyAdd): one instruction at the AVX2
    /// and AVX-512 levels, libm's `fma` per lane at the baseline level (exact there too, so
    /// every level gives the same bits).
    fn mul_add(self, a: Self, b: Self) -> Self;
    /// `self` if `self < other`, else `other` (so a NaN `self` gives `other`).
    fn min(self, other: Self) -> Self;
    /// `self` if `self > other`, else `other` (so a NaN `self` gives `other`).
    fn max(self, other: Self) -> Self;
    /// The magnitude of `self` with the sign bit of `sign`.
    fn copysign(self, sign: Self) -> Self;

    fn simd_lt(self, other: Self) -> Self::Mask;
    fn simd_le(self, other: Self) -> Self::Mask;
    fn simd_gt(self, other: Self) -> Self::Mask;
    fn simd_ge(self, other: Self) -> Self::Mask;
    fn simd_eq(self, other: Self) -> Self::Mask;
    /// `a` where the mask is set, `b` elsewhere.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    fn is_finite(self) -> Self::Mask;

    /// The nearest integer (ties to even) for |x| < 2^51 (the transcendentals' reductions).
    fn round_small(self) -> Self;
    /// `2^k` for an integral `k` in [-1022, 1023] (exact, from the exponent bits).
    fn pow2i(self) -> Self;
    /// `(e, m)` with `x = 2^e m`, `1 <= m < 2`, for a positive normal `x` (IEEE 754's logB
    /// and the significand; other inputs give unspecified values).
    fn split_exponent(self) -> (Self, Self);
    /// `table[i]` in each lane, with `i` the low four bits of the lane's bit pattern: where
    /// `x + ROUNDER` keeps the integer that x rounds to (two's complement, so `i = n mod 16`).
    /// A copy of a table entry, so the same bits at every level (the reductions of the
    /// table-driven `exp`).
    fn lookup16(self, table: &[f64; 16]) -> Self;
    /// The lane whose bit pattern is `bits(self) + (bits(n) << 48)` (wrapping): for `n` as
    /// `x + ROUNDER` leaves an integer, adds `(n mod 2^16) 2^48` to `self`'s bits, which moves
    /// `n / 16` into the exponent field (the scaling of the table-driven `exp`).
    fn add_shl48(self, n: Self) -> Self;

    /// `self 2^k` for an integral `k` with the result normal (IEEE 754's scaleB, exact there).
    #[inline(always)]
    fn scale2(self, k: Self) -> Self {
        self * k.pow2i()
    }

    // -- derived operations, written once on top of the primitives --------------------------

    /// `lo` below `lo`, `hi` above `hi`, `self` between; a NaN stays NaN (so a non-finite
    /// command is still seen as one after saturation).
    #[inline(always)]
    fn clamp(self, lo: Self, hi: Self) -> Self {
        Self::select(
            self.simd_lt(lo),
            lo,
            Self::select(self.simd_gt(hi), hi, self),
        )
    }

    /// `sgn(x)` with `sgn(0) = 0` (and 0 for NaN).
    #[inline(always)]
    fn signum0(self) -> Self {
        let one = Self::splat(1.0);
        let zero = Self::zero();
        Self::select(
            self.simd_gt(zero),
            one,
            Self::select(self.simd_lt(zero), -one, zero),
        )
    }

    #[inline(always)]
    fn exp(self) -> Self {
        math::exp(self)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        math::ln(self)
    }
    /// `self^y` for `self > 0` (`0^y = 0` for y > 0).
    #[inline(always)]
    fn powf(self, y: Self) -> Self {
        math::pow(self, y)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        math::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        math::cos(self)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        math::sin_cos(self)
    }
    #[inline(always)]
    fn tanh(self) -> Self {
        math::tanh(self)
    }
    /// `atan2(self, x)`: the angle of (x, self).
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        math::atan2(self, x)
    }
}

impl Mask for bool {
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(value: bool) -> Self {
        value
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(&self, _i: usize) -> bool {
        *self
    }
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
    #[inline(always)]
    fn all(self) -> bool {
        self
    }
}

impl Real for f64 {
    type Mask = bool;
    const LANES: usize = 1;

    #[inline(always)]
    fn splat(value: f64) -> Self {
        value
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        f(0)
    }
    #[inline(always)]
    fn lane(&self, _i: usize) -> f64 {
        *self
    }
    #[inline(always)]
    fn set_lane(&mut self, _i: usize, value: f64) {
        *self = value;
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::from_bits(self.to_bits() & !SIGN_BIT)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        f64::mul_add(self, a, b)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        if self < other { self } else { other }
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        if self > other { self } else { other }
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        f64::from_bits((self.to_bits() & !SIGN_BIT) | (sign.to_bits() & SIGN_BIT))
    }
    #[inline(always)]
    fn simd_lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn simd_le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn simd_gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn simd_ge(self, other: Self) -> bool {
        self >= other
    }
    #[inline(always)]
    fn simd_eq(self, other: Self) -> bool {
        self == other
    }
    #[inline(always)]
    fn select(mask: bool, a: Self, b: Self) -> Self {
        if mask { a } else { b }
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        // exponent bits not all ones
        (self.to_bits() & EXPONENT_BITS) != EXPONENT_BITS
    }
    #[inline(always)]
    fn round_small(self) -> Self {
        (self + ROUNDER) - ROUNDER
    }
    #[inline(always)]
    fn pow2i(self) -> Self {
        // k + 2^52 + 1023 holds k + 1023 in its low mantissa bits; shift them into the exponent
        f64::from_bits((self + 4_503_599_627_371_519.0).to_bits() << 52)
    }
    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let bits = self.to_bits();
        let biased = f64::from_bits(0x4330_0000_0000_0000 | (bits >> 52));
        let e = biased - 4_503_599_627_371_519.0;
        let m = f64::from_bits((bits & MANTISSA_BITS) | ONE_BITS);
        (e, m)
    }
    #[inline(always)]
    fn lookup16(self, table: &[f64; 16]) -> Self {
        table[(self.to_bits() & 15) as usize]
    }
    #[inline(always)]
    fn add_shl48(self, n: Self) -> Self {
        f64::from_bits(self.to_bits().wrapping_add(n.to_bits() << 48))
    }
}

const SIGN_BIT: u64 = 0x8000_0000_0000_0000;
const EXPONENT_BITS: u64 = 0x7FF0_0000_0000_0000;
const MANTISSA_BITS: u64 = 0x000F_FFFF_FFFF_FFFF;
const ONE_BITS: u64 = 0x3FF0_0000_0000_0000;

/// W cases of a block, one `f64` each.
///
/// Every operation is a loop over the lanes with the same scalar IEEE operation as `f64`'s
/// (each `Real` method maps the `f64` one), which the compiler turns into vertical SIMD
/// instructions of the width the kernel was compiled for.
#[derive(Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Lanes<const W: usize>(pub [f64; W]);

/// The mask of [`Lanes`]: all ones (set) or all zeros per lane, as wide as a lane, so that a
/// select is three bitwise operations.
#[derive(Clone, Copy, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct LaneMask<const W: usize>(pub [u64; W]);

impl<const W: usize> fmt::Debug for Lanes<W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.0.iter()).finish()
    }
}

impl<const W: usize> fmt::Debug for LaneMask<W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list()
            .entries(self.0.iter().map(|&m| m != 0))
            .finish()
    }
}

#[inline(always)]
fn map<const W: usize>(a: [f64; W], f: impl Fn(f64) -> f64) -> [f64; W] {
    let mut out = [0.0; W];
    for i in 0..W {
        out[i] = f(a[i]);
    }
    out
}

#[inline(always)]
fn zip<const W: usize>(a: [f64; W], b: [f64; W], f: impl Fn(f64, f64) -> f64) -> [f64; W] {
    let mut out = [0.0; W];
    for i in 0..W {
        out[i] = f(a[i], b[i]);
    }
    out
}

#[inline(always)]
fn compare<const W: usize>(a: [f64; W], b: [f64; W], f: impl Fn(f64, f64) -> bool) -> LaneMask<W> {
    let mut out = [0u64; W];
    for i in 0..W {
        out[i] = if f(a[i], b[i]) { u64::MAX } else { 0 };
    }
    LaneMask(out)
}

impl<const W: usize> Mask for LaneMask<W> {
    const LANES: usize = W;
    #[inline(always)]
    fn splat(value: bool) -> Self {
        Self([if value { u64::MAX } else { 0 }; W])
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        let mut out = [0u64; W];
        for (i, o) in out.iter_mut().enumerate() {
            *o = if f(i) { u64::MAX } else { 0 };
        }
        Self(out)
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> bool {
        self.0[i] != 0
    }
    #[inline(always)]
    fn any(self) -> bool {
        let mut acc = 0u64;
        for m in self.0 {
            acc |= m;
        }
        acc != 0
    }
    #[inline(always)]
    fn all(self) -> bool {
        let mut acc = u64::MAX;
        for m in self.0 {
            acc &= m;
        }
        acc != 0
    }
}

macro_rules! mask_binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const W: usize> $tr for LaneMask<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                let mut out = [0u64; W];
                for i in 0..W {
                    out[i] = self.0[i] $op rhs.0[i];
                }
                Self(out)
            }
        }
    };
}
mask_binop!(BitAnd, bitand, &);
mask_binop!(BitOr, bitor, |);
mask_binop!(BitXor, bitxor, ^);

impl<const W: usize> Not for LaneMask<W> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let mut out = self.0;
        for m in &mut out {
            *m = !*m;
        }
        Self(out)
    }
}

macro_rules! lanes_binop {
    ($tr:ident, $f:ident, $atr:ident, $af:ident, $op:tt) => {
        impl<const W: usize> $tr for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                Self(zip(self.0, rhs.0, |a, b| a $op b))
            }
        }
        impl<const W: usize> $tr<f64> for Lanes<W> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: f64) -> Self {
                Self(map(self.0, |a| a $op rhs))
            }
        }
        impl<const W: usize> $atr for Lanes<W> {
            #[inline(always)]
            fn $af(&mut self, rhs: Self) {
                *self = *self $op rhs;
            }
        }
    };
}
lanes_binop!(Add, add, AddAssign, add_assign, +);
lanes_binop!(Sub, sub, SubAssign, sub_assign, -);
lanes_binop!(Mul, mul, MulAssign, mul_assign, *);
lanes_binop!(Div, div, DivAssign, div_assign, /);

impl<const W: usize> Neg for Lanes<W> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self(map(self.0, |a| -a))
    }
}

impl<const W: usize> num_traits::Zero for Lanes<W> {
    #[inline(always)]
    fn zero() -> Self {
        Self([0.0; W])
    }
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.0.iter().all(|&v| v == 0.0)
    }
}

impl<const W: usize> num_traits::One for Lanes<W> {
    #[inline(always)]
    fn one() -> Self {
        Self([1.0; W])
    }
}

impl<const W: usize> Real for Lanes<W> {
    type Mask = LaneMask<W>;
    const LANES: usize = W;

    #[inline(always)]
    fn splat(value: f64) -> Self {
        Self([value; W])
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        let mut out = [0.0; W];
        for (i, o) in out.iter_mut().enumerate() {
            *o = f(i);
        }
        Self(out)
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> f64 {
        self.0[i]
    }
    #[inline(always)]
    fn set_lane(&mut self, i: usize, value: f64) {
        self.0[i] = value;
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Self(map(self.0, <f64 as Real>::abs))
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Self(map(self.0, f64::sqrt))
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        let mut out = self.0;
        for ((o, a), b) in out.iter_mut().zip(a.0).zip(b.0) {
            *o = o.mul_add(a, b);
        }
        Self(out)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Self(zip(self.0, other.0, <f64 as Real>::min))
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Self(zip(self.0, other.0, <f64 as Real>::max))
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        Self(zip(self.0, sign.0, <f64 as Real>::copysign))
    }
    #[inline(always)]
    fn simd_lt(self, other: Self) -> LaneMask<W> {
        compare(self.0, other.0, |a, b| a < b)
    }
    #[inline(always)]
    fn simd_le(self, other: Self) -> LaneMask<W> {
        compare(self.0, other.0, |a, b| a <= b)
    }
    #[inline(always)]
    fn simd_gt(self, other: Self) -> LaneMask<W> {
        compare(self.0, other.0, |a, b| a > b)
    }
    #[inline(always)]
    fn simd_ge(self, other: Self) -> LaneMask<W> {
        compare(self.0, other.0, |a, b| a >= b)
    }
    #[inline(always)]
    fn simd_eq(self, other: Self) -> LaneMask<W> {
        compare(self.0, other.0, |a, b| a == b)
    }
    #[inline(always)]
    fn select(mask: LaneMask<W>, a: Self, b: Self) -> Self {
        let mut out = [0.0; W];
        for (o, (m, (a, b))) in out
            .iter_mut()
            .zip(mask.0.into_iter().zip(a.0.into_iter().zip(b.0)))
        {
            *o = f64::from_bits((a.to_bits() & m) | (b.to_bits() & !m));
        }
        Self(out)
    }
    #[inline(always)]
    fn is_finite(self) -> LaneMask<W> {
        let mut out = [0u64; W];
        for (o, v) in out.iter_mut().zip(self.0) {
            *o = if (v.to_bits() & EXPONENT_BITS) != EXPONENT_BITS {
                u64::MAX
            } else {
                0
            };
        }
        LaneMask(out)
    }
    #[inline(always)]
    fn round_small(self) -> Self {
        Self(map(self.0, <f64 as Real>::round_small))
    }
    #[inline(always)]
    fn pow2i(self) -> Self {
        Self(map(self.0, <f64 as Real>::pow2i))
    }
    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let mut e = [0.0; W];
        let mut m = [0.0; W];
        for i in 0..W {
            (e[i], m[i]) = <f64 as Real>::split_exponent(self.0[i]);
        }
        (Self(e), Self(m))
    }
    #[inline(always)]
    fn lookup16(self, table: &[f64; 16]) -> Self {
        Self(map(self.0, |x| x.lookup16(table)))
    }
    #[inline(always)]
    fn add_shl48(self, n: Self) -> Self {
        Self(zip(self.0, n.0, <f64 as Real>::add_shl48))
    }
}

/// `sum_i a_i b_i`, summed from the first component on (a fixed order: the same bits on every
/// path).
#[inline(always)]
pub fn dot<R: Real, const N: usize>(a: &SVector<R, N>, b: &SVector<R, N>) -> R {
    let mut acc = a[0] * b[0];
    for i in 1..N {
        acc += a[i] * b[i];
    }
    acc
}

/// Euclidean norm, `sqrt(dot(v, v))`.
#[inline(always)]
pub fn norm<R: Real, const N: usize>(v: &SVector<R, N>) -> R {
    dot(v, v).sqrt()
}

/// Sum of the components, from the first on.
#[inline(always)]
pub fn sum<R: Real, const N: usize>(v: &SVector<R, N>) -> R {
    let mut acc = v[0];
    for i in 1..N {
        acc += v[i];
    }
    acc
}

/// The vector `(f(0), ..., f(N - 1))`: an `SVector::from_fn` that is sure to be inlined. The
/// hot loop must inline everything it calls, so that all of it is compiled with the kernel's
/// instruction set; a call left out of line would run at the baseline level.
#[inline(always)]
pub fn vector<R: Real, const N: usize>(mut f: impl FnMut(usize) -> R) -> SVector<R, N> {
    let mut a = [R::zero(); N];
    for (i, v) in a.iter_mut().enumerate() {
        *v = f(i);
    }
    SVector::from(a)
}

/// `v * c` for a plain number `c` (the same operation in every lane).
#[inline(always)]
pub fn scale<R: Real, const N: usize>(v: &SVector<R, N>, c: f64) -> SVector<R, N> {
    let mut out = *v;
    for i in 0..N {
        out[i] = v[i] * c;
    }
    out
}

/// `a + b`, `a - b`, `-a`, `a_i b_i`, `a_i / b_i` and `v r` for vectors of lanes: nalgebra's
/// operators are not always inlined into the kernel (they call the lane operations, which
/// need the kernel's target features), and a call left out of line runs at the baseline level.
/// The hot code uses these instead.
#[inline(always)]
pub fn add<R: Real, const N: usize>(a: &SVector<R, N>, b: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *a;
    for i in 0..N {
        out[i] = a[i] + b[i];
    }
    out
}

#[inline(always)]
pub fn sub<R: Real, const N: usize>(a: &SVector<R, N>, b: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *a;
    for i in 0..N {
        out[i] = a[i] - b[i];
    }
    out
}

#[inline(always)]
pub fn neg<R: Real, const N: usize>(a: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *a;
    for i in 0..N {
        out[i] = -a[i];
    }
    out
}

#[inline(always)]
pub fn mul<R: Real, const N: usize>(a: &SVector<R, N>, b: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *a;
    for i in 0..N {
        out[i] = a[i] * b[i];
    }
    out
}

#[inline(always)]
pub fn div<R: Real, const N: usize>(a: &SVector<R, N>, b: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *a;
    for i in 0..N {
        out[i] = a[i] / b[i];
    }
    out
}

#[inline(always)]
pub fn scale_by<R: Real, const N: usize>(v: &SVector<R, N>, r: R) -> SVector<R, N> {
    let mut out = *v;
    for i in 0..N {
        out[i] = v[i] * r;
    }
    out
}

/// `|v_i|` per component.
#[inline(always)]
pub fn abs<R: Real, const N: usize>(v: &SVector<R, N>) -> SVector<R, N> {
    let mut out = *v;
    for i in 0..N {
        out[i] = v[i].abs();
    }
    out
}

/// A vector with every component equal to `value` in every lane.
#[inline(always)]
pub fn splat_vector<R: Real, const N: usize>(value: f64) -> SVector<R, N> {
    filled(R::splat(value))
}

/// A matrix with every entry `value`. Use this, not nalgebra's `from_element` or `zeros`:
/// those are not always inlined, and a lane type's copy out of line runs without the kernel's
/// instruction set (it took 10 % of W3 before this helper).
#[inline(always)]
pub fn filled<R: Real, const M: usize, const N: usize>(value: R) -> SMatrix<R, M, N> {
    SMatrix::from_array_storage(nalgebra::ArrayStorage([[value; M]; N]))
}

/// A matrix of zeros ([`filled`] with 0).
#[inline(always)]
pub fn zeros<R: Real, const M: usize, const N: usize>() -> SMatrix<R, M, N> {
    filled(R::zero())
}

/// Lane-wise select of two vectors.
#[inline(always)]
pub fn select_vector<R: Real, const N: usize>(
    mask: R::Mask,
    a: &SVector<R, N>,
    b: &SVector<R, N>,
) -> SVector<R, N> {
    let mut out = *b;
    for i in 0..N {
        out[i] = R::select(mask, a[i], b[i]);
    }
    out
}

/// Whether every component is finite, per lane.
#[inline(always)]
pub fn all_finite<R: Real, const N: usize>(v: &SVector<R, N>) -> R::Mask {
    let mut m = v[0].is_finite();
    for i in 1..N {
        m = m & v[i].is_finite();
    }
    m
}

/// [`Real::write_rows`] one value at a time.
#[inline(always)]
pub fn write_rows_by_lane<R: Real, const D: usize>(v: &[R; D], out: &mut [f64], used: usize) {
    for (i, row) in out.chunks_exact_mut(D).take(used).enumerate() {
        for (value, lanes) in row.iter_mut().zip(v) {
            *value = lanes.lane(i);
        }
    }
}

/// [`Real::read_rows`] one value at a time. (Loops, not `std::array::from_fn`, whose closure
/// is not always inlined into a kernel compiled for an instruction set.)
#[inline(always)]
pub fn read_rows_by_lane<R: Real, const D: usize>(rows: &[f64], used: usize) -> [R; D] {
    let mut v = [R::zero(); D];
    for (c, v) in v.iter_mut().enumerate() {
        *v = column(rows, used, D, c);
    }
    v
}

/// Column `c` of the rows `rows` (`used x width`) as lanes, the lanes beyond `used` (at least
/// one) repeating the last row.
#[inline(always)]
pub fn column<R: Real>(rows: &[f64], used: usize, width: usize, c: usize) -> R {
    assert!(used > 0, "at least one lane is used");
    R::from_fn(|i| rows[i.min(used - 1) * width + c])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primitives_are_exact() {
        for k in [-1022.0, -1.0, 0.0, 1.0, 52.0, 1023.0] {
            assert_eq!(<f64 as Real>::pow2i(k), 2f64.powi(k as i32));
        }
        for x in [1.0, 1.5, 3.0, 1e-300, 7.25e300, std::f64::consts::PI] {
            let (e, m) = <f64 as Real>::split_exponent(x);
            assert!((1.0..2.0).contains(&m), "{x}: {m}");
            assert_eq!(m * 2f64.powi(e as i32), x);
        }
        assert_eq!(<f64 as Real>::round_small(2.5), 2.0);
        assert_eq!(<f64 as Real>::round_small(-3.5), -4.0);
        assert_eq!(<f64 as Real>::round_small(0.49999999999999994), 0.0);
    }

    #[test]
    fn lanes_map_the_scalar_operations() {
        let a = Lanes([1.0, -2.0, f64::NAN, 0.0]);
        let b = Lanes([3.0, -4.0, 1.0, -0.0]);
        assert_eq!((a + b).0[..2], [4.0, -6.0]);
        assert_eq!(a.min(b).0[..2], [1.0, -4.0]);
        assert_eq!(a.min(b).0[2], 1.0, "a NaN self gives the other");
        let m = a.simd_lt(b);
        assert_eq!(
            [m.lane(0), m.lane(1), m.lane(2), m.lane(3)],
            [true, false, false, false]
        );
        let s = Lanes::select(m, a, b);
        assert_eq!(s.0[..2], [1.0, -4.0]);
        assert_eq!(
            Lanes([2.0, -0.0, 0.0, -7.0]).signum0().0,
            [1.0, 0.0, 0.0, -1.0]
        );
        assert!(!Lanes([1.0, f64::INFINITY]).is_finite().all());
        assert!(Lanes([1.0, f64::INFINITY]).is_finite().any());
    }
}
