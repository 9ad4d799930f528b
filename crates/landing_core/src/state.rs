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

    /// `self + k c`, component by component (the integrators' update, inlined for sure).
    #[inline(always)]
    fn add_scaled(&self, k: &Self, c: R) -> Self {
        Self::from_components(|i| self.component(i) + k.component(i) * c)
    }

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
}
