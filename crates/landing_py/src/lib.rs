//! `landing._core`: the thin pyo3 layer over `landing_core`.
//!
//! Inputs are copied into owned Rust values, validated (by the core's own `validate`), then the
//! batch runs with the GIL released. The Python package (`python/landing`) builds the parameter
//! tables; nothing here holds simulation logic.

mod analysis;
mod errors;
mod fuzzy_spec;
mod gravity_spec;
mod output;
mod params;
mod specs;
mod tether;

use std::panic::{AssertUnwindSafe, catch_unwind};

use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::batch::{Batch, BatchOutput, PerCase, run_with_threads};
use landing_core::control::ControlLaw;
use landing_core::disturbance::Disturbance;
use landing_core::gravity::{Harmonic2, PointMass, TwoPointMass};
use landing_core::integrator::{Euler, IntegratorKind, Rk4};
use landing_core::plant::tether::{
    TetheredFlexible2, TetheredFlexible4, TetheredFlexible8, TetheredFlexible16, TetheredSimplified,
};
use landing_core::plant::{DoubleIntegrator, MarsLander, Plant, SmallBody};
use landing_core::reference::Reference;
use landing_core::rng::philox4x64_10;
use landing_core::state::State;
use landing_core::{BatchError, SimConfig, Tolerance};

use errors::{InputError, batch_error, internal_error, param_error, to_pyerr};
use params::Params;
use specs::{
    LawSpec, PlantSpec, kind_of, parse_disturbance, parse_law, parse_plant, parse_reference,
    with_plants,
};

/// What a batch needs besides its law, owned, ready to cross into the GIL-free region.
struct Setting<const D: usize, P: Plant<D>> {
    plants: PerCase<P>,
    references: PerCase<Reference<D>>,
    disturbances: PerCase<Disturbance<D>>,
    x0: Vec<P::State>,
    integrator: IntegratorKind,
    cfg: SimConfig,
    threads: Option<usize>,
}

struct Job<const D: usize, P: Plant<D>> {
    law: LawSpec<D>,
    setting: Setting<D, P>,
}

impl<const D: usize, P: Plant<D>> Setting<D, P> {
    /// The dispatch on the integrator, once per batch.
    fn run<L: ControlLaw<D>>(self, laws: PerCase<L>) -> Result<BatchOutput<D>, BatchError> {
        let Setting {
            plants,
            references,
            disturbances,
            x0,
            integrator,
            cfg,
            threads,
        } = self;
        let batch = Batch {
            plants,
            laws,
            references,
            disturbances,
            x0,
        };
        match integrator {
            IntegratorKind::Rk4 => run_with_threads(&batch, Rk4, &cfg, threads),
            IntegratorKind::Euler => run_with_threads(&batch, Euler, &cfg, threads),
        }
    }
}

impl<const D: usize, P: Plant<D>> Job<D, P> {
    /// The dispatch on the law, once per batch.
    fn run(self) -> Result<BatchOutput<D>, BatchError> {
        match self.law {
            LawSpec::FixedTimeMss(l) => self.setting.run(l),
            LawSpec::SuperTwisting(l) => self.setting.run(l),
            LawSpec::OpenLoop(l) => self.setting.run(l),
            LawSpec::PdSlidingMode(l) => self.setting.run(l),
            LawSpec::FastTerminalSmc(l) => self.setting.run(l),
            LawSpec::FuzzyFastTerminalSmc(l) => self.setting.run(l),
            LawSpec::IntegralExponentialReaching(l) => self.setting.run(l),
            LawSpec::FuzzyVariableRate(l) => self.setting.run(l),
            LawSpec::Ntsmc(l) => self.setting.run(l),
            LawSpec::FixedTimeNtsmc(l) => self.setting.run(l),
        }
    }
}

