//! `simulate_batch`: compiled handles (or Python callables) and initial states in, a batch run
//! with the GIL released, numpy arrays out.

use std::sync::atomic::AtomicBool;

use numpy::{PyReadonlyArray2, PyReadwriteArray3, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::batch::{Batch, Lent, RunOptions, RunRequest, check_initial_states, run};
use landing_core::control::AnyLaw;
use landing_core::disturbance::Disturbance as CoreDisturbance;
use landing_core::external::{ExternalError, Laws, StateLayout, run_external, run_external_plant};
use landing_core::interrupt::{Stopped, supervised};
use landing_core::params::{AxisCount, Dim};
use landing_core::plant::PlantModel;
use landing_core::reference::Reference as CoreReference;
use landing_core::registry::{PlantVisitor, initial_states};
use landing_core::rollout::MAX_DIAGNOSTIC_WIDTH;
use landing_core::{BatchOutput, PerCase, SimConfig, with_axes};

use crate::callables::{Handed, PyLaw, PyPlant};
use crate::errors::{InputError, axes_error, batch_error, guard, internal_error, invalid};
use crate::laws::Law;
use crate::output;
use crate::plants::Plant;
use crate::signals::{Disturbance, Reference};

/// Runs `job` without the GIL, watching for Python's signals when it is large (Ctrl-C stops
/// it: `landing_core::interrupt`), its panics as `SimulationError`s; boxed, so that this
/// machinery is compiled once per output type, not per plant.
fn detached<T: Send>(
    py: Python<'_>,
    work: u128,
    cancel: &AtomicBool,
    job: Box<dyn FnOnce() -> T + Send + '_>,
) -> PyResult<T> {
    let signals = || Python::attach(|py| py.check_signals());
    py.detach(|| supervised(work, cancel, signals, job))
        .map_err(|stopped| match stopped {
            Stopped::Interrupted(e) => e,
            Stopped::Panicked(p) => internal_error(p),
        })
}

/// What computes the commands: a compiled law, or a Python callable called once per control
/// instant on every case ([`PyLaw`]) with the names and widths of its diagnostic signals.
enum Control<'a, 'py> {
    Builtin(&'a Law),
    Python(&'a Bound<'py, PyAny>, Vec<(String, usize)>),
}

/// The commands of a batch with D axes: the compiled law's cases, or the Python law.
enum Commands<const D: usize> {
    Builtin(PerCase<AnyLaw<D>>),
    Python(PyLaw),
}

/// What every batch needs beside its plant, read for D axes and checked against the cases.
struct Parts<const D: usize> {
    references: PerCase<CoreReference<D>>,
    disturbances: PerCase<CoreDisturbance<D>>,
    commands: Commands<D>,
}

/// A batch on a compiled plant or a Python plant, before it is read for its axis count.
struct Simulate<'a, 'py> {
    py: Python<'py>,
    control: Control<'a, 'py>,
    reference: Option<&'a Reference>,
    disturbance: Option<&'a Disturbance>,
    x0: &'a [f64],
    n: usize,
    cfg: SimConfig,
    options: RunOptions<'static>,
    /// The arrays the recording is written into, when the caller lends them (`into`).
    lent: Option<[Bound<'py, PyAny>; 3]>,
}

impl<'py> Simulate<'_, 'py> {
    /// Reads the parts for D axes, runs `job` on them without the GIL, cancellable (`work`
    /// integrator steps: see [`detached`]), and hands the output over with the plant's names.
    fn run<const D: usize, J>(
        self,
        names: [&'static [&'static str]; 2],
        work: u128,
        job: J,
    ) -> PyResult<Bound<'py, PyDict>>
    where
        Dim<D>: AxisCount<D>,
        J: FnOnce(Parts<D>, &RunOptions<'_>) -> Result<BatchOutput<D>, ExternalError<PyErr>> + Send,
    {
        let n = self.n;
        let references = match self.reference {
            None => PerCase::shared(CoreReference::default()),
            Some(r) => r
                .compiled
                .for_cases::<D>("reference", n)
                .map_err(InputError::from)?,
        };
        let disturbances = match self.disturbance {
            None => PerCase::shared(CoreDisturbance::none()),
            Some(d) => d
                .compiled
                .for_cases::<D>("disturbance", n)
                .map_err(InputError::from)?,
        };
        let (commands, layout, work) = match self.control {
            Control::Builtin(law) => {
                let owner = format!("controller ({})", law.kind);
                let laws = law
                    .compiled
                    .for_cases::<D>(&owner, n)
                    .map_err(InputError::from)?;
                let named = laws.get(0).diagnostic_layout().into_iter();
                let layout = named.map(|(name, w)| (name.to_string(), w)).collect();
                (Commands::Builtin(laws), layout, work)
            }
            Control::Python(step, layout) => {
                let width: usize = layout.iter().map(|(_, w)| w).sum();
                if width > MAX_DIAGNOSTIC_WIDTH {
                    invalid!(
                        "diagnostics take {width} values per case; at most {MAX_DIAGNOSTIC_WIDTH}"
                    );
                }
                let law = PyLaw {
                    per_call: step.getattr("cases_per_call")?.extract()?,
                    step: step.clone().unbind(),
                    width,
                    handed: Handed::default(),
                };
                // always watched: every call of the law takes the GIL, so even a short
                // horizon may run long
                (Commands::Python(law), layout, u128::MAX)
            }
        };
        let cancel = AtomicBool::new(false);
        let options = RunOptions {
            cancel: Some(&cancel),
            ..self.options
        };
        let parts = Parts {
            references,
            disturbances,
            commands,
        };
        let out = detached(
            self.py,
            work,
            &cancel,
            Box::new(move || job(parts, &options)),
        )?;
        let out = out.map_err(|e| match e {
            ExternalError::Batch(e) => batch_error(e),
            ExternalError::Law(e) | ExternalError::Plant(e) => e,
        })?;
        let [state_names, control_names] = names;
        output::to_dict(
            self.py,
            output::Parts {
                out,
                state_names,
                control_names,
                layout,
                lent: self.lent,
            },
        )
    }

    /// Runs the batch on a plant written in Python (`landing.plants.PythonPlant`: its `_hooks`
    /// and `_layout`, see [`PyPlant`]) with D axes.
    fn python_plant<const D: usize>(self, mut plant: PyPlant<D>) -> PyResult<Bound<'py, PyDict>>
    where
        Dim<D>: AxisCount<D>,
    {
        let (cfg, x0) = (self.cfg, self.x0);
        self.run([&[], &[]], u128::MAX, move |mut p, options| {
            let laws = match &mut p.commands {
                Commands::Builtin(l) => Laws::Builtin(l),
                Commands::Python(l) => Laws::External(l),
            };
            let (references, disturbances) = (&p.references, &p.disturbances);
            run_external_plant(
                &mut plant,
                laws,
                x0,
                references,
                disturbances,
                &cfg,
                options,
            )
        })
    }
}

impl<'py> PlantVisitor for Simulate<'_, 'py> {
    type Output = PyResult<Bound<'py, PyDict>>;

    fn visit<const D: usize, P: PlantModel<D>>(self, plants: &PerCase<P>) -> Self::Output
    where
        Dim<D>: AxisCount<D>,
    {
        let x0 = initial_states(plants, self.x0).map_err(InputError::from)?;
        let (plants, cfg) = (plants.clone(), self.cfg);
        let work = (self.n as u128) * u128::from(cfg.steps) * u128::from(cfg.substeps);
        self.run(
            [P::STATE_NAMES, P::CONTROL_NAMES],
            work,
            move |p, options| {
                let Parts {
                    references,
                    disturbances,
                    commands,
                } = p;
                match commands {
                    Commands::Builtin(laws) => {
                        let batch = Batch {
                            plants,
                            laws,
                            references,
                            disturbances,
                            x0,
                        };
                        Ok(run(&batch, &cfg, options)?)
                    }
                    Commands::Python(mut law) => {
                        let batch = Batch {
                            plants,
                            laws: (),
                            references,
                            disturbances,
                            x0,
                        };
                        run_external(&batch, &cfg, options, &mut law)
                    }
                }
            },
        )
    }
}

/// A Python plant's layout, `(n_state, positions, velocities, mass, altitude)`.
type Layout = (usize, Vec<usize>, Vec<usize>, Option<usize>, Option<usize>);

/// The plant argument: a compiled plant, or a Python plant's `_hooks` and `_layout`.
enum PlantArg<'py> {
    Compiled(PyRef<'py, Plant>),
    Python([Option<Py<PyAny>>; 4], Layout),
}

/// See `landing.simulate_batch` for the documentation: `controller` is a compiled law, or a
/// Python callable `step` (see [`PyLaw`]) with `diagnostic_layout`, the names and widths of its
/// diagnostic signals. A panic anywhere below arrives as a `SimulationError` (see [`guard`]);
/// an exception `step` raises stops the batch and is raised as it is.
#[pyfunction]
#[pyo3(signature = (plant, controller, x0, *, t_final, dt, integrator, substeps, reference, disturbance, record_every, seed, first_case, settle_tolerance, settle_relative, chatter_cutoff, threads, kernel=None, stop_at=None, diagnostic_layout=None, into=None))]
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
    into: Option<Recording<'py>>,
) -> PyResult<Bound<'py, PyDict>> {
    guard(move || {
        let law = controller.cast::<Law>().ok().map(|l| l.borrow());
        let control = match (&law, diagnostic_layout) {
            (Some(law), None) => Control::Builtin(law),
            (None, Some(layout)) if controller.is_callable() => Control::Python(controller, layout),
            _ => invalid!(
                "controller must be a compiled law, or a callable with its diagnostic_layout"
            ),
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
        let (cfg, mut options) = request.compile().map_err(InputError::from)?;
        let mut into = into;
        let lent = match &mut into {
            None => None,
            Some((states, controls, diagnostics)) => {
                options.recording = Some(lend([
                    ("states", states),
                    ("controls", controls),
                    ("diagnostics", diagnostics),
                ])?);
                let array = |a: &PyReadwriteArray3<'py, f64>| a.as_any().clone();
                Some([array(states), array(controls), array(diagnostics)])
            }
        };
        let plant = match plant.cast::<Plant>() {
            Ok(p) => PlantArg::Compiled(p.borrow()),
            Err(_) => PlantArg::Python(
                plant.getattr("_hooks")?.extract()?,
                plant.getattr("_layout")?.extract()?,
            ),
        };
        let width = match &plant {
            PlantArg::Compiled(p) => p.plants.info().state_names.len(),
            PlantArg::Python(_, layout) => layout.0,
        };
        let n = x0.shape()[0];
        check_initial_states([n, x0.shape()[1]], width).map_err(InputError::from)?;
        let simulate = Simulate {
            py,
            control,
            reference: reference.as_deref(),
            disturbance: disturbance.as_deref(),
            x0: x0.as_slice()?,
            n,
            cfg,
            options,
            lent,
        };
        match plant {
            PlantArg::Compiled(p) => {
                p.cases
                    .check(&format!("plant ({})", p.kind), n)
                    .map_err(InputError::from)?;
                p.plants.visit(simulate)
            }
            PlantArg::Python(hooks, (dim, positions, velocities, mass, altitude)) => {
                with_axes!(positions.len(), D => {
                    let layout = StateLayout::<D>::new(dim, &positions, &velocities, mass, altitude);
                    let layout = layout.map_err(InputError::from)?;
                    simulate.python_plant(PyPlant { layout, hooks, n, handed: Handed::default() })
                }, a => Err(axes_error(a).into()))
            }
        }
    })
}

/// The arrays a caller lends for a batch's recording: states, controls, diagnostics.
type Recording<'py> = (
    PyReadwriteArray3<'py, f64>,
    PyReadwriteArray3<'py, f64>,
    PyReadwriteArray3<'py, f64>,
);

/// The core's view of the lent arrays, each C-contiguous (the core checks their shapes).
fn lend(arrays: [(&str, &mut PyReadwriteArray3<'_, f64>); 3]) -> PyResult<Lent> {
    let mut buffers = Vec::with_capacity(3);
    for (what, a) in arrays {
        if !a.is_c_contiguous() {
            invalid!("into: the {what} array must be C-contiguous");
        }
        let shape: [usize; 3] = a.shape().try_into().expect("a 3-dimensional array");
        buffers.push((a.as_slice_mut()?.as_mut_ptr(), shape));
    }
    // SAFETY: each pointer is the data of an array this call holds borrowed for writing
    // (`PyReadwriteArray`: no other borrow, from Rust or numpy's borrow checker) until it
    // returns, of its shape's product of f64; the one batch this call runs is the only writer
    Ok(unsafe { Lent::new(buffers[0], buffers[1], buffers[2]) })
}
