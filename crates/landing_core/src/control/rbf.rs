//! Gaussian radial-basis-function network of seed 003 section 3.1.2, per axis.
//!
//! Each axis has its own network on its own errors z = (e1, e2) (the seed indexes centres and
//! widths by axis i and node j). The two inputs have different units and scales (rad and
//! rad/s), so they are normalised first, z = (e1 / scale_e1, e2 / scale_e2), and the seed's
//! isotropic Gaussian applies to the normalised input:
//!
//! ```text
//! Phi_j(z) = exp(-|z - mu_j|^2 / b^2)
//! ```
//! The centres mu_j form an n x n grid on [-1, 1]^2 (a single node at 0 for n = 1). The
//! Gaussian separates, `Phi_(a,c) = exp(-(z1 - mu_a)^2/b^2) exp(-(z2 - mu_c)^2/b^2)`, so a
//! grid of n^2 nodes costs 2 n exponentials.

use crate::lanes::Real;
use crate::lanes::slots::Slots;

/// Most centres per input.
pub const MAX_GRID: usize = 7;
/// Most nodes of one axis's network.
pub const MAX_NODES: usize = MAX_GRID * MAX_GRID;

/// Centre a of an n-point grid on [-1, 1].
#[inline(always)]
pub fn centre(a: usize, n: usize) -> f64 {
    if n == 1 {
        0.0
    } else {
        -1.0 + 2.0 * a as f64 / (n - 1) as f64
    }
}

/// The n^2 basis values at the normalised input `z`, node (a, c) at index `a n + c`, written
/// in `slots` (`n <= MAX_GRID`).
#[inline(always)]
pub fn basis<R: Real>(n: usize, z: [R; 2], width: R, slots: &mut Slots<R, MAX_NODES>) -> &[R] {
    let inv = R::one() / (width * width);
    let mut g1 = [R::zero(); MAX_GRID];
    let mut g2 = [R::zero(); MAX_GRID];
    for a in 0..n {
        let c = centre(a, n);
        let d1 = z[0] - c;
        let d2 = z[1] - c;
        g1[a] = (-d1 * d1 * inv).exp();
        g2[a] = (-d2 * d2 * inv).exp();
    }
    let mut out = slots.start();
    for &g1 in &g1[..n] {
        for &g2 in &g2[..n] {
            out.push(g1 * g2);
        }
    }
    out.done()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_the_seeds_gaussian_on_the_grid() {
        let z = [0.3, -0.7];
        let b = 0.8;
        let mut slots = Slots::EMPTY;
        let phi = basis(3, z, b, &mut slots);
        assert_eq!(phi.len(), 9);
        for a in 0..3 {
            for c in 0..3 {
                let mu = [-1.0 + a as f64, -1.0 + c as f64];
                let d2 = (z[0] - mu[0]).powi(2) + (z[1] - mu[1]).powi(2);
                let expect = (-d2 / (b * b)).exp();
                assert!((phi[a * 3 + c] - expect).abs() < 1e-15);
            }
        }
        assert_eq!(basis(1, [0.0, 0.0], 1.0, &mut slots), &[1.0]);
    }
}