/// Reads x0 (N x state dim) and checks every case against the plant.
fn read_x0<const D: usize, P: Plant<D>>(
    plants: &PerCase<P>,
    x0: &PyReadonlyArray2<'_, f64>,
) -> Result<Vec<P::State>, InputError> {
    let nx = P::State::DIM;
    let shape = x0.shape();
    if shape[1] != nx || shape[0] == 0 {
        return Err(InputError::Shape(format!(
            "x0 has shape ({}, {}); this plant takes (N, {nx}) with N >= 1 (state {:?})",
            shape[0],
            shape[1],
            P::STATE_NAMES
        )));
    }
    let view = x0.as_array();
    let mut out = Vec::with_capacity(shape[0]);
    for (i, row) in view.outer_iter().enumerate() {
        let values: Vec<f64> = row.iter().copied().collect();
        let x = P::State::from_slice(&values);
        plants.get(i).check_initial(&x).map_err(|e| {
            let axis = e.axis.unwrap_or(0);
            InputError::Value(format!("x0[{i}, {axis}] = {} violates {}", e.value, e.rule))
        })?;
        out.push(x);
    }
    Ok(out)
}

fn table<'py>(obj: &Bound<'py, PyAny>, what: &str) -> Result<Bound<'py, PyDict>, InputError> {
    obj.clone()
        .cast_into::<PyDict>()
        .map_err(|_| InputError::Type(format!("{what} must be a table")))
}

#[allow(clippy::too_many_arguments)]
fn prepare<'py, const D: usize, P: Plant<D>>(
    plants: PerCase<P>,
    controller: &Bound<'py, PyDict>,
    x0: &PyReadonlyArray2<'py, f64>,
    reference: Option<&Bound<'py, PyDict>>,
    disturbance: Option<&Bound<'py, PyDict>>,
    integrator: IntegratorKind,
    cfg: SimConfig,
    threads: Option<usize>,
) -> Result<Job<D, P>, InputError> {
    let x0 = read_x0(&plants, x0)?;
    let n = Some(x0.len());
    let law_kind = kind_of(controller, "controller")?;
    let mut p = Params::new(format!("controller ({law_kind})"), controller.clone(), n);
    let law = parse_law::<D>(&law_kind, &mut p).map_err(|e| e.context(&p.owner))?;
    let references = match reference {
        None => PerCase::shared(Reference::default()),
        Some(r) => {
            let kind = kind_of(r, "reference")?;
            let mut p = Params::new(format!("reference ({kind})"), r.clone(), n);
            parse_reference::<D>(&kind, &mut p).map_err(|e| e.context(&p.owner))?
        }
    };
    let disturbances = match disturbance {
        None => PerCase::shared(Disturbance::none()),
        Some(d) => {
            let mut p = Params::new("disturbance", d.clone(), n);
            parse_disturbance::<D>(&mut p).map_err(|e| e.context(&p.owner))?
        }
    };
    Ok(Job {
        law,
        setting: Setting {
            plants,
            references,
            disturbances,
            x0,
            integrator,
            cfg,
            threads,
        },
    })
}

/// A job for one of the plants (the dispatch on the plant, once per batch).
enum Prepared {
    Mars(Job<3, MarsLander>),
    DoubleIntegrator(Job<3, DoubleIntegrator>),
    SmallBodyPointMass(Job<3, SmallBody<PointMass>>),
    SmallBodyTwoPointMass(Job<3, SmallBody<TwoPointMass>>),
    SmallBodyHarmonic2(Job<3, SmallBody<Harmonic2>>),
    TetherSimplified(Job<2, TetheredSimplified>),
    TetherFlexible2(Job<2, TetheredFlexible2>),
    TetherFlexible4(Job<2, TetheredFlexible4>),
    TetherFlexible8(Job<2, TetheredFlexible8>),
    TetherFlexible16(Job<2, TetheredFlexible16>),
}

/// Runs a prepared job without the GIL, turning a panic into an exception.
fn execute<'py, const D: usize, P: Plant<D>>(
    py: Python<'py>,
    job: Job<D, P>,
) -> PyResult<Bound<'py, PyDict>> {
    let diag_layout = job.law.diagnostic_layout();
    let result = py.detach(move || catch_unwind(AssertUnwindSafe(move || job.run())));
    match result {
        Ok(Ok(out)) => output::to_dict(py, out, P::STATE_NAMES, P::CONTROL_NAMES, &diag_layout),
        Ok(Err(e)) => Err(batch_error(py, e)),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "panic".into());
            Err(internal_error(py, what))
        }
    }
}

