//! Gravity fields. Sign convention: the potential U is positive for a point mass
//! (U = +mu/r), and the field is its gradient, g = grad U, so gravity always attracts.
//!
//! Every field is generic over its number type (see [`crate::lanes`]): `PointMass` is one
//! case's field, `PointMass<Lanes<W>>` the fields of a block of cases.

mod harmonic2;
mod point_mass;
mod two_point;
mod uniform;

pub use harmonic2::Harmonic2;
pub use point_mass::PointMass;
pub use two_point::{G, TwoPointMass};
pub use uniform::{GRAVITY, Uniform};

use nalgebra::Vector3;

use crate::error::Validate;
use crate::lanes::{Gather, Real};

pub trait GravityField<R: Real>: Copy + Send + Sync {
    /// Field (acceleration) at `r`, m/s^2.
    fn acceleration(&self, r: &Vector3<R>) -> Vector3<R>;
    /// Potential at `r` with `acceleration = grad potential`, m^2/s^2.
    fn potential(&self, r: &Vector3<R>) -> R;
}

/// A gravity field as configured (one case's parameters), and the same field over lanes.
pub trait GravityModel:
    GravityField<f64> + Validate + Clone + PartialEq + Send + Sync + 'static
{
    type At<R: Real>: GravityField<R> + Gather<R, Case = Self>;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central finite difference of the potential, 4th order.
    fn fd_gradient<F: GravityField<f64>>(f: &F, r: &Vector3<f64>) -> Vector3<f64> {
        let h = 1e-2 * r.norm().max(1.0) * 1e-3;
        Vector3::from_fn(|i, _| {
            let e = Vector3::from_fn(|j, _| if i == j { h } else { 0.0 });
            (-f.potential(&(r + e * 2.0)) + 8.0 * f.potential(&(r + e))
                - 8.0 * f.potential(&(r - e))
                + f.potential(&(r - e * 2.0)))
                / (12.0 * h)
        })
    }

    fn probes() -> Vec<Vector3<f64>> {
        vec![
            Vector3::new(3200.0, 1300.0, 9000.0),
            Vector3::new(550.0, 500.0, 8200.0),
            Vector3::new(-20_000.0, 7_000.0, -3_000.0),
            Vector3::new(15_000.0, -14_000.0, 500.0),
            Vector3::new(2_000.0, 80.0, 20.0),
        ]
    }

    fn check_gradient<F: GravityField<f64>>(f: &F) {
        for r in probes() {
            let g = f.acceleration(&r);
            let fd = fd_gradient(f, &r);
            assert!(
                (g - fd).norm() <= 1e-7 * g.norm(),
                "at {r:?}: {g:?} vs {fd:?}"
            );
        }
    }

    fn check_inward<F: GravityField<f64>>(f: &F) {
        // beyond the mass points' span (2 x 7.7 km for the Eros dumbbell) the field points
        // at the centre's side
        for r in probes() {
            let g = f.acceleration(&(r * 10.0));
            assert!(g.dot(&r) < 0.0, "field at {r:?} points outward: {g:?}");
        }
    }

    #[test]
    fn each_field_is_the_gradient_of_its_potential() {
        check_gradient(&PointMass { mu: 4.46e5 });
        check_gradient(&TwoPointMass::eros());
        check_gradient(&Harmonic2::seed002());
        check_gradient(&Harmonic2 {
            mu: 1e6,
            r0: 5000.0,
            c20: 0.3,
            c22: -0.2,
        });
    }

    #[test]
    fn fields_attract() {
        check_inward(&PointMass { mu: 4.46e5 });
        check_inward(&TwoPointMass::eros());
        check_inward(&Harmonic2::seed002());
        let p = PointMass { mu: 1.0 };
        assert_eq!(p.potential(&Vector3::new(2.0, 0.0, 0.0)), 0.5);
        assert!(p.potential(&Vector3::new(1.0, 0.0, 0.0)) > 0.0);
    }

    #[test]
    fn far_fields_tend_to_the_point_mass() {
        let h = Harmonic2::seed002();
        let pm = PointMass { mu: h.mu };
        let two = TwoPointMass::eros();
        let pm2 = PointMass {
            mu: two.mu[0] + two.mu[1],
        };
        let dir = Vector3::new(0.3, -0.5, 0.8).normalize();
        let mut last_h = f64::INFINITY;
        let mut last_2 = f64::INFINITY;
        for k in 1..6 {
            let r = dir * (1e4 * 10f64.powi(k));
            let rel_h =
                (h.acceleration(&r) - pm.acceleration(&r)).norm() / pm.acceleration(&r).norm();
            let rel_2 =
                (two.acceleration(&r) - pm2.acceleration(&r)).norm() / pm2.acceleration(&r).norm();
            // the quadrupole falls as (R/r)^2 relative to the monopole
            assert!(
                rel_h < last_h / 50.0 && rel_2 < last_2 / 50.0,
                "{k}: {rel_h} {rel_2}"
            );
            last_h = rel_h;
            last_2 = rel_2;
        }
        assert!(last_h < 1e-10 && last_2 < 1e-10);
    }

    #[test]
    fn eros_dumbbell_defaults() {
        let e = TwoPointMass::eros();
        assert!((e.mu[0] + e.mu[1] - G * 6.687e15).abs() < 1e-6);
        // second moment along x: sum M_i d^2 = M d^2 = M a^2 / 5
        let d = e.positions[0][0];
        assert!((d * d / (17_200.0f64.powi(2) / 5.0) - 1.0).abs() < 1e-14);
        assert_eq!(e.positions[1][0], -d);
    }

    #[test]
    fn a_block_of_fields_evaluates_each_case() {
        use crate::lanes::Lanes;
        let cases = [
            Harmonic2::seed002(),
            Harmonic2 {
                mu: 1e6,
                r0: 5000.0,
                c20: 0.3,
                c22: -0.2,
            },
        ];
        let block: Harmonic2<Lanes<2>> = Gather::gather(&|i| &cases[i]);
        let r = [
            Vector3::new(3200.0, 1300.0, 9000.0),
            Vector3::new(-900.0, 20.0, 4000.0),
        ];
        let rl = Vector3::from_fn(|j, _| Lanes([r[0][j], r[1][j]]));
        let g = block.acceleration(&rl);
        for i in 0..2 {
            let gi = cases[i].acceleration(&r[i]);
            for j in 0..3 {
                assert_eq!(g[j].0[i].to_bits(), gi[j].to_bits());
            }
        }
    }
}
