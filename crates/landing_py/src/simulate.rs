//! `simulate_batch`: compiled handles and initial states in, a batch run with the GIL released,
//! numpy arrays out.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use landing_core::batch::{Batch, RunOptions, RunRequest, run};
use landing_core::disturbance::Disturbance as CoreDisturbance;
use landing_core::external::{ExternalError, ExternalLaw, Inputs, run_external};
use landing_core::limits::{MAX_CASES, within_cap};
use landing_core::params::{AxisCount, ByAxes, Dim, ReadFor};
use landing_core::plant::PlantModel;
use landing_core::reference::Reference as CoreReference;
use landing_core::registry::{PlantVisitor, initial_states};
use landing_core::rollout::MAX_DIAGNOSTIC_WIDTH;
use landing_core::{PerCase, SimConfig};

use crate::errors::{InputError, batch_error, guard, internal_error};
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

/// What computes the commands: a compiled law, or a Python callable called once per control
/// instant on every case ([`PyLaw`]).
enum Control<'a, 'py> {
    Builtin(&'a Law),
    Python {
        step: &'a Bound<'py, PyAny>,
        layout: Vec<(String, usize)>,
    },
}

/// A Python callable as the core's [`ExternalLaw`]: `step(t, k, e, de, position, velocity,
/// acceleration, drift, inertia)`, each an (N, D) float64 array but the instant `t` and its
/// index `k`, returns `(command, diagnostics)`, float64 arrays of shapes (N, D) and (N,
/// width), C-contiguous. The Python layer (`landing.controllers.PythonLaw`) checks what the
/// user's function returns and makes it so; the shapes are checked again here, because a wrong
/// one would be read out of bounds.
struct PyLaw {
    step: Py<PyAny>,
    width: usize,
    n: usize,
}

impl<const D: usize> ExternalLaw<D> for PyLaw {
    type Error = PyErr;

    fn diagnostic_width(&self) -> usize {
        self.width
    }

    fn command(
        &mut self,
        inputs: &Inputs<D>,
        command: &mut [f64],
        diagnostics: &mut [f64],
    ) -> PyResult<()> {
        let n = self.n;
        Python::attach(|py| {
            let rows = |v: &[f64]| -> PyResult<Bound<'_, PyAny>> {
                Ok(PyArray1::from_slice(py, v).reshape([n, D])?.into_any())
            };
            let args = PyTuple::new(
                py,
                [
                    inputs.t.into_pyobject(py)?.into_any(),
                    inputs.k.into_pyobject(py)?.into_any(),
                    rows(&inputs.e)?,
                    rows(&inputs.de)?,
                    rows(&inputs.position)?,
                    rows(&inputs.velocity)?,
                    rows(&inputs.acceleration)?,
                    rows(&inputs.drift)?,
                    rows(&inputs.inertia)?,
                ],
            )?;
            let out = self.step.bind(py).call1(args)?;
            let (u, diag): (PyReadonlyArray2<'_, f64>, PyReadonlyArray2<'_, f64>) =
                out.extract()?;
            copy_rows("command", &u, n, D, command)?;
            copy_rows("diagnostics", &diag, n, self.width, diagnostics)
        })
    }
}

/// Copies a C-contiguous (n, width) array into `into`, or an error naming it.
fn copy_rows(
    what: &str,
    a: &PyReadonlyArray2<'_, f64>,
    n: usize,
    width: usize,
    into: &mut [f64],
) -> PyResult<()> {
    if a.shape() != [n, width] {
        return Err(InputError::value(format!(
            "the Python law's step returned {what} of shape {:?}; expected ({n}, {width})",
            a.shape()
        ))
        .into());
    }
    into.copy_from_slice(a.as_slice()?);
    Ok(())
}

/// Builds the batch for the plant's type and runs it without the GIL.
struct Simulate<'a, 'py> {
    py: Python<'py>,
    control: Control<'a, 'py>,
    reference: Option<&'a Reference>,
    disturbance: Option<&'a Disturbance>,
    x0: &'a [f64],
    n: usize,
    cfg: SimConfig,
    options: RunOptions<'static>,
}

/// Runs `job` without the GIL, interruptibly when it is large (see [`interruptible`]), catching
/// its panics; boxed, so that this machinery is compiled once per output type, not per plant.
fn detached<T: Send>(
    py: Python<'_>,
    work: u128,
    cancel: &AtomicBool,
    job: Box<dyn FnOnce() -> T + Send + '_>,
) -> PyResult<T> {
    let result = py.detach(|| {
        let job = || catch_unwind(AssertUnwindSafe(job));
        if work < INTERRUPTIBLE_WORK {
            Ok(job())
        } else {
            interruptible(cancel, job)
        }
    });
    result?.map_err(internal_error)
}

