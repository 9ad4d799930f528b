//! [`Axes`]: the D axes of a law side by side, as one wider lane value.
//!
//! A law's transcendentals form a dependent chain per axis (a logarithm, then powers, then the
//! next surface's logarithm...). Written axis after axis, the processor's reordering window
//! holds only part of one axis's chain, and in narrow blocks each step waits on the one
//! before. `Axes<R, D>` holds the D axes' values in one value whose every operation acts on
//! all of them, so each step of the chain issues D times as many independent instructions.
//! Every operation is the same IEEE operation lane by lane as `R`'s: a case's bits do not
//! change (the fast/general path choices inside `exp` and `ln` give the same bits either way).

use std::fmt;
use std::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, DivAssign, Mul, MulAssign, Neg, Not, Sub, SubAssign,
};

use nalgebra::SVector;

use super::{Mask, Real};

/// The values of D axes, each a lane value `R`.
#[derive(Clone, Copy, PartialEq)]
pub struct Axes<R, const D: usize>(pub [R; D]);

/// The per-lane mask of [`Axes`].
#[derive(Clone, Copy)]
pub struct AxesMask<M, const D: usize>(pub [M; D]);

impl<R: Real, const D: usize> Axes<R, D> {
    /// The components of a vector, side by side.
    #[inline(always)]
    pub fn of(v: &SVector<R, D>) -> Self {
        let mut out = [R::zero(); D];
        for (i, o) in out.iter_mut().enumerate() {
            *o = v[i];
        }
        Self(out)
    }

    /// Back to a vector.
    #[inline(always)]
    pub fn vector(self) -> SVector<R, D> {
        let mut v: SVector<R, D> = super::zeros();
        for i in 0..D {
            v[i] = self.0[i];
        }
        v
    }
}

impl<R: fmt::Debug, const D: usize> fmt::Debug for Axes<R, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.0.iter()).finish()
    }
}

impl<M: fmt::Debug, const D: usize> fmt::Debug for AxesMask<M, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.0.iter()).finish()
    }
}

impl<M: Mask, const D: usize> Mask for AxesMask<M, D> {
    const LANES: usize = M::LANES * D;
    #[inline(always)]
    fn splat(value: bool) -> Self {
        Self([M::splat(value); D])
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> bool) -> Self {
        let mut out = [M::splat(false); D];
        for (a, o) in out.iter_mut().enumerate() {
            *o = M::from_fn(|i| f(a * M::LANES + i));
        }
        Self(out)
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> bool {
        self.0[i / M::LANES].lane(i % M::LANES)
    }
    #[inline(always)]
    fn any(self) -> bool {
        let mut acc = self.0[0];
        for m in &self.0[1..] {
            acc = acc | *m;
        }
        acc.any()
    }
    #[inline(always)]
    fn all(self) -> bool {
        let mut acc = self.0[0];
        for m in &self.0[1..] {
            acc = acc & *m;
        }
        acc.all()
    }
}

macro_rules! mask_binop {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<M: Mask, const D: usize> $tr for AxesMask<M, D> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                let mut out = self.0;
                for i in 0..D {
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

impl<M: Mask, const D: usize> Not for AxesMask<M, D> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        let mut out = self.0;
        for o in out.iter_mut() {
            *o = !*o;
        }
        Self(out)
    }
}

/// Each method of `Axes` applies `R`'s to every axis in a plain loop: no closures, which are
/// not always inlined and out of line would run without the kernel's instruction set (seen at
/// AVX2: a closure per lookup made W1 ten times slower).
macro_rules! each {
    ($self:ident . $m:ident ( $($arg:expr),* )) => {{
        let mut out = $self.0;
        for i in 0..D {
            out[i] = $self.0[i].$m($($arg),*);
        }
        Axes(out)
    }};
}

macro_rules! each2 {
    ($self:ident . $m:ident ( $other:ident )) => {{
        let mut out = $self.0;
        for i in 0..D {
            out[i] = $self.0[i].$m($other.0[i]);
        }
        Axes(out)
    }};
}

macro_rules! each_mask {
    ($self:ident . $m:ident ( $other:ident )) => {{
        let mut out = [R::Mask::splat(false); D];
        for i in 0..D {
            out[i] = $self.0[i].$m($other.0[i]);
        }
        AxesMask(out)
    }};
}

macro_rules! binop {
    ($tr:ident, $f:ident, $atr:ident, $af:ident, $op:tt) => {
        impl<R: Real, const D: usize> $tr for Axes<R, D> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                let mut out = self.0;
                for i in 0..D {
                    out[i] = self.0[i] $op rhs.0[i];
                }
                Self(out)
            }
        }
        impl<R: Real, const D: usize> $tr<f64> for Axes<R, D> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: f64) -> Self {
                let mut out = self.0;
                for i in 0..D {
                    out[i] = self.0[i] $op rhs;
                }
                Self(out)
            }
        }
        impl<R: Real, const D: usize> $atr for Axes<R, D> {
            #[inline(always)]
            fn $af(&mut self, rhs: Self) {
                *self = *self $op rhs;
            }
        }
    };
}
binop!(Add, add, AddAssign, add_assign, +);
binop!(Sub, sub, SubAssign, sub_assign, -);
binop!(Mul, mul, MulAssign, mul_assign, *);
binop!(Div, div, DivAssign, div_assign, /);

