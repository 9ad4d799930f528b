//! `simulate_batch`: compiled handles and initial states in, a batch run with the GIL released,
//! numpy arrays out.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

use landing_core::batch::{Batch, RunOptions, RunRequest, run};
use landing_core::control::AnyLaw;
use landing_core::disturbance::Disturbance as CoreDisturbance;
use landing_core::external::{
    ExternalError, ExternalLaw, ExternalPlant, Inputs, Laws, StateLayout, run_external,
    run_external_plant,
};
use landing_core::limits::{MAX_CASES, within_cap};
use landing_core::params::{AxisCount, ByAxes, Dim, ReadFor};
use landing_core::plant::PlantModel;
use landing_core::reference::Reference as CoreReference;
use landing_core::registry::{PlantVisitor, initial_states};
use landing_core::rollout::MAX_DIAGNOSTIC_WIDTH;
use landing_core::{BatchOutput, PerCase, SimConfig, with_axes};

use crate::errors::{InputError, axes_error, batch_error, guard, internal_error};
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
    handed: Handed,
}

/// The (N, width) arrays handed to Python at every call, reused from one call to the next: a
/// fresh array at every call faults its pages in again (a quarter of a Python law's time at
/// 10^4 cases). An array the callee kept a reference to (in its memory, a view of it) is left
/// to it, and replaced by a new one.
#[derive(Default)]
struct Handed {
    slots: Vec<Option<Py<PyArray2<f64>>>>,
}

impl Handed {
    /// Slot `slot`'s array, holding `values` (`n x width`, row-major).
    fn array<'py>(
        &mut self,
        py: Python<'py>,
        slot: usize,
        values: &[f64],
        n: usize,
    ) -> Bound<'py, PyAny> {
        let width = values.len() / n;
        if self.slots.len() <= slot {
            self.slots.resize_with(slot + 1, || None);
        }
        let held = &mut self.slots[slot];
        // SAFETY: a plain reference count read of a live object, with the GIL held
        let ours = |a: &Py<PyArray2<f64>>| unsafe { pyo3::ffi::Py_REFCNT(a.as_ptr()) } == 1;
        if !held
            .as_ref()
            .is_some_and(|a| ours(a) && a.bind(py).shape() == [n, width])
        {
            *held = Some(PyArray2::zeros(py, [n, width], false).unbind());
        }
        let a = held.as_ref().expect("set above").bind(py);
        // SAFETY: a C-contiguous (n, width) float64 array that only this slot holds (its count
        // is one, or it was just made), so no Python code sees the write; numpy's read-only
        // flag, which the Python layer sets, guards Python's writes, not this one
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), a.data(), values.len()) };
        a.clone().into_any()
    }
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
        let handed = &mut self.handed;
        Python::attach(|py| {
            let fields = [
                &inputs.e,
                &inputs.de,
                &inputs.position,
                &inputs.velocity,
                &inputs.acceleration,
                &inputs.drift,
                &inputs.inertia,
            ];
            let mut items = vec![
                inputs.t.into_pyobject(py)?.into_any(),
                inputs.k.into_pyobject(py)?.into_any(),
            ];
            for (slot, v) in fields.into_iter().enumerate() {
                items.push(handed.array(py, slot, v, n));
            }
            let args = PyTuple::new(py, items)?;
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

/// A batch's outcome under a law or on a plant computed in Python: their exceptions as raised.
fn outcome<const D: usize>(
    r: Result<BatchOutput<D>, ExternalError<PyErr>>,
) -> PyResult<BatchOutput<D>> {
    match r {
        Ok(out) => Ok(out),
        Err(ExternalError::Batch(e)) => Err(batch_error(e)),
        Err(ExternalError::Law(e) | ExternalError::Plant(e)) => Err(e),
    }
}

/// What computes the commands of a batch with D axes: the compiled law's cases, or the Python
/// law's adapter.
enum Commands<const D: usize> {
    Builtin(PerCase<AnyLaw<D>>),
    Python(PyLaw),
}

/// What every batch needs beside its plant, read for D axes.
struct Parts<const D: usize> {
    references: PerCase<CoreReference<D>>,
    disturbances: PerCase<CoreDisturbance<D>>,
    commands: Commands<D>,
    /// The names and widths of the law's diagnostic signals.
    layout: Vec<(String, usize)>,
}

impl<'py> Simulate<'_, 'py> {
    /// The reference, the disturbance and the law for D axes, each checked against the cases.
    fn parts<const D: usize>(&self) -> PyResult<Parts<D>>
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
        let (commands, layout) = match &self.control {
            Control::Builtin(law) => {
                let laws: PerCase<AnyLaw<D>> =
                    for_cases(&law.compiled, &format!("controller ({})", law.kind), n)?;
                let named = laws.get(0).diagnostic_layout();
                let layout = named.into_iter().map(|(name, w)| (name.to_string(), w));
                (Commands::Builtin(laws), layout.collect())
            }
            Control::Python { step, layout } => {
                let width: usize = layout.iter().map(|(_, w)| w).sum();
                if width > MAX_DIAGNOSTIC_WIDTH {
                    let most = MAX_DIAGNOSTIC_WIDTH;
                    let msg = format!("diagnostics take {width} values per case; at most {most}");
                    return Err(InputError::value(msg).into());
                }
                let step = (*step).clone().unbind();
                let handed = Handed::default();
                (
                    Commands::Python(PyLaw {
                        step,
                        width,
                        n,
                        handed,
                    }),
                    layout.clone(),
                )
            }
        };
        Ok(Parts {
            references,
            disturbances,
            commands,
            layout,
        })
    }

    /// Runs the batch on a plant written in Python (`landing.plants.PythonPlant`: its `_hooks`
    /// and `_layout`, see [`PyPlant`]) with D axes.
    fn python_plant<const D: usize>(self, mut plant: PyPlant<D>) -> PyResult<Bound<'py, PyDict>>
    where
        Dim<D>: AxisCount<D>,
    {
        let Parts {
            references,
            disturbances,
            mut commands,
            layout,
        } = self.parts::<D>()?;
        let cancel = AtomicBool::new(false);
        let options = RunOptions {
            cancel: Some(&cancel),
            ..self.options
        };
        let (cfg, x0) = (self.cfg, self.x0);
        let laws = match &mut commands {
            Commands::Builtin(l) => Laws::Builtin(l),
            Commands::Python(l) => Laws::External(l),
        };
        let job = Box::new(|| {
            run_external_plant(
                &mut plant,
                laws,
                x0,
                &references,
                &disturbances,
                &cfg,
                &options,
            )
        });
        let out = outcome(detached(self.py, u128::MAX, &cancel, job)?)?;
        let parts = output::Parts {
            out,
            state_names: &[],
            control_names: &[],
            layout,
        };
        output::to_dict(self.py, parts)
    }
}