/// The reading of a law, a reference or a disturbance for D axes, if it fits `n` cases.
fn for_cases<M: ReadFor, const D: usize>(
    compiled: &ByAxes<M>,
    owner: &str,
    n: usize,
) -> Result<PerCase<M::At<D>>, InputError>
where
    Dim<D>: AxisCount<D>,
{
    let (models, cases) = compiled.get::<D>()?;
    cases.check(owner, n)?;
    Ok(models.clone())
}

impl<'py> PlantVisitor for Simulate<'_, 'py> {
    type Output = PyResult<Bound<'py, PyDict>>;

    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output
    where
        Dim<D>: AxisCount<D>,
    {
        let n = self.n;
        let references = match self.reference {
            None => PerCase::shared(CoreReference::default()),
            Some(r) => for_cases(&r.compiled, "reference", n)?,
        };
        let disturbances = match self.disturbance {
            None => PerCase::shared(CoreDisturbance::none()),
            Some(d) => for_cases(&d.compiled, "disturbance", n)?,
        };
        let x0 = initial_states(plants, self.x0).map_err(InputError::from)?;
        let cfg = self.cfg;
        let cancel = AtomicBool::new(false);
        let options = RunOptions {
            cancel: Some(&cancel),
            ..self.options
        };
        let work = (n as u128) * u128::from(cfg.steps) * u128::from(cfg.substeps);
        let (out, layout) = match self.control {
            Control::Builtin(law) => {
                let laws = for_cases(&law.compiled, &format!("controller ({})", law.kind), n)?;
                let layout = laws
                    .get(0)
                    .diagnostic_layout()
                    .into_iter()
                    .map(|(name, width)| (name.to_string(), width))
                    .collect();
                let batch = Batch {
                    plants: plants.clone(),
                    laws,
                    references,
                    disturbances,
                    x0,
                };
                let job = Box::new(|| run(&batch, &cfg, &options));
                let out = detached(self.py, work, &cancel, job)?.map_err(batch_error)?;
                (out, layout)
            }
            Control::Python { step, layout } => {
                let width = layout.iter().map(|(_, w)| w).sum();
                if width > MAX_DIAGNOSTIC_WIDTH {
                    return Err(InputError::value(format!(
                        "diagnostics take {width} values per case; at most {MAX_DIAGNOSTIC_WIDTH}"
                    ))
                    .into());
                }
                let batch = Batch {
                    plants: plants.clone(),
                    laws: (),
                    references,
                    disturbances,
                    x0,
                };
                let mut law = PyLaw {
                    step: step.clone().unbind(),
                    width,
                    n,
                };
                // always interruptible: every call of the law takes the GIL, so even a short
                // horizon may run long
                let job = Box::new(|| run_external(&batch, &cfg, &options, &mut law));
                let result = detached(self.py, u128::MAX, &cancel, job)?;
                let out = match result {
                    Ok(out) => out,
                    Err(ExternalError::Batch(e)) => return Err(batch_error(e)),
                    Err(ExternalError::Law(e)) => return Err(e),
                };
                (out, layout)
            }
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

/// See `landing.simulate_batch` for the documentation: `controller` is a compiled law, or a
/// Python callable `step` (see [`PyLaw`]) with `diagnostic_layout`, the names and widths of its
/// diagnostic signals. A panic anywhere below arrives as a `SimulationError` (see [`guard`]);
/// an exception `step` raises stops the batch and is raised as it is.
#[pyfunction]
#[pyo3(signature = (plant, controller, x0, *, t_final, dt, integrator, substeps, reference, disturbance, record_every, seed, first_case, settle_tolerance, settle_relative, chatter_cutoff, threads, kernel=None, diagnostic_layout=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_batch<'py>(
    py: Python<'py>,
    plant: &Plant,
    controller: &Bound<'py, PyAny>,
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
    diagnostic_layout: Option<Vec<(String, usize)>>,
) -> PyResult<Bound<'py, PyDict>> {
    guard(move || {
        let law = controller.cast::<Law>().ok().map(|l| l.borrow());
        let control = match (&law, diagnostic_layout) {
            (Some(law), None) => Control::Builtin(law),
            (None, Some(layout)) if controller.is_callable() => Control::Python {
                step: controller,
                layout,
            },
            _ => {
                let rule = "a compiled law, or a callable with its diagnostic_layout";
                return Err(InputError::value(format!("controller must be {rule}")).into());
            }
        };
        let request = RunRequest {
            t_final,
            dt,
            integrator,
            substeps,
            record_every,
            seed,
            first_case,
            settle_tolerance,
            settle_relative,
            chatter_cutoff,
            threads,
            kernel,
        };
        let (cfg, options) = request.compile().map_err(InputError::from)?;
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
        within_cap("x0 cases N", n as u64, "max_cases", MAX_CASES).map_err(InputError::from)?;
        plant
            .cases
            .check(&format!("plant ({})", plant.kind), n)
            .map_err(InputError::from)?;
        plant.plants.visit(Simulate {
            py,
            control,
            reference: reference.as_deref(),
            disturbance: disturbance.as_deref(),
            x0: x0.as_slice()?,
            n,
            cfg,
            options,
        })
    })
}
