//! Fixed-step integrators (SPEC section 2).
//!
//! An integrator advances `x' = f(t, x)` by one step `h`; the rollout calls it `substeps` times
//! per control period with the command held, so `f` closes over the held command and evaluates
//! time-dependent disturbances at each stage's own time.

use crate::state::State;

pub trait Integrator: Copy + Send + Sync + 'static {
    /// Name used at the Python boundary.
    const NAME: &'static str;
    /// Convergence order (global error ~ h^ORDER), for documentation and tests.
    const ORDER: u32;

    fn step<S: State, F: Fn(f64, &S) -> S>(&self, f: &F, t: f64, x: &S, h: f64) -> S;
}

/// Classic four-stage Runge-Kutta.
#[derive(Clone, Copy, Debug, Default)]
pub struct Rk4;

impl Integrator for Rk4 {
    const NAME: &'static str = "rk4";
    const ORDER: u32 = 4;

    #[inline(always)]
    fn step<S: State, F: Fn(f64, &S) -> S>(&self, f: &F, t: f64, x: &S, h: f64) -> S {
        let half = 0.5 * h;
        let k1 = f(t, x);
        let k2 = f(t + half, &(*x + k1 * half));
        let k3 = f(t + half, &(*x + k2 * half));
        let k4 = f(t + h, &(*x + k3 * h));
        *x + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0)
    }
}

/// Forward Euler.
#[derive(Clone, Copy, Debug, Default)]
pub struct Euler;

impl Integrator for Euler {
    const NAME: &'static str = "euler";
    const ORDER: u32 = 1;

    #[inline(always)]
    fn step<S: State, F: Fn(f64, &S) -> S>(&self, f: &F, t: f64, x: &S, h: f64) -> S {
        *x + f(t, x) * h
    }
}

/// The integrators by name, for dispatch at the boundary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    Rk4,
    Euler,
}

impl IntegratorKind {
    pub const NAMES: [&'static str; 2] = [Rk4::NAME, Euler::NAME];

    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "rk4" => Some(Self::Rk4),
            "euler" => Some(Self::Euler),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    /// Global error at t = 5 of the harmonic oscillator x'' = -x, x(0) = 1, x'(0) = 0, whose
    /// solution is (cos t, -sin t).
    fn oscillator_error<I: Integrator>(integ: I, h: f64) -> f64 {
        let f = |_t: f64, x: &Vector2<f64>| Vector2::new(x[1], -x[0]);
        let n = (5.0 / h).round() as usize;
        let mut x = Vector2::new(1.0, 0.0);
        for k in 0..n {
            x = integ.step(&f, k as f64 * h, &x, h);
        }
        let t = n as f64 * h;
        (x - Vector2::new(t.cos(), -t.sin())).norm()
    }

    /// Global error at t = 2 of the time-dependent x' = x cos t, x(0) = 1 (x = e^{sin t}):
    /// checks that stage times are the right ones.
    fn time_dependent_error<I: Integrator>(integ: I, h: f64) -> f64 {
        let f = |t: f64, x: &nalgebra::Vector1<f64>| *x * t.cos();
        let n = (2.0 / h).round() as usize;
        let mut x = nalgebra::Vector1::new(1.0);
        for k in 0..n {
            x = integ.step(&f, k as f64 * h, &x, h);
        }
        (x[0] - (n as f64 * h).sin().exp()).abs()
    }

    fn observed_order(e_coarse: f64, e_fine: f64) -> f64 {
        (e_coarse / e_fine).log2()
    }

    #[test]
    fn rk4_is_fourth_order() {
        for err in [oscillator_error::<Rk4>, time_dependent_error::<Rk4>] {
            let e = [0.1, 0.05, 0.025].map(|h| err(Rk4, h));
            for w in e.windows(2) {
                let p = observed_order(w[0], w[1]);
                assert!((p - 4.0).abs() < 0.15, "observed order {p}, errors {e:?}");
            }
        }
    }

    #[test]
    fn euler_is_first_order() {
        for err in [oscillator_error::<Euler>, time_dependent_error::<Euler>] {
            let e = [0.004, 0.002, 0.001].map(|h| err(Euler, h));
            for w in e.windows(2) {
                let p = observed_order(w[0], w[1]);
                assert!((p - 1.0).abs() < 0.05, "observed order {p}, errors {e:?}");
            }
        }
    }
}
