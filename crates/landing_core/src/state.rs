//! The state-vector abstraction the integrators and rollouts are generic over.

use nalgebra::SVector;

use crate::lanes::{Real, all_finite, vector};

/// A fixed-size plant state over lanes: copied by value, no heap, the arithmetic the
/// integrators need (`x + k h`, with `h` splat over the lanes), written component by component.
pub trait State<R: Real>: Copy + Send + Sync + 'static {
    /// Number of components.
    const DIM: usize;

    fn component(&self, i: usize) -> R;

    fn from_components(f: impl FnMut(usize) -> R) -> Self;

    /// Whether every component is finite, per lane.
    fn all_finite(&self) -> R::Mask;

    /// `self + k c`, component by component (the integrators' update).
    fn add_scaled(&self, k: &Self, c: R) -> Self;

    /// `k c`, component by component.
    fn scaled(&self, c: R) -> Self;

    /// Lane-wise select: `a` where the mask is set, `b` elsewhere.
    #[inline(always)]
    fn select(mask: R::Mask, a: &Self, b: &Self) -> Self {
        Self::from_components(|i| R::select(mask, a.component(i), b.component(i)))
    }
}

impl<R: Real, const N: usize> State<R> for SVector<R, N> {
    const DIM: usize = N;

    #[inline(always)]
    fn component(&self, i: usize) -> R {
        self[i]
    }

    #[inline(always)]
    fn from_components(f: impl FnMut(usize) -> R) -> Self {
        vector(f)
    }

    #[inline(always)]
    fn all_finite(&self) -> R::Mask {
        all_finite(self)
    }

    // explicit loops, not closures: a closure this often called is not always inlined, and
    // out of line it would run without the kernel's instructions
    #[inline(always)]
    fn add_scaled(&self, k: &Self, c: R) -> Self {
        let mut out = *self;
        for i in 0..N {
            out[i] = self[i] + k[i] * c;
        }
        out
    }

    #[inline(always)]
    fn scaled(&self, c: R) -> Self {
        let mut out = *self;
        for i in 0..N {
            out[i] = self[i] * c;
        }
        out
    }

    #[inline(always)]
    fn select(mask: R::Mask, a: &Self, b: &Self) -> Self {
        let mut out = *a;
        for i in 0..N {
            out[i] = R::select(mask, a[i], b[i]);
        }
        out
    }
}
