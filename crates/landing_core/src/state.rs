//! The state-vector abstraction the integrators and rollouts are generic over.

use nalgebra::SVector;
use std::ops::{Add, Mul};

use crate::lanes::{Real, all_finite, vector};

/// A fixed-size plant state over lanes: copied by value, no heap, the arithmetic the
/// integrators need (`x + k h`, with `h` splat over the lanes).
pub trait State<R: Real>:
    Copy + Send + Sync + 'static + Add<Output = Self> + Mul<R, Output = Self>
{
    /// Number of components.
    const DIM: usize;

    fn component(&self, i: usize) -> R;

    fn from_components(f: impl FnMut(usize) -> R) -> Self;

    /// Whether every component is finite, per lane.
    fn all_finite(&self) -> R::Mask;

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
