//! The state-vector abstraction the integrators and rollouts are generic over.

use nalgebra::SVector;
use std::ops::{Add, Mul};

/// A fixed-size plant state: copied by value, no heap, arithmetic for the integrators.
pub trait State:
    Copy + Send + Sync + 'static + Add<Output = Self> + Mul<f64, Output = Self>
{
    /// Number of components.
    const DIM: usize;

    fn as_slice(&self) -> &[f64];

    /// Build from exactly `DIM` values.
    fn from_slice(values: &[f64]) -> Self;

    #[inline]
    fn all_finite(&self) -> bool {
        self.as_slice().iter().all(|v| v.is_finite())
    }
}

impl<const N: usize> State for SVector<f64, N> {
    const DIM: usize = N;

    #[inline]
    fn as_slice(&self) -> &[f64] {
        nalgebra::Matrix::as_slice(self)
    }

    #[inline]
    fn from_slice(values: &[f64]) -> Self {
        SVector::<f64, N>::from_column_slice(values)
    }
}