impl<R: Real, const D: usize> Neg for Axes<R, D> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        let mut out = self.0;
        for v in &mut out {
            *v = -*v;
        }
        Self(out)
    }
}

impl<R: Real, const D: usize> num_traits::Zero for Axes<R, D> {
    #[inline(always)]
    fn zero() -> Self {
        Self([R::zero(); D])
    }
    fn is_zero(&self) -> bool {
        self.0.iter().all(|a| a.is_zero())
    }
}

impl<R: Real, const D: usize> num_traits::One for Axes<R, D> {
    #[inline(always)]
    fn one() -> Self {
        Self([R::one(); D])
    }
}

impl<R: Real, const D: usize> Real for Axes<R, D> {
    type Mask = AxesMask<R::Mask, D>;
    const LANES: usize = R::LANES * D;

    #[inline(always)]
    fn splat(value: f64) -> Self {
        Self([R::splat(value); D])
    }
    #[inline(always)]
    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        let mut out = [R::zero(); D];
        for (a, o) in out.iter_mut().enumerate() {
            *o = R::from_fn(|i| f(a * R::LANES + i));
        }
        Self(out)
    }
    #[inline(always)]
    fn lane(&self, i: usize) -> f64 {
        self.0[i / R::LANES].lane(i % R::LANES)
    }
    #[inline(always)]
    fn set_lane(&mut self, i: usize, value: f64) {
        self.0[i / R::LANES].set_lane(i % R::LANES, value)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        each!(self.abs())
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        each!(self.sqrt())
    }
    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        let mut out = self.0;
        for ((o, a), b) in out.iter_mut().zip(a.0).zip(b.0) {
            *o = o.mul_add(a, b);
        }
        Axes(out)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        each2!(self.min(other))
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        each2!(self.max(other))
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        each2!(self.copysign(sign))
    }
    #[inline(always)]
    fn simd_lt(self, other: Self) -> Self::Mask {
        each_mask!(self.simd_lt(other))
    }
    #[inline(always)]
    fn simd_le(self, other: Self) -> Self::Mask {
        each_mask!(self.simd_le(other))
    }
    #[inline(always)]
    fn simd_gt(self, other: Self) -> Self::Mask {
        each_mask!(self.simd_gt(other))
    }
    #[inline(always)]
    fn simd_ge(self, other: Self) -> Self::Mask {
        each_mask!(self.simd_ge(other))
    }
    #[inline(always)]
    fn simd_eq(self, other: Self) -> Self::Mask {
        each_mask!(self.simd_eq(other))
    }
    #[inline(always)]
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self {
        let mut out = a.0;
        for ((o, m), b) in out.iter_mut().zip(mask.0).zip(b.0) {
            *o = R::select(m, *o, b);
        }
        Self(out)
    }
    #[inline(always)]
    fn is_finite(self) -> Self::Mask {
        let mut out = [R::Mask::splat(false); D];
        for (o, v) in out.iter_mut().zip(self.0) {
            *o = v.is_finite();
        }
        AxesMask(out)
    }
    #[inline(always)]
    fn round_small(self) -> Self {
        each!(self.round_small())
    }
    #[inline(always)]
    fn pow2i(self) -> Self {
        each!(self.pow2i())
    }
    #[inline(always)]
    fn split_exponent(self) -> (Self, Self) {
        let mut e = self.0;
        let mut m = self.0;
        for i in 0..D {
            (e[i], m[i]) = self.0[i].split_exponent();
        }
        (Self(e), Self(m))
    }
    #[inline(always)]
    fn scale2(self, k: Self) -> Self {
        each2!(self.scale2(k))
    }
    #[inline(always)]
    fn lookup16(self, table: &[f64; 16]) -> Self {
        each!(self.lookup16(table))
    }
    #[inline(always)]
    fn add_shl48(self, n: Self) -> Self {
        each2!(self.add_shl48(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::Lanes;
    use nalgebra::Vector3;

    type A = Axes<Lanes<4>, 3>;

    #[test]
    fn lanes_are_numbered_axis_after_axis() {
        let a = A::from_fn(|i| i as f64);
        for i in 0..A::LANES {
            assert_eq!(a.lane(i), i as f64);
        }
        let m = <A as Real>::Mask::from_fn(|i| i % 5 == 0);
        for i in 0..A::LANES {
            assert_eq!(m.lane(i), i % 5 == 0);
        }
        assert!(!m.all() && m.any());
    }

    #[test]
    fn every_lane_is_the_lane_type_operation() {
        // exp and a power of mixed values, side by side, against each axis on its own
        let v = Vector3::new(
            Lanes([0.5, -3.0, 0.0, 750.0]),
            Lanes([1e-300, 2.0, f64::NAN, -0.0]),
            Lanes([7.25, 1e5, -1e-3, 3.0]),
        );
        let a = Axes::of(&v);
        let q = A::splat(0.7);
        let exp = a.exp().vector();
        let pow = a.abs().powf(q).vector();
        for k in 0..3 {
            let e = v[k].exp();
            let p = v[k].abs().powf(Lanes([0.7; 4]));
            for i in 0..4 {
                assert_eq!(exp[k].lane(i).to_bits(), e.lane(i).to_bits());
                assert_eq!(pow[k].lane(i).to_bits(), p.lane(i).to_bits());
            }
        }
    }
}
