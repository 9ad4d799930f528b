//! Dispersions of initial states: the random part of a Monte Carlo campaign.
//!
//! Case i's sample depends only on (seed, i): component j takes draw j of the case's
//! dispersion stream, so a campaign gives the same cases whatever the batch
//! size, chunking or thread count.

use crate::error::{ParamError, require};
use crate::rng::{CaseStream, streams};

/// The distribution of one state component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Component {
    /// Normal with a mean and a standard deviation (0 for a fixed value).
    Normal { mean: f64, std: f64 },
    /// Uniform on [low, high] (low = high for a fixed value).
    Uniform { low: f64, high: f64 },
}

impl Component {
    pub fn validate(&self) -> Result<(), ParamError> {
        match *self {
            Component::Normal { mean, std } => {
                require(true, "mean", mean, "finite values")?;
                require(std >= 0.0, "std", std, "std >= 0")
            }
            Component::Uniform { low, high } => {
                require(true, "low", low, "finite values")?;
                require(high >= low, "high", high, "high >= low")
            }
        }
    }

    /// Mean and standard deviation of the distribution.
    pub fn moments(&self) -> (f64, f64) {
        match *self {
            Component::Normal { mean, std } => (mean, std),
            Component::Uniform { low, high } => (0.5 * (low + high), (high - low) / 12f64.sqrt()),
        }
    }
}

/// Independent components, one per state component.
#[derive(Clone, Debug, PartialEq)]
pub struct Dispersion {
    pub components: Vec<Component>,
}

impl Dispersion {
    pub fn validate(&self) -> Result<(), ParamError> {
        for (j, c) in self.components.iter().enumerate() {
            c.validate().map_err(|e| e.on_axis(j))?;
        }
        Ok(())
    }

    pub fn dim(&self) -> usize {
        self.components.len()
    }

    /// The sample of global case `case` into `out` (length `dim`).
    pub fn sample_into(&self, seed: u64, case: u64, out: &mut [f64]) {
        let rng = CaseStream::new(seed, streams::DISPERSION, case);
        let n = self.dim();
        let mut z = vec![0.0; n];
        let mut u = vec![0.0; n];
        // normals and uniforms read the same words: each component uses one of them only
        rng.fill_normals(0, &mut z);
        rng.fill_uniforms(0, &mut u);
        for (j, c) in self.components.iter().enumerate() {
            out[j] = match *c {
                Component::Normal { mean, std } => mean + std * z[j],
                Component::Uniform { low, high } => low + (high - low) * u[j],
            };
        }
    }

    /// Cases `first_case .. first_case + n`, row-major (n x dim).
    pub fn sample(&self, seed: u64, first_case: u64, n: usize) -> Vec<f64> {
        let d = self.dim();
        let mut out = vec![0.0; n * d];
        for (i, row) in out.chunks_mut(d.max(1)).enumerate().take(n) {
            self.sample_into(seed, first_case + i as u64, row);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_match_requested_moments_and_do_not_depend_on_chunking() {
        let d = Dispersion {
            components: vec![
                Component::Normal {
                    mean: -2000.0,
                    std: 100.0,
                },
                Component::Uniform {
                    low: -15.0,
                    high: 45.0,
                },
                Component::Normal {
                    mean: 1905.0,
                    std: 0.0,
                },
            ],
        };
        let n = 20_000;
        let all = d.sample(3, 0, n);
        let mut parts = d.sample(3, 0, 7);
        parts.extend(d.sample(3, 7, n - 7));
        assert_eq!(all, parts);
        for (j, c) in d.components.iter().enumerate() {
            let col: Vec<f64> = all.iter().skip(j).step_by(3).copied().collect();
            let mean = col.iter().sum::<f64>() / n as f64;
            let sd = (col.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
            let (m, s) = c.moments();
            assert!(
                (mean - m).abs() <= 4.0 * s / (n as f64).sqrt() + 1e-12,
                "{j}: {mean} vs {m}"
            );
            assert!((sd - s).abs() <= 0.03 * s + 1e-12, "{j}: {sd} vs {s}");
        }
        let u: Vec<f64> = all.iter().skip(1).step_by(3).copied().collect();
        assert!(u.iter().all(|&x| (-15.0..=45.0).contains(&x)));
    }
}
