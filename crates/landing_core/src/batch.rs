//! Many cases at once, in parallel on rayon.
//!
//! Cases are independent and each draws its random numbers from streams keyed by its own
//! index, so the output is bit-identical whatever the thread count or the way rayon splits the
//! work. Output buffers are allocated once, up front, and handed out as disjoint per-case slices.

use rayon::prelude::*;

use crate::control::ControlLaw;
use crate::disturbance::Disturbance;
use crate::integrator::Integrator;
use crate::metrics::CaseMetrics;
use crate::plant::Plant;
use crate::reference::Reference;
use crate::rollout::{CaseBuffers, SimConfig, rollout};
use crate::state::State;

/// A value shared by every case, or one per case.
#[derive(Clone, Debug)]
pub struct PerCase<T>(Vec<T>);

impl<T> PerCase<T> {
    pub fn shared(value: T) -> Self {
        Self(vec![value])
    }

    /// One value per case; a single value is shared.
    pub fn from_vec(values: Vec<T>) -> Self {
        Self(values)
    }

    #[inline(always)]
    pub fn get(&self, case: usize) -> &T {
        &self.0[if self.0.len() == 1 { 0 } else { case }]
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    pub fn iter(&self) -> impl Iterator<Item = &T> {
        self.0.iter()
    }
}

/// Everything that varies between the cases of a batch.
pub struct Batch<const D: usize, P: Plant<D>, L: ControlLaw<D>> {
    pub plants: PerCase<P>,
    pub laws: PerCase<L>,
    pub references: PerCase<Reference<D>>,
    pub disturbances: PerCase<Disturbance<D>>,
    pub x0: Vec<P::State>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum BatchError {
    /// A per-case table whose length is neither 1 nor the number of cases.
    Length {
        what: &'static str,
        len: usize,
        cases: usize,
    },
    /// The recording would not fit in memory.
    Allocation { bytes: u128 },
    /// The requested thread pool could not be built.
    ThreadPool(String),
}

impl std::fmt::Display for BatchError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Length { what, len, cases } => {
                write!(
                    f,
                    "{what} has {len} entries for {cases} cases; give 1 or {cases}"
                )
            }
            Self::Allocation { bytes } => write!(
                f,
                "the recording needs {:.1} GiB; record fewer instants (record_every) or fewer cases",
                *bytes as f64 / (1u64 << 30) as f64
            ),
            Self::ThreadPool(e) => write!(f, "could not start the thread pool: {e}"),
        }
    }
}

impl std::error::Error for BatchError {}

/// The recording and metrics of a batch, in flat row-major buffers.
#[derive(Debug, Clone)]
pub struct BatchOutput<const D: usize> {
    pub n_cases: usize,
    pub state_dim: usize,
    pub diagnostic_dim: usize,
    /// Recorded instants (length n_records).
    pub times: Vec<f64>,
    /// n_cases x n_records x state_dim.
    pub states: Vec<f64>,
    /// n_cases x n_records x D: the applied (saturated) commands.
    pub controls: Vec<f64>,
    /// n_cases x n_records x diagnostic_dim.
    pub diagnostics: Vec<f64>,
    /// n_cases x state_dim.
    pub final_state: Vec<f64>,
    pub metrics: Vec<CaseMetrics<D>>,
}

impl<const D: usize> BatchOutput<D> {
    pub fn n_records(&self) -> usize {
        self.times.len()
    }
}

fn zeroed(len: usize) -> Result<Vec<f64>, BatchError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| BatchError::Allocation {
            bytes: len as u128 * 8,
        })?;
    v.resize(len, 0.0);
    Ok(v)
}

/// `len`-sized disjoint chunks for `n` cases (empty slices when `len` is 0).
fn chunks(buf: &mut [f64], len: usize, n: usize) -> Vec<&mut [f64]> {
    if len == 0 {
        (0..n).map(|_| -> &mut [f64] { &mut [] }).collect()
    } else {
        buf.chunks_mut(len).collect()
    }
}

/// Runs every case of the batch on the current rayon pool.
pub fn run<const D: usize, P, L, I>(
    batch: &Batch<D, P, L>,
    integrator: I,
    cfg: &SimConfig,
) -> Result<BatchOutput<D>, BatchError>
where
    P: Plant<D>,
    L: ControlLaw<D>,
    I: Integrator,
{
    let n = batch.x0.len();
    for (what, len) in [
        ("plant", batch.plants.len()),
        ("controller", batch.laws.len()),
        ("reference", batch.references.len()),
        ("disturbance", batch.disturbances.len()),
    ] {
        if len != 1 && len != n {
            return Err(BatchError::Length {
                what,
                len,
                cases: n,
            });
        }
    }
    let nx = P::State::DIM;
    let nd = crate::control::diagnostic_width::<D, L>();
    let nr = cfg.n_records();
    let total = (n as u128) * (nr as u128) * ((nx + D + nd) as u128) * 8;
    if total > isize::MAX as u128 {
        return Err(BatchError::Allocation { bytes: total });
    }
    let mut states = zeroed(n * nr * nx)?;
    let mut controls = zeroed(n * nr * D)?;
    let mut diagnostics = zeroed(n * nr * nd)?;
    let mut final_state = zeroed(n * nx)?;

    let jobs: Vec<_> = chunks(&mut states, nr * nx, n)
        .into_iter()
        .zip(chunks(&mut controls, nr * D, n))
        .zip(chunks(&mut diagnostics, nr * nd, n))
        .zip(chunks(&mut final_state, nx, n))
        .enumerate()
        .collect();
    let metrics: Vec<CaseMetrics<D>> = jobs
        .into_par_iter()
        .map(|(i, (((s, c), d), f))| {
            rollout(
                batch.plants.get(i),
                batch.laws.get(i),
                integrator,
                &batch.x0[i],
                batch.references.get(i),
                batch.disturbances.get(i),
                cfg,
                cfg.first_case + i as u64,
                CaseBuffers {
                    states: s,
                    controls: c,
                    diagnostics: d,
                    final_state: f,
                },
            )
        })
        .collect();

    Ok(BatchOutput {
        n_cases: n,
        state_dim: nx,
        diagnostic_dim: nd,
        times: cfg.record_times(),
        states,
        controls,
        diagnostics,
        final_state,
        metrics,
    })
}

/// [`run`] on a pool of `threads` threads, or on rayon's global pool for `None`.
pub fn run_with_threads<const D: usize, P, L, I>(
    batch: &Batch<D, P, L>,
    integrator: I,
    cfg: &SimConfig,
    threads: Option<usize>,
) -> Result<BatchOutput<D>, BatchError>
where
    P: Plant<D>,
    L: ControlLaw<D>,
    I: Integrator,
{
    match threads {
        None => run(batch, integrator, cfg),
        Some(k) => rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .map_err(|e| BatchError::ThreadPool(e.to_string()))?
            .install(|| run(batch, integrator, cfg)),
    }
}
