//! Lumped unknown disturbances (SPEC 3.1: a_p of seed 001 eq. 30 and 47).
//!
//! The disturbance is a generalized acceleration added to q'' by the plant; the laws never see
//! it. Deterministic parts are evaluated at each integrator stage's time; the random part is
//! drawn once per control period from the case's counter-based stream and held (SPEC 2).

use nalgebra::SVector;

use crate::error::{ParamError, require};
use crate::rng::{CaseStream, streams};

/// Most sinusoidal components one disturbance carries (kept fixed so the type stays `Copy`).
pub const MAX_SINUSOIDS: usize = 4;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sinusoid<const D: usize> {
    pub amplitude: SVector<f64, D>,
    /// Angular frequency, rad/s.
    pub omega: SVector<f64, D>,
    pub phase: SVector<f64, D>,
}

impl<const D: usize> Sinusoid<D> {
    /// Same frequency and phase on every axis: one sine serves them all.
    fn in_phase(&self) -> bool {
        (1..D).all(|i| self.omega[i] == self.omega[0] && self.phase[i] == self.phase[0])
    }
}

/// `d(t) = constant + sum_j A_j sin(omega_j t + phase_j) + n_k`, with `n_k` uniform on
/// `[-bound, bound]` per axis, drawn for control period k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disturbance<const D: usize> {
    pub constant: SVector<f64, D>,
    sinusoids: [Sinusoid<D>; MAX_SINUSOIDS],
    in_phase: [bool; MAX_SINUSOIDS],
    n_sinusoids: usize,
    pub noise_bound: SVector<f64, D>,
}

impl<const D: usize> Default for Disturbance<D> {
    fn default() -> Self {
        let zero = SVector::zeros();
        Self {
            constant: zero,
            sinusoids: [Sinusoid {
                amplitude: zero,
                omega: zero,
                phase: zero,
            }; MAX_SINUSOIDS],
            in_phase: [false; MAX_SINUSOIDS],
            n_sinusoids: 0,
            noise_bound: zero,
        }
    }
}

/// Per-period state of a disturbance: the held random draw.
#[derive(Clone, Copy, Debug)]
pub struct HeldNoise<const D: usize>(pub SVector<f64, D>);

impl<const D: usize> Disturbance<D> {
    pub fn none() -> Self {
        Self::default()
    }

    pub fn with_constant(mut self, value: SVector<f64, D>) -> Self {
        self.constant += value;
        self
    }

    pub fn with_noise(mut self, bound: SVector<f64, D>) -> Self {
        self.noise_bound += bound;
        self
    }

    /// Adds a sinusoid; fails past [`MAX_SINUSOIDS`] components.
    pub fn with_sinusoid(mut self, s: Sinusoid<D>) -> Result<Self, ParamError> {
        if self.n_sinusoids == MAX_SINUSOIDS {
            return Err(ParamError::new(
                "disturbance",
                (MAX_SINUSOIDS + 1) as f64,
                "at most 4 sinusoidal components",
            ));
        }
        self.sinusoids[self.n_sinusoids] = s;
        self.in_phase[self.n_sinusoids] = s.in_phase();
        self.n_sinusoids += 1;
        Ok(self)
    }

    pub fn sinusoids(&self) -> &[Sinusoid<D>] {
        &self.sinusoids[..self.n_sinusoids]
    }

    pub fn has_noise(&self) -> bool {
        self.noise_bound.iter().any(|&b| b > 0.0)
    }

    /// Bound on |d_i(t)| per axis (used by the theory's practical fixed-time neighbourhoods).
    pub fn bound(&self) -> SVector<f64, D> {
        let mut b = self.constant.abs() + self.noise_bound;
        for s in self.sinusoids() {
            b += s.amplitude.abs();
        }
        b
    }

    /// The random draw for control period `period` of the case whose stream is given.
    #[inline]
    pub fn draw(&self, rng: &CaseStream, period: u64) -> HeldNoise<D> {
        if !self.has_noise() {
            return HeldNoise(SVector::zeros());
        }
        // ceil(D / 4) Philox blocks per period, so axes never share a word
        let blocks = D.div_ceil(4) as u64;
        let mut u = SVector::<f64, D>::zeros();
        rng.fill_uniforms(period * blocks, u.as_mut_slice());
        HeldNoise(
            self.noise_bound
                .component_mul(&(u * 2.0 - SVector::repeat(1.0))),
        )
    }

    /// The deterministic part at time `t`.
    #[inline(always)]
    pub fn deterministic(&self, t: f64) -> SVector<f64, D> {
        let mut d = self.constant;
        for (s, &in_phase) in self.sinusoids[..self.n_sinusoids]
            .iter()
            .zip(&self.in_phase)
        {
            if in_phase {
                d += s.amplitude * (s.omega[0] * t + s.phase[0]).sin();
            } else {
                for i in 0..D {
                    d[i] += s.amplitude[i] * (s.omega[i] * t + s.phase[i]).sin();
                }
            }
        }
        d
    }

    #[inline(always)]
    pub fn at(&self, t: f64, held: &HeldNoise<D>) -> SVector<f64, D> {
        self.deterministic(t) + held.0
    }

    pub fn validate(&self) -> Result<(), ParamError> {
        for i in 0..D {
            require(true, "constant", self.constant[i], "finite values")
                .map_err(|e| e.on_axis(i))?;
            let b = self.noise_bound[i];
            require(b >= 0.0, "bound", b, "bound >= 0").map_err(|e| e.on_axis(i))?;
            for s in self.sinusoids() {
                require(true, "amplitude", s.amplitude[i], "finite values")
                    .map_err(|e| e.on_axis(i))?;
                require(true, "omega", s.omega[i], "finite values").map_err(|e| e.on_axis(i))?;
                require(true, "phase", s.phase[i], "finite values").map_err(|e| e.on_axis(i))?;
            }
        }
        Ok(())
    }
}

/// The stream a case's disturbance draws from.
pub fn disturbance_stream(seed: u64, case: u64) -> CaseStream {
    CaseStream::new(seed, streams::DISTURBANCE, case)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn deterministic_parts_add_up() {
        let d = Disturbance::<3>::none()
            .with_constant(Vector3::new(1.0, 0.0, -1.0))
            .with_sinusoid(Sinusoid {
                amplitude: Vector3::repeat(20.0),
                omega: Vector3::repeat(1.0),
                phase: Vector3::new(0.0, 0.5, 0.0),
            })
            .unwrap();
        let v = d.at(0.3, &HeldNoise(Vector3::zeros()));
        assert!((v[0] - (1.0 + 20.0 * 0.3f64.sin())).abs() < 1e-14);
        assert!((v[1] - 20.0 * 0.8f64.sin()).abs() < 1e-14);
        assert_eq!(d.bound(), Vector3::new(21.0, 20.0, 21.0));
    }

    #[test]
    fn noise_is_bounded_held_and_reproducible() {
        let d = Disturbance::<3>::none().with_noise(Vector3::new(0.5, 1.0, 0.0));
        let s = disturbance_stream(11, 4);
        let mut max = Vector3::<f64>::zeros();
        for k in 0..5000 {
            let n = d.draw(&s, k);
            max = max.sup(&n.0.abs());
            assert_eq!(n.0, d.draw(&s, k).0);
        }
        assert!(max[0] <= 0.5 && max[0] > 0.49);
        assert!(max[1] <= 1.0 && max[1] > 0.98);
        assert_eq!(max[2], 0.0);
    }
}
