//! `simulate_batch`: compiled handles and initial states in, a batch run with the GIL released,
//! numpy arrays out.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::batch::{Batch, RunOptions, run};
use landing_core::disturbance::Disturbance as CoreDisturbance;
use landing_core::integrator::IntegratorKind;
use landing_core::limits::{MAX_CASES, MAX_SUBSTEPS, MAX_THREADS};
use landing_core::params::{AxisCount, Dim, Named};
use landing_core::plant::PlantModel;
use landing_core::reference::Reference as CoreReference;
use landing_core::registry::{PlantVisitor, initial_states};
use landing_core::{Level, PerCase, SimConfig, Tolerance};

use crate::errors::{InputError, batch_error, guard, internal_error, within_cap};
use crate::laws::Law;
use crate::output;
use crate::plants::Plant;
use crate::signals::{Disturbance, Reference};

/// Batches of fewer integrator steps than this (cases x periods x substeps) run on the calling
/// thread and cannot be interrupted: they take milliseconds. Larger ones run on a scoped
/// thread while the calling thread watches for signals ([`interruptible`]).
const INTERRUPTIBLE_WORK: u128 = 1 << 17;

/// How often the calling thread lets Python run its signal handlers during a batch.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `job` on a scoped thread while this thread, every [`SIGNAL_POLL`], takes the GIL and
/// lets Python run its signal handlers. When a handler raises (Ctrl-C: KeyboardInterrupt),
/// `cancel` is raised, the batch stops at its blocks' next poll (milliseconds), and the
/// handler's exception is returned; nothing of the batch is kept. Called without the GIL.
fn interruptible<T: Send>(cancel: &AtomicBool, job: impl FnOnce() -> T + Send) -> PyResult<T> {
    let watcher = std::thread::current();
    std::thread::scope(|scope| {
        let worker = scope.spawn(move || {
            let out = job();
            watcher.unpark();
            out
        });
        let mut raised = None;
        while !worker.is_finished() {
            std::thread::park_timeout(SIGNAL_POLL);
            if raised.is_none()
                && !worker.is_finished()
                && let Err(e) = Python::attach(|py| py.check_signals())
            {
                cancel.store(true, Ordering::Relaxed);
                raised = Some(e);
            }
        }
        // the job catches its own panics, so the thread cannot have panicked
        let out = worker
            .join()
            .expect("the batch's panics are caught inside it");
        match raised {
            Some(e) => Err(e),
            None => Ok(out),
        }
    })
}

/// Builds the batch for the plant's type and runs it without the GIL.
struct Simulate<'a, 'py> {
    py: Python<'py>,
    law: &'a Law,
    reference: Option<&'a Reference>,
    disturbance: Option<&'a Disturbance>,
    x0: &'a [f64],
    n: usize,
    cfg: SimConfig,
    options: RunOptions<'static>,
}

impl<'py> PlantVisitor for Simulate<'_, 'py> {
    type Output = PyResult<Bound<'py, PyDict>>;

    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output
    where
        Dim<D>: AxisCount<D>,
    {
        let n = self.n;
        let (laws, law_cases) = self.law.compiled.get::<D>().map_err(InputError::from)?;
        let owner = format!("controller ({})", self.law.kind);
        law_cases.check(&owner, n).map_err(InputError::from)?;
        let references = match self.reference {
            None => PerCase::shared(CoreReference::default()),
            Some(r) => {
                let (refs, cases) = r.compiled.get::<D>().map_err(InputError::from)?;
                cases.check("reference", n).map_err(InputError::from)?;
                refs.clone()
            }
        };
        let disturbances = match self.disturbance {
            None => PerCase::shared(CoreDisturbance::none()),
            Some(d) => {
                let (ds, cases) = d.compiled.get::<D>().map_err(InputError::from)?;
                cases.check("disturbance", n).map_err(InputError::from)?;
                ds.clone()
            }
        };
        let x0 = initial_states(plants, self.x0).map_err(InputError::from)?;
        let batch = Batch {
            plants: plants.clone(),
            laws: laws.clone(),
            references,
            disturbances,
            x0,
        };
        let layout = laws.get(0).diagnostic_layout();
        let cfg = self.cfg;
        let cancel = AtomicBool::new(false);
        let options = RunOptions {
            cancel: Some(&cancel),
            ..self.options
        };
        let work = (n as u128) * u128::from(cfg.steps) * u128::from(cfg.substeps);
        let result = self.py.detach(|| {
            let job = || catch_unwind(AssertUnwindSafe(|| run(&batch, &cfg, &options)));
            if work < INTERRUPTIBLE_WORK {
                Ok(job())
            } else {
                interruptible(&cancel, job)
            }
        });
        let out = match result? {
            Ok(Ok(out)) => out,
            Ok(Err(e)) => return Err(batch_error(e)),
            Err(panic) => return Err(internal_error(panic)),
        };
        output::to_dict(
            self.py,
            output::Parts {
                out,
                state_names: P::STATE_NAMES,
                control_names: P::CONTROL_NAMES,
                layout,
            },
        )
    }
}