impl<'py> PlantVisitor for Simulate<'_, 'py> {
    type Output = PyResult<Bound<'py, PyDict>>;

    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output
    where
        Dim<D>: AxisCount<D>,
    {
        let n = self.n;
        let Parts {
            references,
            disturbances,
            commands,
            layout,
        } = self.parts::<D>()?;
        let x0 = initial_states(plants, self.x0).map_err(InputError::from)?;
        let cfg = self.cfg;
        let cancel = AtomicBool::new(false);
        let options = RunOptions {
            cancel: Some(&cancel),
            ..self.options
        };
        let work = (n as u128) * u128::from(cfg.steps) * u128::from(cfg.substeps);
        let plants = plants.clone();
        let out = match commands {
            Commands::Builtin(laws) => {
                let batch = Batch {
                    plants,
                    laws,
                    references,
                    disturbances,
                    x0,
                };
                let job = Box::new(|| run(&batch, &cfg, &options));
                detached(self.py, work, &cancel, job)?.map_err(batch_error)?
            }
            Commands::Python(mut law) => {
                let batch = Batch {
                    plants,
                    laws: (),
                    references,
                    disturbances,
                    x0,
                };
                // always interruptible: every call of the law takes the GIL, so even a short
                // horizon may run long
                let job = Box::new(|| run_external(&batch, &cfg, &options, &mut law));
                outcome(detached(self.py, u128::MAX, &cancel, job)?)?
            }
        };
        let parts = output::Parts {
            out,
            state_names: P::STATE_NAMES,
            control_names: P::CONTROL_NAMES,
            layout,
        };
        output::to_dict(self.py, parts)
    }
}

/// A plant written in Python, as the core's [`ExternalPlant`]: `landing.plants.PythonPlant`
/// hands over its hooks `(derivative, model, actuate, in_domain)`, each None but the first when
/// absent, and each called as `f(t, *arrays)` on (N, width) float64 arrays (`derivative(t, x,
/// u)`, `model(t, x)`, `actuate(t, x, a)`, `in_domain(t, x)`) to return one C-contiguous
/// float64 array (N, n_state), (N, 2 D): drifts then inertias, (N, D), (N, 1): 1 inside.
struct PyPlant<const D: usize> {
    layout: StateLayout<D>,
    hooks: [Option<Py<PyAny>>; 4],
    n: usize,
    handed: Handed,
}

