//! The state-vector abstraction the integrators and rollouts are generic over.

use nalgebra::SVector;

use crate::lanes::{Real, all_finite, vector};

/// A fixed-size plant state over lanes: copied by value, no heap, the arithmetic the
/// integrators need (`x + k h`, with `h` splat over the lanes), written component by component.
pub trait State<R: Real>: Copy + Send + Sync + 'static {
    /// Number of components.
    const DIM: usize;

    fn component(&self, i: usize) -> R;

    fn set_component(&mut self, i: usize, v: R);

    fn from_components(f: impl FnMut(usize) -> R) -> Self;

    /// Whether every component is finite, per lane.
    fn all_finite(&self) -> R::Mask;

    /// Whether every component is at most `bound` in magnitude, per lane (false for a NaN).
    fn all_within(&self, bound: R) -> R::Mask;

    // The integrators' updates work in place: a state of the flexible tether over a block of
    // lanes is kilobytes, and a value returned per update was a memcpy the compiler kept.

    /// `self = x + k c`, component by component.
    fn set_add_scaled(&mut self, x: &Self, k: &Self, c: R);

    /// `self += k c`, component by component.
    fn add_scaled_assign(&mut self, k: &Self, c: R);

    /// `self += k`, component by component.
    fn add_assign_state(&mut self, k: &Self);

    /// `self = k c`, component by component.
    fn set_scaled(&mut self, k: &Self, c: R);

    /// Lane-wise: `a` where the mask is set, `self` elsewhere.
    fn select_assign(&mut self, mask: R::Mask, a: &Self);
}

impl<R: Real, const N: usize> State<R> for SVector<R, N> {
    const DIM: usize = N;

    #[inline(always)]
    fn component(&self, i: usize) -> R {
        self[i]
    }

    #[inline(always)]
    fn set_component(&mut self, i: usize, v: R) {
        self[i] = v;
    }

    #[inline(always)]
    fn from_components(f: impl FnMut(usize) -> R) -> Self {
        vector(f)
    }

    #[inline(always)]
    fn all_finite(&self) -> R::Mask {
        all_finite(self)
    }

    #[inline(always)]
    fn all_within(&self, bound: R) -> R::Mask {
        let mut m = self[0].abs().simd_le(bound);
        for i in 1..N {
            m = m & self[i].abs().simd_le(bound);
        }
        m
    }

    // explicit loops, not closures: a closure this often called is not always inlined, and
    // out of line it would run without the kernel's instructions
    #[inline(always)]
    fn set_add_scaled(&mut self, x: &Self, k: &Self, c: R) {
        for i in 0..N {
            self[i] = k[i].mul_add(c, x[i]);
        }
    }

    #[inline(always)]
    fn add_scaled_assign(&mut self, k: &Self, c: R) {
        for i in 0..N {
            self[i] = k[i].mul_add(c, self[i]);
        }
    }

    #[inline(always)]
    fn add_assign_state(&mut self, k: &Self) {
        for i in 0..N {
            self[i] += k[i];
        }
    }

    #[inline(always)]
    fn set_scaled(&mut self, k: &Self, c: R) {
        for i in 0..N {
            self[i] = k[i] * c;
        }
    }

    #[inline(always)]
    fn select_assign(&mut self, mask: R::Mask, a: &Self) {
        for i in 0..N {
            self[i] = R::select(mask, a[i], self[i]);
        }
    }
}