/// See `landing.simulate_batch` for the documentation. A panic anywhere below arrives as a
/// `SimulationError` (see [`guard`]).
#[pyfunction]
#[pyo3(signature = (plant, controller, x0, *, t_final, dt, integrator, substeps, reference, disturbance, record_every, seed, first_case, settle_tolerance, settle_relative, chatter_cutoff, threads, kernel=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_batch<'py>(
    py: Python<'py>,
    plant: &Plant,
    controller: &Law,
    x0: PyReadonlyArray2<'py, f64>,
    t_final: f64,
    dt: f64,
    integrator: &str,
    substeps: i64,
    reference: Option<PyRef<'py, Reference>>,
    disturbance: Option<PyRef<'py, Disturbance>>,
    record_every: i64,
    seed: u64,
    first_case: u64,
    settle_tolerance: f64,
    settle_relative: bool,
    chatter_cutoff: Option<f64>,
    threads: Option<i64>,
    kernel: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    guard(move || {
        let integ = IntegratorKind::from_name(integrator).ok_or_else(|| {
            InputError::value(format!(
                "integrator = {integrator:?} is not one of {:?}",
                IntegratorKind::NAMES
            ))
        })?;
        if substeps < 1 {
            return Err(
                InputError::value(format!("substeps = {substeps} violates substeps >= 1")).into(),
            );
        }
        within_cap("substeps", substeps as u64, "max_substeps", MAX_SUBSTEPS)?;
        if record_every < 0 {
            return Err(InputError::value(format!(
                "record_every = {record_every} violates record_every >= 0"
            ))
            .into());
        }
        let threads = match threads {
            None => None,
            Some(k) if k >= 1 => {
                within_cap("threads", k as u64, "max_threads", MAX_THREADS)?;
                Some(k as usize)
            }
            Some(k) => {
                return Err(
                    InputError::value(format!("threads = {k} violates threads >= 1")).into(),
                );
            }
        };
        let level = kernel
            .map(Level::from_name)
            .transpose()
            .map_err(|e| InputError::value(format!("kernel: {e}")))?;
        let cfg = SimConfig::new(t_final, dt, substeps as u32, record_every as u64, seed)
            .map_err(InputError::from)?
            .with_first_case(first_case)
            .with_integrator(integ)
            .with_settle(if settle_relative {
                Tolerance::Relative(settle_tolerance)
            } else {
                Tolerance::Absolute(settle_tolerance)
            })
            .map_err(InputError::from)?;
        let cfg = match chatter_cutoff {
            None => cfg,
            Some(hz) => cfg.with_chatter_cutoff(hz).map_err(InputError::from)?,
        };
        let shape = x0.shape();
        let n = shape[0];
        let names = plant.plants.info().state_names;
        if shape[1] != names.len() || n == 0 {
            return Err(InputError::value(format!(
                "x0 has shape ({}, {}); this plant takes (N, {}) with N >= 1 (state {names:?})",
                shape[0],
                shape[1],
                names.len()
            ))
            .into());
        }
        within_cap("x0 cases N", n as u64, "max_cases", MAX_CASES)?;
        plant
            .cases
            .check(&format!("plant ({})", plant.kind), n)
            .map_err(InputError::from)?;
        plant.plants.visit(Simulate {
            py,
            law: controller,
            reference: reference.as_deref(),
            disturbance: disturbance.as_deref(),
            x0: x0.as_slice()?,
            n,
            cfg,
            options: RunOptions {
                threads,
                level,
                cancel: None,
            },
        })
    })
}