/// See `landing.simulate_batch` for the documentation.
#[pyfunction]
#[pyo3(signature = (plant, controller, x0, *, t_final, dt, integrator, substeps, reference, disturbance, record_every, seed, first_case, settle_tolerance, settle_relative, chatter_cutoff, threads))]
#[allow(clippy::too_many_arguments)]
fn simulate_batch<'py>(
    py: Python<'py>,
    plant: &Bound<'py, PyAny>,
    controller: &Bound<'py, PyAny>,
    x0: PyReadonlyArray2<'py, f64>,
    t_final: f64,
    dt: f64,
    integrator: &str,
    substeps: i64,
    reference: Option<Bound<'py, PyAny>>,
    disturbance: Option<Bound<'py, PyAny>>,
    record_every: i64,
    seed: u64,
    first_case: u64,
    settle_tolerance: f64,
    settle_relative: bool,
    chatter_cutoff: Option<f64>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    let prepared = (|| -> Result<_, InputError> {
        let integ = IntegratorKind::from_name(integrator).ok_or_else(|| {
            InputError::Value(format!(
                "integrator = {integrator:?} is not one of {:?}",
                IntegratorKind::NAMES
            ))
        })?;
        if substeps < 1 || substeps > u32::MAX as i64 {
            return Err(InputError::Value(format!(
                "substeps = {substeps} violates substeps >= 1"
            )));
        }
        if record_every < 0 {
            return Err(InputError::Value(format!(
                "record_every = {record_every} violates record_every >= 0"
            )));
        }
        let threads = match threads {
            None => None,
            Some(k) if k >= 1 => Some(k as usize),
            Some(k) => {
                return Err(InputError::Value(format!(
                    "threads = {k} violates threads >= 1"
                )));
            }
        };
        let cfg = SimConfig::new(t_final, dt, substeps as u32, record_every as u64, seed)
            .map_err(|e| param_error(&e, None))?
            .with_first_case(first_case)
            .with_settle(if settle_relative {
                Tolerance::Relative(settle_tolerance)
            } else {
                Tolerance::Absolute(settle_tolerance)
            })
            .map_err(|e| param_error(&e, None))?;
        let cfg = match chatter_cutoff {
            None => cfg,
            Some(hz) => cfg
                .with_chatter_cutoff(hz)
                .map_err(|e| param_error(&e, None))?,
        };
        let plant = table(plant, "plant")?;
        let controller = table(controller, "controller")?;
        let reference = reference
            .as_ref()
            .map(|r| table(r, "reference"))
            .transpose()?;
        let disturbance = disturbance
            .as_ref()
            .map(|d| table(d, "disturbance"))
            .transpose()?;
        let n = Some(x0.shape()[0]);
        let kind = kind_of(&plant, "plant")?;
        let mut p = Params::new(format!("plant ({kind})"), plant.clone(), n);
        let spec = parse_plant(&kind, &mut p).map_err(|e| e.context(&p.owner))?;
        macro_rules! job {
            ($variant:ident, $plants:expr, $d:literal) => {
                Prepared::$variant(prepare::<$d, _>(
                    $plants,
                    &controller,
                    &x0,
                    reference.as_ref(),
                    disturbance.as_ref(),
                    integ,
                    cfg,
                    threads,
                )?)
            };
        }
        let prepared = match spec {
            PlantSpec::Mars(plants) => job!(Mars, plants, 3),
            PlantSpec::DoubleIntegrator(plants) => job!(DoubleIntegrator, plants, 3),
            PlantSpec::SmallBodyPointMass(plants) => job!(SmallBodyPointMass, plants, 3),
            PlantSpec::SmallBodyTwoPointMass(plants) => job!(SmallBodyTwoPointMass, plants, 3),
            PlantSpec::SmallBodyHarmonic2(plants) => job!(SmallBodyHarmonic2, plants, 3),
            PlantSpec::TetherSimplified(plants) => job!(TetherSimplified, plants, 2),
            PlantSpec::TetherFlexible2(plants) => job!(TetherFlexible2, plants, 2),
            PlantSpec::TetherFlexible4(plants) => job!(TetherFlexible4, plants, 2),
            PlantSpec::TetherFlexible8(plants) => job!(TetherFlexible8, plants, 2),
            PlantSpec::TetherFlexible16(plants) => job!(TetherFlexible16, plants, 2),
        };
        Ok(prepared)
    })();
    match prepared.map_err(|e| to_pyerr(py, e))? {
        Prepared::Mars(job) => execute(py, job),
        Prepared::DoubleIntegrator(job) => execute(py, job),
        Prepared::SmallBodyPointMass(job) => execute(py, job),
        Prepared::SmallBodyTwoPointMass(job) => execute(py, job),
        Prepared::SmallBodyHarmonic2(job) => execute(py, job),
        Prepared::TetherSimplified(job) => execute(py, job),
        Prepared::TetherFlexible2(job) => execute(py, job),
        Prepared::TetherFlexible4(job) => execute(py, job),
        Prepared::TetherFlexible8(job) => execute(py, job),
        Prepared::TetherFlexible16(job) => execute(py, job),
    }
}

