//! Dispersions of initial states and of parameters: the random part of a Monte Carlo campaign.
//!
//! Case i's sample depends only on (seed, stream, i): component j takes draw j of the case's
//! stream, so a campaign gives the same cases whatever the batch size, chunking or thread
//! count. The initial states draw from the dispersion stream; a dispersed parameter from its
//! own stream, keyed by its name ([`parameter_stream`]), so that its draws do not depend on
//! which other parameters are dispersed.

use crate::error::{ParamError, ReadError, check};
use crate::limits::{MAX_CASES, within_cap};
use crate::params::{FromParams, Param, ParamSource, Schema};
use crate::rng::{CaseStream, streams};
use crate::special::{normal_cdf, normal_quantile};

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
const MU: Param = Param::components("mu")
    .unit("log of the component's units")
    .doc("mean of the logarithm of each component");
const SIGMA: Param = Param::components("sigma")
    .unit("1")
    .rule("sigma >= 0")
    .doc("standard deviation of the logarithm of each component (0 fixes the value at exp(mu))");
/// The bounds of a truncated normal: the window must hold some of the normal's probability.
const WINDOW: &str = "low <= high and a window of probability > 0 (mean within it when std = 0)";

crate::named! {
    /// The distributions' kinds at the Python boundary.
    pub enum DispersionKind in "dispersion" {
        Normal => "normal": Schema::new(&[MEAN, STD]),
        Uniform => "uniform": Schema::new(&[LOW, HIGH]),
        TruncatedNormal => "truncated_normal": Schema::new(&[MEAN, STD, LOW, HIGH]),
        LogNormal => "lognormal": Schema::new(&[MU, SIGMA]),
    }
}

/// The distribution of one state component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Component {
    /// Normal with a mean and a standard deviation (0 for a fixed value).
    Normal { mean: f64, std: f64 },
    /// Uniform on [low, high] (low = high for a fixed value).
    Uniform { low: f64, high: f64 },
    /// Normal(mean, std) conditioned on [low, high], drawn by inverting its distribution
    /// function (exact in the tails, where rejection would loop).
    TruncatedNormal {
        mean: f64,
        std: f64,
        low: f64,
        high: f64,
    },
    /// exp(N(mu, sigma)): positive, for quantities dispersed by a factor (numpy's and
    /// scipy's `lognorm(s=sigma, scale=exp(mu))` parametrisation).
    LogNormal { mu: f64, sigma: f64 },
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
            Component::TruncatedNormal {
                mean,
                std,
                low,
                high,
            } => {
                check(&STD, std, |s| s >= 0.0)?;
                let held = if std == 0.0 {
                    (low..=high).contains(&mean)
                } else {
                    let (a, b, _) = standard_window(mean, std, low, high);
                    high >= low && normal_cdf(b) - normal_cdf(a) > 0.0
                };
                if !held {
                    return Err(ParamError::new("high", high, WINDOW));
                }
                Ok(())
            }
            Component::LogNormal { sigma, .. } => check(&SIGMA, sigma, |s| s >= 0.0),
        }
    }

    /// The component's value for the uniform `u` in [0, 1) and the normal `z` of the same
    /// draw (each kind uses one of them).
    fn draw(&self, z: f64, u: f64) -> f64 {
        match *self {
            Component::Normal { mean, std } => mean + std * z,
            Component::Uniform { low, high } => low + (high - low) * u,
            Component::TruncatedNormal { std: 0.0, mean, .. } => mean,
            Component::TruncatedNormal {
                mean,
                std,
                low,
                high,
            } => {
                let (a, b, sign) = standard_window(mean, std, low, high);
                let (pa, pb) = (normal_cdf(a), normal_cdf(b));
                let x = normal_quantile(pa + u * (pb - pa)).clamp(a, b);
                // rounding may leave the window by an ulp: the bounds hold exactly
                (mean + sign * std * x).clamp(low, high)
            }
            Component::LogNormal { mu, sigma } => (mu + sigma * z).exp(),
        }
    }

    /// Mean and standard deviation of the distribution.
    pub fn moments(&self) -> (f64, f64) {
        match *self {
            Component::Normal { mean, std } => (mean, std),
            Component::Uniform { low, high } => (0.5 * (low + high), (high - low) / 12f64.sqrt()),
            Component::TruncatedNormal { std: 0.0, mean, .. } => (mean, 0.0),
            Component::TruncatedNormal {
                mean,
                std,
                low,
                high,
            } => {
                // the standard truncated normal's moments, from the density at the ends
                let (a, b, sign) = standard_window(mean, std, low, high);
                let pdf = |x: f64| (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
                let z = normal_cdf(b) - normal_cdf(a);
                let m = (pdf(a) - pdf(b)) / z;
                let v = 1.0 + (a * pdf(a) - b * pdf(b)) / z - m * m;
                (mean + sign * std * m, std * v.max(0.0).sqrt())
            }
            Component::LogNormal { mu, sigma } => {
                let m = (mu + 0.5 * sigma * sigma).exp();
                (m, m * (sigma * sigma).exp_m1().sqrt())
            }
        }
    }
}

