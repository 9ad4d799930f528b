//! Dispersions of initial states: the random part of a Monte Carlo campaign.
//!
//! Case i's sample depends only on (seed, i): component j takes draw j of the case's
//! dispersion stream, so a campaign gives the same cases whatever the batch
//! size, chunking or thread count.

use crate::error::{ParamError, ReadError, check};
use crate::params::{FromParams, Param, ParamSource, Schema};
use crate::rng::{CaseStream, streams};

const MEAN: Param = Param::components("mean")
    .unit("units of the component")
    .doc("mean of each component (one for all)");
const STD: Param = Param::components("std")
    .unit("units of the component")
    .rule("std >= 0")
    .doc("standard deviation of each component (0 fixes the value)");
const LOW: Param = Param::components("low")
    .unit("units of the component")
    .doc("lower end of each component's range");
const HIGH: Param = Param::components("high")
    .unit("units of the component")
    .rule("high >= low")
    .doc("upper end of each component's range (high = low fixes the value)");

crate::named! {
    /// The distributions' kinds at the Python boundary.
    pub enum DispersionKind in "dispersion" {
        Normal => "normal": Schema::new(&[MEAN, STD]),
        Uniform => "uniform": Schema::new(&[LOW, HIGH]),
    }
}

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
                check(&MEAN, mean, |_| true)?;
                check(&STD, std, |s| s >= 0.0)
            }
            Component::Uniform { low, high } => {
                check(&LOW, low, |_| true)?;
                check(&HIGH, high, |h| h >= low)
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

impl FromParams for Dispersion {
    /// `normal` (mean, std) or `uniform` (low, high), each a scalar or one value per
    /// component (a scalar serves every component), validated.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let kind = p.kind::<DispersionKind>()?;
        let (a, b) = match kind {
            DispersionKind::Normal => (&MEAN, &STD),
            DispersionKind::Uniform => (&LOW, &HIGH),
        };
        let first = p.components(a)?;
        let second = p.components(b)?;
        if first.len() != second.len() && first.len() != 1 && second.len() != 1 {
            return Err(ReadError::value(format!(
                "{} has {} components and {} has {}",
                a.name,
                first.len(),
                b.name,
                second.len()
            )));
        }
        let pick = |v: &[f64], j: usize| v[if v.len() == 1 { 0 } else { j }];
        let components = (0..first.len().max(second.len()))
            .map(|j| match kind {
                DispersionKind::Normal => Component::Normal {
                    mean: pick(&first, j),
                    std: pick(&second, j),
                },
                DispersionKind::Uniform => Component::Uniform {
                    low: pick(&first, j),
                    high: pick(&second, j),
                },
            })
            .collect();
        let d = Dispersion { components };
        d.validate().map_err(|e| {
            let j = e.axis.unwrap_or(0);
            ReadError::value(format!(
                "{}[{j}] = {} violates {}",
                e.param, e.value, e.rule
            ))
        })?;
        Ok(d)
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