/// Validates a plant table without running anything (used by the constructors).
#[pyfunction]
fn check_plant(py: Python<'_>, owner: &str, table: Bound<'_, PyDict>) -> PyResult<usize> {
    let run = || -> Result<usize, InputError> {
        let kind = kind_of(&table, "plant")?;
        let mut p = Params::new(owner, table.clone(), None);
        let spec = parse_plant(&kind, &mut p).map_err(|e| e.context(owner))?;
        Ok(spec.axes())
    };
    run().map_err(|e| to_pyerr(py, e))
}

/// Validates a controller table for the axis counts the plants use (3 and 2): it is valid if
/// either reading is. A table whose per-axis arrays all have length 2 is read for 2 axes
/// first, so that an error names the axis (a 2-vector read for 3 axes would be one value per
/// case of a 2-case batch).
#[pyfunction]
fn check_controller(py: Python<'_>, owner: &str, table: Bound<'_, PyDict>) -> PyResult<()> {
    let run = || -> Result<(), InputError> {
        let kind = kind_of(&table, "controller")?;
        let lengths: Vec<usize> = table
            .values()
            .iter()
            .filter_map(|v| v.extract::<numpy::PyReadonlyArrayDyn<'_, f64>>().ok())
            .filter_map(|a| a.shape().last().copied().filter(|_| !a.shape().is_empty()))
            .collect();
        let two_axes = lengths.contains(&2) && !lengths.contains(&3);
        let parse = |axes: usize| {
            let mut p = Params::new(owner, table.clone(), None);
            if axes == 3 {
                parse_law::<3>(&kind, &mut p).map(|_| ())
            } else {
                parse_law::<2>(&kind, &mut p).map(|_| ())
            }
        };
        let (first, second) = if two_axes { (2, 3) } else { (3, 2) };
        match parse(first) {
            Err(e) => parse(second).map_err(|_| e),
            ok => ok,
        }
        .map_err(|e| e.context(owner))
    };
    run().map_err(|e| to_pyerr(py, e))
}

/// Validates a reference or disturbance table (`what` is "reference" or "disturbance").
#[pyfunction]
fn check_signal(py: Python<'_>, owner: &str, what: &str, table: Bound<'_, PyDict>) -> PyResult<()> {
    fn one<const D: usize>(
        what: &str,
        owner: &str,
        table: &Bound<'_, PyDict>,
    ) -> Result<(), InputError> {
        let mut p = Params::new(owner, table.clone(), None);
        if what == "reference" {
            let kind = kind_of(table, "reference")?;
            parse_reference::<D>(&kind, &mut p).map(|_| ())
        } else {
            parse_disturbance::<D>(&mut p).map(|_| ())
        }
    }
    let run = || -> Result<(), InputError> {
        match one::<3>(what, owner, &table) {
            Err(e) if e.is_shape() => one::<2>(what, owner, &table).map_err(|_| e),
            other => other,
        }
        .map_err(|e| e.context(owner))
    };
    run().map_err(|e| to_pyerr(py, e))
}

/// Evaluates a reference table at times `t`: (position, velocity, acceleration), each (T, D).
#[pyfunction]
fn evaluate_reference<'py>(
    py: Python<'py>,
    table: Bound<'py, PyDict>,
    axes: usize,
    t: Vec<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    fn eval<'py, const D: usize>(
        py: Python<'py>,
        table: &Bound<'py, PyDict>,
        t: &[f64],
    ) -> Result<Bound<'py, PyDict>, InputError> {
        let kind = kind_of(table, "reference")?;
        let mut p = Params::new(format!("reference ({kind})"), table.clone(), None);
        let refs = parse_reference::<D>(&kind, &mut p).map_err(|e| e.context(&p.owner))?;
        if refs.len() != 1 {
            return Err(InputError::Shape(
                "evaluate() needs a reference shared by all cases".into(),
            ));
        }
        let r = refs.get(0);
        let mut pos = Vec::with_capacity(t.len() * D);
        let mut vel = Vec::with_capacity(t.len() * D);
        let mut acc = Vec::with_capacity(t.len() * D);
        for &ti in t {
            let pt = r.at(ti);
            pos.extend_from_slice(pt.position.as_slice());
            vel.extend_from_slice(pt.velocity.as_slice());
            acc.extend_from_slice(pt.acceleration.as_slice());
        }
        let d = PyDict::new(py);
        for (name, v) in [("position", pos), ("velocity", vel), ("acceleration", acc)] {
            d.set_item(name, output::array2(py, v, t.len(), D)?)?;
        }
        Ok(d)
    }
    let r = match axes {
        3 => eval::<3>(py, &table, &t),
        2 => eval::<2>(py, &table, &t),
        _ => Err(InputError::Value(format!(
            "axes = {axes} violates axes in (2, 3)"
        ))),
    };
    r.map_err(|e| to_pyerr(py, e))
}