impl<const D: usize> PyPlant<D> {
    /// Hook `i` on `args`, its result into `out` (`n x width`).
    fn call(&mut self, i: usize, t: f64, args: &[&[f64]], out: &mut [f64]) -> PyResult<()> {
        let what = ["derivative", "model", "actuate", "in_domain"][i];
        let f = self.hooks[i]
            .as_ref()
            .ok_or_else(|| InputError::value(format!("the plant has no {what} to call")))?;
        let (n, handed) = (self.n, &mut self.handed);
        Python::attach(|py| {
            let mut items = vec![t.into_pyobject(py)?.into_any()];
            for (j, a) in args.iter().enumerate() {
                // two slots per hook: its arguments after t
                items.push(handed.array(py, 2 * i + j, a, n));
            }
            let r: PyReadonlyArray2<'_, f64> =
                f.bind(py).call1(PyTuple::new(py, items)?)?.extract()?;
            copy_rows(what, &r, n, out.len() / n, out)
        })
    }
}

impl<const D: usize> ExternalPlant<D> for PyPlant<D> {
    type Error = PyErr;

    fn layout(&self) -> &StateLayout<D> {
        &self.layout
    }

    fn hooks(&self) -> [bool; 3] {
        [1, 2, 3].map(|i| self.hooks[i].is_some())
    }

    fn derivative(&mut self, t: f64, x: &[f64], u: &[f64], xdot: &mut [f64]) -> PyResult<()> {
        self.call(0, t, &[x, u], xdot)
    }

    fn model(&mut self, t: f64, x: &[f64], model: &mut [f64]) -> PyResult<()> {
        self.call(1, t, &[x], model)
    }

    fn actuate(&mut self, t: f64, x: &[f64], a: &[f64], u: &mut [f64]) -> PyResult<()> {
        self.call(2, t, &[x, a], u)
    }

    fn in_domain(&mut self, t: f64, x: &[f64], inside: &mut [f64]) -> PyResult<()> {
        self.call(3, t, &[x], inside)
    }
}

/// A Python plant's hooks and layout, `(n_state, positions, velocities, mass, altitude)`.
type PlantSpec = (
    [Option<Py<PyAny>>; 4],
    (usize, Vec<usize>, Vec<usize>, Option<usize>, Option<usize>),
);

/// See `landing.simulate_batch` for the documentation: `controller` is a compiled law, or a
/// Python callable `step` (see [`PyLaw`]) with `diagnostic_layout`, the names and widths of its
/// diagnostic signals. A panic anywhere below arrives as a `SimulationError` (see [`guard`]);
/// an exception `step` raises stops the batch and is raised as it is.
#[pyfunction]
#[pyo3(signature = (plant, controller, x0, *, t_final, dt, integrator, substeps, reference, disturbance, record_every, seed, first_case, settle_tolerance, settle_relative, chatter_cutoff, threads, kernel=None, stop_at=None, diagnostic_layout=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_batch<'py>(
    py: Python<'py>,
    plant: &Bound<'py, PyAny>,
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
    stop_at: Option<&str>,
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
            stop_at,
        };
        let (cfg, options) = request.compile().map_err(InputError::from)?;
        let compiled = plant.cast::<Plant>().ok().map(|p| p.borrow());
        let spec: Option<PlantSpec> = match &compiled {
            Some(_) => None,
            None => Some((
                plant.getattr("_hooks")?.extract()?,
                plant.getattr("_layout")?.extract()?,
            )),
        };
        let width = match (&compiled, &spec) {
            (Some(p), _) => p.plants.info().state_names.len(),
            (None, Some((_, layout))) => layout.0,
            (None, None) => unreachable!("a plant is compiled or has a spec"),
        };
        let [n, columns] = [x0.shape()[0], x0.shape()[1]];
        if columns != width || n == 0 {
            let msg =
                format!("x0 has shape ({n}, {columns}); this plant takes (N, {width}), N >= 1");
            return Err(InputError::value(msg).into());
        }
        within_cap("x0 cases N", n as u64, "max_cases", MAX_CASES).map_err(InputError::from)?;
        let simulate = Simulate {
            py,
            control,
            reference: reference.as_deref(),
            disturbance: disturbance.as_deref(),
            x0: x0.as_slice()?,
            n,
            cfg,
            options,
        };
        match (compiled, spec) {
            (Some(p), _) => {
                let owner = format!("plant ({})", p.kind);
                p.cases.check(&owner, n).map_err(InputError::from)?;
                p.plants.visit(simulate)
            }
            (None, Some((hooks, (dim, positions, velocities, mass, altitude)))) => {
                with_axes!(positions.len(), D => {
                    let layout = StateLayout::<D>::new(dim, &positions, &velocities, mass, altitude)
                        .map_err(InputError::from)?;
                    simulate.python_plant(PyPlant { layout, hooks, n, handed: Handed::default() })
                }, a => Err(axes_error(a).into()))
            }
            (None, None) => unreachable!("a plant is compiled or has a spec"),
        }
    })
}