/// The window [low, high] of N(mean, std) in standard units, mirrored into the lower half when
/// it lies in the upper one (the distribution function is accurate there, where 1 - Phi is
/// not), and the sign that undoes the mirror.
fn standard_window(mean: f64, std: f64, low: f64, high: f64) -> (f64, f64, f64) {
    let (a, b) = ((low - mean) / std, (high - mean) / std);
    if a > 0.0 { (-b, -a, -1.0) } else { (a, b, 1.0) }
}

/// The stream of the dispersed parameter `name` (`"plant.isp"`): its FNV-1a hash with the top
/// bit set, so that it is none of the fixed streams of [`streams`], and a case's draw of one
/// parameter does not depend on the other parameters dispersed.
pub fn parameter_stream(name: &str) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    h | 1 << 63
}

/// Independent components: one per state component (initial states), or per component of a
/// dispersed parameter.
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

    /// The sample of global case `case` from `stream` into `out` (length `dim`).
    pub fn sample_into(&self, seed: u64, stream: u64, case: u64, out: &mut [f64]) {
        let rng = CaseStream::new(seed, stream, case);
        let n = self.dim();
        let mut z = vec![0.0; n];
        let mut u = vec![0.0; n];
        // normals and uniforms read the same words: each component uses one of them only
        rng.fill_normals(0, &mut z);
        rng.fill_uniforms(0, &mut u);
        for (j, c) in self.components.iter().enumerate() {
            out[j] = c.draw(z[j], u[j]);
        }
    }

    /// Cases `first_case .. first_case + n` of the initial states' stream, row-major (n x dim).
    pub fn sample(&self, seed: u64, first_case: u64, n: usize) -> Vec<f64> {
        self.sample_stream(seed, streams::DISPERSION, first_case, n)
    }

    /// [`Dispersion::sample_stream`] for cases a caller names: refused when `n` passes the
    /// case cap or the cases run past the counter's 2^64.
    pub fn sample_checked(
        &self,
        seed: u64,
        stream: u64,
        first_case: u64,
        n: usize,
    ) -> Result<Vec<f64>, ReadError> {
        within_cap("n", n as u64, "max_cases", MAX_CASES)?;
        if first_case.checked_add(n as u64).is_none() {
            return Err(ReadError::value(format!(
                "first_case = {first_case} violates first_case + n < 2^64 (n = {n})"
            )));
        }
        Ok(self.sample_stream(seed, stream, first_case, n))
    }

    /// Cases `first_case .. first_case + n` of `stream` ([`parameter_stream`] for a parameter).
    pub fn sample_stream(&self, seed: u64, stream: u64, first_case: u64, n: usize) -> Vec<f64> {
        let d = self.dim();
        let mut out = vec![0.0; n * d];
        for (i, row) in out.chunks_mut(d.max(1)).enumerate().take(n) {
            self.sample_into(seed, stream, first_case + i as u64, row);
        }
        out
    }
}