/// Coefficients (c0, c1, c2, c3), each of length D, of the cubic through the boundary states.
#[pyfunction]
fn cubic_from_boundary(
    py: Python<'_>,
    p0: Vec<f64>,
    v0: Vec<f64>,
    pt: Vec<f64>,
    vt: Vec<f64>,
    t_end: f64,
) -> PyResult<Vec<Vec<f64>>> {
    fn fit<const D: usize>(v: [&[f64]; 4], t_end: f64) -> Result<Vec<Vec<f64>>, InputError> {
        let s = v.map(nalgebra::SVector::<f64, D>::from_column_slice);
        match Reference::cubic_from_boundary(s[0], s[1], s[2], s[3], t_end)
            .map_err(|e| param_error(&e, None))?
        {
            Reference::Cubic { coefficients, .. } => {
                Ok(coefficients.iter().map(|c| c.as_slice().to_vec()).collect())
            }
            Reference::Constant { .. } => unreachable!("cubic_from_boundary builds a cubic"),
        }
    }
    let run = || -> Result<Vec<Vec<f64>>, InputError> {
        let d = p0.len();
        for (name, v) in [("v0", &v0), ("pT", &pt), ("vT", &vt)] {
            if v.len() != d {
                return Err(InputError::Shape(format!(
                    "{name} has {} axes, p0 has {d}",
                    v.len()
                )));
            }
        }
        let all = [p0.as_slice(), v0.as_slice(), pt.as_slice(), vt.as_slice()];
        match d {
            3 => fit::<3>(all, t_end),
            2 => fit::<2>(all, t_end),
            _ => Err(InputError::Shape(format!(
                "p0 has {d} axes; 2 or 3 are supported"
            ))),
        }
    };
    run().map_err(|e| to_pyerr(py, e))
}

/// State, control and axis names of a plant kind. Plants whose layout depends on their
/// parameters (the flexible tether's node count) need their table, which also adds the
/// model's derived figures (see `tether::extras`).
#[pyfunction]
#[pyo3(signature = (kind, table=None))]
fn plant_info<'py>(
    py: Python<'py>,
    kind: &str,
    table: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    fn info<'py, const D: usize, P: Plant<D>>(py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("state_names", P::STATE_NAMES.to_vec())?;
        d.set_item("control_names", P::CONTROL_NAMES.to_vec())?;
        d.set_item("axes", D)?;
        Ok(d)
    }
    if let Some(table) = table {
        let mut p = Params::new(format!("plant ({kind})"), table.clone(), None);
        let spec = parse_plant(kind, &mut p).map_err(|e| to_pyerr(py, e.context(&p.owner)))?;
        fn of<'py, const D: usize, P: Plant<D>>(
            py: Python<'py>,
            _plants: &PerCase<P>,
        ) -> PyResult<Bound<'py, PyDict>> {
            info::<D, P>(py)
        }
        let d = with_plants!(&spec, plants, D => of::<D, _>(py, plants)?);
        tether::extras(&spec, &d)?;
        return Ok(d);
    }
    match kind {
        "mars_lander" => info::<3, MarsLander>(py),
        "double_integrator" => info::<3, DoubleIntegrator>(py),
        "small_body" => info::<3, SmallBody<PointMass>>(py),
        "tethered_satellite" => Err(to_pyerr(
            py,
            InputError::Type(
                "plant_info needs the table of a tethered_satellite (its layout depends on it)"
                    .into(),
            ),
        )),
        other => Err(to_pyerr(
            py,
            InputError::Value(format!(
                "unknown plant kind {other:?}; known: {:?}",
                PlantSpec::KINDS
            )),
        )),
    }
}

/// The generalized coordinates (q, q') the laws read, for states (M, state dim) of a plant.
#[pyfunction]
fn plant_coordinates<'py>(
    py: Python<'py>,
    table: Bound<'py, PyDict>,
    states: PyReadonlyArray2<'py, f64>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    fn coords<const D: usize, P: Plant<D>>(
        plants: &PerCase<P>,
        states: &PyReadonlyArray2<'_, f64>,
    ) -> Result<(Vec<f64>, Vec<f64>, usize), InputError> {
        let nx = P::State::DIM;
        let shape = states.shape();
        if shape[1] != nx {
            return Err(InputError::Shape(format!(
                "states have {} components; this plant's have {nx} ({:?})",
                shape[1],
                P::STATE_NAMES
            )));
        }
        let view = states.as_array();
        let (mut q, mut qd) = (
            Vec::with_capacity(shape[0] * D),
            Vec::with_capacity(shape[0] * D),
        );
        for row in view.outer_iter() {
            let values: Vec<f64> = row.iter().copied().collect();
            let (a, b) = plants.get(0).coordinates(&P::State::from_slice(&values));
            q.extend_from_slice(a.as_slice());
            qd.extend_from_slice(b.as_slice());
        }
        Ok((q, qd, D))
    }
    let run = || -> Result<(Vec<f64>, Vec<f64>, usize), InputError> {
        let kind = kind_of(&table, "plant")?;
        let mut p = Params::new(format!("plant ({kind})"), table.clone(), None);
        let spec = parse_plant(&kind, &mut p).map_err(|e| e.context(&p.owner))?;
        with_plants!(&spec, plants, D => coords::<D, _>(plants, &states))
    };
    let (q, qd, d) = run().map_err(|e| to_pyerr(py, e))?;
    let m = states.shape()[0];
    Ok((output::array2(py, q, m, d)?, output::array2(py, qd, m, d)?))
}

/// One Philox4x64-10 block, exposed so the tests can compare with `numpy.random.Philox`.
#[pyfunction]
fn philox4x64(counter: [u64; 4], key: [u64; 2]) -> [u64; 4] {
    philox4x64_10(counter, key)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(simulate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(check_plant, m)?)?;
    m.add_function(wrap_pyfunction!(check_controller, m)?)?;
    m.add_function(wrap_pyfunction!(check_signal, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_reference, m)?)?;
    m.add_function(wrap_pyfunction!(cubic_from_boundary, m)?)?;
    m.add_function(wrap_pyfunction!(philox4x64, m)?)?;
    m.add_function(wrap_pyfunction!(plant_info, m)?)?;
    m.add_function(wrap_pyfunction!(plant_coordinates, m)?)?;
    m.add_function(wrap_pyfunction!(tether::tether_initial_state, m)?)?;
    analysis::register(m)?;
    fuzzy_spec::register(m)?;
    gravity_spec::register(m)?;
    m.add("INTEGRATORS", IntegratorKind::NAMES.to_vec())?;
    m.add("PLANT_KINDS", PlantSpec::KINDS.to_vec())?;
    m.add("CONTROLLER_KINDS", specs::LAW_KINDS.to_vec())?;
    Ok(())
}