impl FromParams for Dispersion {
    /// `normal` (mean, std), `uniform` (low, high), `truncated_normal` (mean, std, low, high)
    /// or `lognormal` (mu, sigma), each a scalar or one value per component (a scalar serves
    /// every component), validated.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let kind = p.kind::<DispersionKind>()?;
        let params: &[Param] = match kind {
            DispersionKind::Normal => &[MEAN, STD],
            DispersionKind::Uniform => &[LOW, HIGH],
            DispersionKind::TruncatedNormal => &[MEAN, STD, LOW, HIGH],
            DispersionKind::LogNormal => &[MU, SIGMA],
        };
        let values = params
            .iter()
            .map(|q| p.components(q))
            .collect::<Result<Vec<_>, _>>()?;
        let dim = values.iter().map(Vec::len).max().unwrap_or(1);
        if let Some((q, v)) = params
            .iter()
            .zip(&values)
            .find(|(_, v)| v.len() != 1 && v.len() != dim)
        {
            // both named: the message holds whichever of the two the user meant to change
            let widest = params[values.iter().position(|v| v.len() == dim).unwrap_or(0)].name;
            return Err(ReadError::value(format!(
                "{} has {} components and {widest} {dim}: give each one value, or {dim}",
                q.name,
                v.len()
            )));
        }
        let components = (0..dim)
            .map(|j| {
                let v: Vec<f64> = values
                    .iter()
                    .map(|v| v[if v.len() == 1 { 0 } else { j }])
                    .collect();
                match kind {
                    DispersionKind::Normal => Component::Normal {
                        mean: v[0],
                        std: v[1],
                    },
                    DispersionKind::Uniform => Component::Uniform {
                        low: v[0],
                        high: v[1],
                    },
                    DispersionKind::TruncatedNormal => Component::TruncatedNormal {
                        mean: v[0],
                        std: v[1],
                        low: v[2],
                        high: v[3],
                    },
                    DispersionKind::LogNormal => Component::LogNormal {
                        mu: v[0],
                        sigma: v[1],
                    },
                }
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
                // the moments of these two are closed forms of their own (the truncated
                // normal's from the density at its ends): the sampler must meet them
                Component::TruncatedNormal {
                    mean: 225.0,
                    std: 5.0,
                    low: 215.0,
                    high: 228.0,
                },
                Component::LogNormal {
                    mu: 0.1,
                    sigma: 0.2,
                },
            ],
        };
        let n = 20_000;
        let all = d.sample(3, 0, n);
        let mut parts = d.sample(3, 0, 7);
        parts.extend(d.sample(3, 7, n - 7));
        assert_eq!(all, parts);
        for (j, c) in d.components.iter().enumerate() {
            let col: Vec<f64> = all.iter().skip(j).step_by(d.dim()).copied().collect();
            let mean = col.iter().sum::<f64>() / n as f64;
            let sd = (col.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
            let (m, s) = c.moments();
            assert!(
                (mean - m).abs() <= 4.0 * s / (n as f64).sqrt() + 1e-12,
                "{j}: {mean} vs {m}"
            );
            assert!((sd - s).abs() <= 0.03 * s + 1e-12, "{j}: {sd} vs {s}");
        }
        let u: Vec<f64> = all.iter().skip(1).step_by(d.dim()).copied().collect();
        assert!(u.iter().all(|&x| (-15.0..=45.0).contains(&x)));
        let t: Vec<f64> = all.iter().skip(3).step_by(d.dim()).copied().collect();
        assert!(t.iter().all(|&x| (215.0..=228.0).contains(&x)));
    }
}
