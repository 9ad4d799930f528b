//! A batch on a plant computed outside the core (written in Python): its derivative is asked
//! for once per integrator stage, for every case of the batch at once.
//!
//! Such a plant's state has as many components as its author gives it, known at run time. It
//! is kept in the room of a fixed-size state ([`MAX_EXTERNAL_STATE`] components, the unused ones
//! zero), so that each case runs through the same [`Block`] as a built-in plant's: the command
//! checks, the recording, the metrics, the ground crossing and the stops are that code, and the
//! step is the integrator's own ([`IntegratorKind::accumulate`], [`IntegratorKind::combine`]).
//! What differs is the order. A block of a built-in plant runs a whole period, calling its
//! plant at every stage; here every case starts its period ([`Block::begin_period`]), then each
//! stage of each substep is one call of the plant's derivative on the stage points of every
//! case, then every case ends its substep ([`Block::end_substep`]), and so on.
//!
//! The plant's other hooks are optional: its model (the drift and inertia the law reads;
//! without one, zero and one), its actuator (the applied command from the commanded
//! acceleration; without one, `inertia * a`, unsaturated) and its domain (without one, every
//! finite state). Each is one call per control instant (the domain: per substep) for every
//! case. The disturbance is a generalized acceleration, added to the derivative of each
//! velocity component, as the built-in plants add it.
//!
//! The cases run one by one on one thread, with `f64` numbers (the [`Level::Baseline`]
//! rollout of width 1), between calls that hold the interpreter anyway. The bookkeeping per case
//! is not small against a numpy call (BENCHMARKS.md, "A plant written in Python"): blocks of
//! several cases in SIMD lanes, as the built-in driver runs them, are the next step.

use std::sync::atomic::{AtomicBool, Ordering};

use nalgebra::SVector;

use super::{ExternalError, ExternalLaw, Inputs};
use crate::batch::{BatchError, BatchOutput, Outputs, PerCase, RunOptions};
use crate::control::{AnyLaw, AnyMemory};
use crate::disturbance::Disturbance;
use crate::error::ReadError;
use crate::kernel::{BaselineLaws, LawCalls, Level};
use crate::plant::Plant;
use crate::reference::Reference;
use crate::rollout::{
    Block, BlockBuffers, MAX_DIAGNOSTIC_WIDTH, Setting, SimConfig, stage_disturbance,
};

/// Most state components a plant computed outside the core may have.
pub const MAX_EXTERNAL_STATE: usize = 32;

/// A case's state, in the room of [`MAX_EXTERNAL_STATE`] components.
type Row = SVector<f64, MAX_EXTERNAL_STATE>;

/// Where a plant's state holds what the laws and the metrics read.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StateLayout<const D: usize> {
    /// Number of state components.
    pub dim: usize,
    /// The components of the generalized coordinates q, one per axis.
    pub positions: [usize; D],
    /// The components of their rates q', one per axis (the disturbance adds to their
    /// derivatives).
    pub velocities: [usize; D],
    /// The mass component, for the fuel metrics.
    pub mass: Option<usize>,
    /// The altitude component, for the touchdown metrics.
    pub altitude: Option<usize>,
}

impl<const D: usize> StateLayout<D> {
    /// Checks the layout: `dim` in 1..=[`MAX_EXTERNAL_STATE`], every index below it, the
    /// positions and velocities 2 D distinct components.
    pub fn new(
        dim: usize,
        positions: &[usize],
        velocities: &[usize],
        mass: Option<usize>,
        altitude: Option<usize>,
    ) -> Result<Self, ReadError> {
        let bad = |m: String| Err(ReadError::Value(m));
        if dim == 0 || dim > MAX_EXTERNAL_STATE {
            return bad(format!(
                "n_state = {dim} violates 1 <= n_state <= {MAX_EXTERNAL_STATE}"
            ));
        }
        for (name, v) in [("positions", positions), ("velocities", velocities)] {
            if v.len() != D {
                return bad(format!(
                    "{name} has {} entries; the plant has {D} axes",
                    v.len()
                ));
            }
        }
        let indices = positions
            .iter()
            .chain(velocities)
            .map(|&i| ("positions and velocities", i));
        let named = [("mass", mass), ("altitude", altitude)];
        let optional = named.iter().filter_map(|&(n, i)| i.map(|i| (n, i)));
        if let Some((name, i)) = indices.chain(optional).find(|&(_, i)| i >= dim) {
            return bad(format!(
                "{name}: index {i} violates index < n_state ({dim})"
            ));
        }
        let mut q: Vec<usize> = positions.iter().chain(velocities).copied().collect();
        q.sort_unstable();
        q.dedup();
        if q.len() != 2 * D {
            return bad("positions and velocities must be 2 x axes distinct components".into());
        }
        Ok(Self {
            dim,
            positions: std::array::from_fn(|i| positions[i]),
            velocities: std::array::from_fn(|i| velocities[i]),
            mass,
            altitude,
        })
    }
}

/// A plant computed outside the core, for every case of the batch at once. Arrays are `n x
/// width` row-major, case after case; the outputs are written in place. The optional hooks
/// are called only when [`ExternalPlant::hooks`] says the plant has them.
pub trait ExternalPlant<const D: usize> {
    /// What the plant's failure carries (the bindings: the Python exception).
    type Error: Send;

    fn layout(&self) -> &StateLayout<D>;

    /// Which of the optional hooks the plant has: its model, its actuator, its domain.
    fn hooks(&self) -> [bool; 3];

    /// Called with `true` on the thread that calls the hooks (and an external law) before the
    /// first call, and with `false` after the last, as [`ExternalLaw::on_thread`].
    fn on_thread(&mut self, _entering: bool) {}

    /// `x'` of every case at time `t`, state `x` (`n x dim`) and applied command `u` (`n x D`),
    /// without the disturbance, into `xdot` (`n x dim`).
    fn derivative(
        &mut self,
        t: f64,
        x: &[f64],
        u: &[f64],
        xdot: &mut [f64],
    ) -> Result<(), Self::Error>;

    /// The drift then the inertia the law reads (`n x 2D`: D drifts, then D inertias, per
    /// case) at `t`.
    fn model(&mut self, t: f64, x: &[f64], model: &mut [f64]) -> Result<(), Self::Error>;

    /// The applied command (`n x D`) for the commanded generalized accelerations `a`.
    fn actuate(&mut self, t: f64, x: &[f64], a: &[f64], u: &mut [f64]) -> Result<(), Self::Error>;

    /// Per case 1 when `x` is in the model's domain, 0 when not (`n x 1`).
    fn in_domain(&mut self, t: f64, x: &[f64], inside: &mut [f64]) -> Result<(), Self::Error>;
}

/// What the laws of a batch on an external plant are.
pub enum Laws<'a, const D: usize, E> {
    /// A built-in law per case (or one for all).
    Builtin(&'a PerCase<AnyLaw<D>>),
    /// A law computed outside the core.
    External(&'a mut (dyn ExternalLaw<D, Error = E> + Send)),
}

/// One case's plant as its block sees it: the layout, and what the plant's hooks last said
/// for this case (its applied command, its drift and inertia, whether it is in the domain).
#[derive(Clone, Copy, Debug)]
struct View<const D: usize> {
    layout: StateLayout<D>,
    u: SVector<f64, D>,
    drift: SVector<f64, D>,
    inertia: SVector<f64, D>,
    inside: bool,
}

impl<const D: usize> Plant<f64, D> for View<D> {
    type State = Row;

    fn coordinates(&self, x: &Row) -> (SVector<f64, D>, SVector<f64, D>) {
        let l = &self.layout;
        (
            SVector::from_fn(|i, _| x[l.positions[i]]),
            SVector::from_fn(|i, _| x[l.velocities[i]]),
        )
    }

    fn modelled_acceleration(&self, _t: f64, _x: &Row) -> SVector<f64, D> {
        self.drift
    }

    fn inertia(&self, _x: &Row) -> SVector<f64, D> {
        self.inertia
    }

    fn actuate(&self, _x: &Row, _a: &SVector<f64, D>) -> SVector<f64, D> {
        self.u
    }

    /// Never asked: the driver runs the integrator's stages itself.
    fn derivative(&self, _t: f64, _x: &Row, _u: &SVector<f64, D>, _d: &SVector<f64, D>) -> Row {
        Row::zeros()
    }

    fn in_domain(&self, _x: &Row) -> bool {
        self.inside
    }

    fn mass(&self, x: &Row) -> Option<f64> {
        self.layout.mass.map(|i| x[i])
    }

    fn altitude(&self, x: &Row) -> Option<f64> {
        self.layout.altitude.map(|i| x[i])
    }

    fn altitude_axis(&self) -> Option<usize> {
        let a = self.layout.altitude?;
        self.layout.positions.iter().position(|&p| p == a)
    }

    fn coordinate_components(&self) -> ([usize; D], [usize; D]) {
        (self.layout.positions, self.layout.velocities)
    }

    fn state_dim(&self) -> usize {
        self.layout.dim
    }
}

/// One case between two of the plant's calls.
struct Case<'a, const D: usize> {
    view: View<D>,
    reference: &'a Reference<D>,
    disturbance: &'a Disturbance<D>,
    block: Block<D, f64, View<D>>,
    /// The built-in law's memory (boxed: a law's memory may take a kilobyte, and the cases are
    /// walked several times per period).
    memory: Option<Box<AnyMemory<D, f64>>>,
}

impl<const D: usize> Case<'_, D> {
    /// Runs `f` on the case's block with its setting.
    #[inline(always)]
    fn with<T>(
        &mut self,
        cfg: &SimConfig,
        f: impl FnOnce(&mut Block<D, f64, View<D>>, &Setting<'_, D, f64, View<D>>) -> T,
    ) -> T {
        let set = Setting {
            plant: &self.view,
            reference: self.reference,
            disturbance: self.disturbance,
            table: None,
            cfg,
        };
        f(&mut self.block, &set)
    }
}

/// The end of a running case's substep `(tj, h)`: the block takes the state the integrator
/// stepped to, `next`, and its row `x` (and its row of `xs`) the state the block keeps, unless
/// the case stops, when its block is finished. When the substep is the last of control period
/// `closes` and no call of the plant comes before the period's end, the period ends here too.
/// Returns whether the case runs on.
fn end_substep<const D: usize>(
    case: &mut Case<'_, D>,
    cfg: &SimConfig,
    (tj, h): (f64, f64),
    out: &mut BlockBuffers<'_, D>,
    (next, x): (&Row, &mut Row),
    xs_row: &mut [f64],
    closes: Option<u64>,
) -> bool {
    *case.block.next_mut().1 = *next;
    if !case.with(cfg, |b, set| b.end_substep::<BaselineLaws>(set, tj, h)) {
        case.with(cfg, |b, set| b.finish(set, None, out));
        return false;
    }
    *x = *case.block.state();
    xs_row.copy_from_slice(&x.as_slice()[..xs_row.len()]);
    if let Some(k) = closes {
        case.with(cfg, |b, set| b.end_period(set, k));
    }
    true
}

/// How many cases ahead a walk over the blocks asks for their memory ([`prefetch`]).
const AHEAD: usize = 4;

/// Asks the CPU to bring `value`'s memory into the caches: a hint, which changes nothing else.
/// A walk over 10^4 blocks otherwise waits on memory at every one of them (each is over a
/// kilobyte, and the plant's calls between two walks evict them).
#[inline(always)]
fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = (value as *const T).cast::<i8>();
        for offset in (0..std::mem::size_of::<T>()).step_by(64) {
            // SAFETY: SSE is in every x86-64 CPU, and a prefetch reads nothing the program
            // sees and never faults, whatever the address
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}

/// `n x width` rows, case `i`'s.
fn at(v: &[f64], width: usize, i: usize) -> &[f64] {
    &v[i * width..(i + 1) * width]
}

/// Runs every case of a batch on `plant` under `laws`: initial states `x0` (`n x dim`), a
/// reference and a disturbance per case (or one for all). The output and its metrics are
/// those a built-in plant with the same dynamics gives, to the plant's own arithmetic.
/// Cancelled, at the next control instant, when `options.cancel` is raised; stopped when the
/// plant or the law fails. `options.threads` and `options.level` are not used (see the
/// module's comment).
pub fn run_external_plant<const D: usize, X: ExternalPlant<D>>(
    plant: &mut X,
    laws: Laws<'_, D, X::Error>,
    x0: &[f64],
    references: &PerCase<Reference<D>>,
    disturbances: &PerCase<Disturbance<D>>,
    cfg: &SimConfig,
    options: &RunOptions<'_>,
) -> Result<BatchOutput<D>, ExternalError<X::Error>> {
    plant.on_thread(true);
    let out = run_entered(plant, laws, x0, references, disturbances, cfg, options);
    plant.on_thread(false);
    out
}

/// [`run_external_plant`] between the plant's two `on_thread` calls.
fn run_entered<const D: usize, X: ExternalPlant<D>>(
    plant: &mut X,
    mut laws: Laws<'_, D, X::Error>,
    x0: &[f64],
    references: &PerCase<Reference<D>>,
    disturbances: &PerCase<Disturbance<D>>,
    cfg: &SimConfig,
    options: &RunOptions<'_>,
) -> Result<BatchOutput<D>, ExternalError<X::Error>> {
    let layout = *plant.layout();
    let nx = layout.dim;
    assert!(
        (1..=MAX_EXTERNAL_STATE).contains(&nx),
        "a state of {nx} components (StateLayout::new checks 1..={MAX_EXTERNAL_STATE})"
    );
    let n = x0.len() / nx;
    if let Some(event) = cfg.stop_at.filter(|_| layout.altitude.is_none()) {
        return Err(BatchError::Event(event).into());
    }
    let laws_len = match &laws {
        Laws::Builtin(l) => l.len(),
        Laws::External(_) => 1,
    };
    let tables = [
        ("reference", references.len()),
        ("disturbance", disturbances.len()),
        ("controller", laws_len),
    ];
    for (what, len) in tables {
        if len != 1 && len != n {
            return Err(BatchError::Length {
                what,
                len,
                cases: n,
            }
            .into());
        }
    }
    assert_eq!(x0.len(), n * nx, "x0 holds whole states");
    let nd = match &laws {
        Laws::Builtin(l) => l.get(0).diagnostic_width(),
        Laws::External(l) => l.diagnostic_width(),
    };
    assert!(
        nd <= MAX_DIAGNOSTIC_WIDTH,
        "a law records {nd} diagnostics, more than {MAX_DIAGNOSTIC_WIDTH}"
    );
    let never = AtomicBool::new(false);
    let cancel = options.cancel.unwrap_or(&never);
    let nr = cfg.n_records();
    let mut outputs = Outputs::<D>::allocate(n, nr, nx, nd, options.recording)?;
    if n == 0 {
        return Ok(outputs.finish(cfg, nx, nd, Level::Baseline));
    }
    let mut buffers = outputs.blocks(1, nr, nx, nd);
    let fail = ExternalError::Plant;

    // the plant's arrays: every case's row
    let mut xs = x0.to_vec();
    let mut ys = vec![0.0; n * nx];
    let mut ks = vec![0.0; n * nx];
    let mut model = vec![0.0; n * 2 * D];
    let mut a = vec![0.0; n * D];
    let mut u = vec![0.0; n * D];
    let mut inside = vec![1.0; n];
    let mut diag = vec![0.0; n * nd];
    let mut inputs = Inputs::<D>::new(n);
    let row = |v: &[f64], i: usize| -> Row {
        let r = at(v, nx, i);
        Row::from_fn(|c, _| if c < nx { r[c] } else { 0.0 })
    };
    let write_row = |v: &mut [f64], i: usize, x: &Row| {
        v[i * nx..(i + 1) * nx].copy_from_slice(&x.as_slice()[..nx]);
    };
    let from_model = |model: &[f64], i: usize, view: &mut View<D>| {
        let m = at(model, 2 * D, i);
        view.drift = SVector::from_fn(|c, _| m[c]);
        view.inertia = SVector::from_fn(|c, _| m[D + c]);
    };

    let [has_model, ..] = plant.hooks();
    if has_model {
        plant.model(0.0, &xs, &mut model).map_err(fail)?;
    }
    let mut cases: Vec<Case<'_, D>> = (0..n)
        .map(|i| {
            let mut view = View {
                layout,
                u: SVector::zeros(),
                drift: SVector::zeros(),
                inertia: SVector::repeat(1.0),
                inside: true,
            };
            if has_model {
                from_model(&model, i, &mut view);
            }
            let set = Setting {
                plant: &view,
                reference: references.get(i),
                disturbance: disturbances.get(i),
                table: None,
                cfg,
            };
            let block = Block::start(&set, &row(&xs, i), &[cfg.first_case + i as u64], 1);
            Case {
                view,
                reference: references.get(i),
                disturbance: disturbances.get(i),
                block,
                memory: None,
            }
        })
        .collect();
    if let Laws::Builtin(l) = &laws {
        for (i, case) in cases.iter_mut().enumerate() {
            case.memory = Some(Box::new(BaselineLaws::start(l.get(i), case.block.input())));
        }
    }

    let integrator = cfg.integrator;
    let stages = integrator.evaluations();
    let h = cfg.dt / f64::from(cfg.substeps);
    let [_, has_actuate, has_domain] = plant.hooks();
    let builtin = match &laws {
        Laws::Builtin(l) => Some(*l),
        Laws::External(_) => None,
    };
    // The cases are walked as few times per period as the plant's calls allow, and the walks
    // over the integrator's stages read only what the step needs, kept case after case: each
    // case's block, for 10^4 cases, is far larger than the caches, and a walk over the blocks
    // waits on memory at every case.
    let mut x_rows: Vec<Row> = (0..n).map(|i| row(&xs, i)).collect();
    let mut sums = x_rows.clone();
    let mut y_rows = x_rows.clone();
    let mut held: Vec<SVector<f64, D>> = vec![SVector::zeros(); n];
    let mut running = vec![true; n];
    let dist: Vec<&Disturbance<D>> = (0..n).map(|i| disturbances.get(i)).collect();
    let mut k = 0;
    while k <= cfg.steps && running.contains(&true) {
        if cancel.load(Ordering::Relaxed) {
            return Err(BatchError::Cancelled.into());
        }
        let t = k as f64 * cfg.dt;
        let last = k == cfg.steps;
        // the law's commands (and diagnostics) at t_k: the built-in law's in the walk below,
        // unless the plant's actuator needs them all first
        if let Laws::External(law) = &mut laws {
            for (i, case) in cases.iter().enumerate() {
                inputs.write(i, case.block.input());
            }
            inputs.t = t;
            inputs.k = k;
            law.command(&inputs, &mut a, &mut diag)
                .map_err(ExternalError::Law)?;
        }
        let command = |case: &mut Case<'_, D>, i: usize, a: &mut [f64], diag: &mut [f64]| {
            if let Some(l) = builtin {
                let (law, input) = (l.get(i), case.block.input());
                let memory = case.memory.as_mut().expect("a built-in law has its memory");
                let c = BaselineLaws::command(law, memory, input);
                a[i * D..(i + 1) * D].copy_from_slice(c.as_slice());
                if case.block.records(cfg, k) || (last && cfg.record_every > 0) {
                    BaselineLaws::diagnostics(law, memory, input, &mut diag[i * nd..(i + 1) * nd]);
                }
                if !last && law.has_memory() {
                    BaselineLaws::advance(law, memory, input);
                }
            }
        };
        if has_actuate {
            for i in 0..n {
                if !running[i] {
                    continue;
                }
                if let Some(c) = cases.get(i + AHEAD) {
                    prefetch(c);
                }
                command(&mut cases[i], i, &mut a, &mut diag);
            }
            plant.actuate(t, &xs, &a, &mut u).map_err(fail)?;
        }
        for i in 0..n {
            if !running[i] {
                continue;
            }
            if let Some(c) = cases.get(i + AHEAD) {
                prefetch(c);
            }
            let case = &mut cases[i];
            if !has_actuate {
                command(case, i, &mut a, &mut diag);
            }
            let ai = SVector::<f64, D>::from_column_slice(at(&a, D, i));
            if has_actuate {
                case.view.u = SVector::from_column_slice(at(&u, D, i));
            } else {
                case.view.u = case.view.inertia.component_mul(&ai);
                u[i * D..(i + 1) * D].copy_from_slice(case.view.u.as_slice());
            }
            let (di, out) = (at(&diag, nd, i), &mut buffers[i]);
            if last {
                case.with(cfg, |b, set| b.finish(set, Some((&ai, di)), out));
                running[i] = false;
                continue;
            }
            let hold = case.with(cfg, |b, set| {
                b.begin_period::<BaselineLaws>(set, k, &ai, di, out)
            });
            match hold {
                Some(hold) => held[i] = hold.disturbance,
                None => {
                    case.with(cfg, |b, set| b.finish(set, None, out));
                    running[i] = false;
                }
            }
        }
        if last {
            break;
        }
        let t1 = (k + 1) as f64 * cfg.dt;
        for j in 0..cfg.substeps as usize {
            let tj = t + j as f64 * h;
            // the period ends in this walk when no call of the plant comes between
            let closes = (j + 1 == cfg.substeps as usize && !has_model).then_some(k);
            for s in 0..stages {
                let stage = integrator.stage(s);
                let ts = stage.time(tj, h);
                let points = if s == 0 { &xs } else { &ys };
                plant.derivative(ts, points, &u, &mut ks).map_err(fail)?;
                for i in 0..n {
                    if !running[i] {
                        continue;
                    }
                    // the last stage's walk ends the cases' substeps
                    if s + 1 == stages
                        && !has_domain
                        && let Some(c) = cases.get(i + AHEAD)
                    {
                        prefetch(c);
                    }
                    let d = stage_disturbance(dist[i], None, (k, j, stage), ts, &held[i]);
                    let mut ki = row(&ks, i);
                    for (c, &v) in layout.velocities.iter().enumerate() {
                        ki[v] += d[c];
                    }
                    integrator.accumulate(s, &x_rows[i], &ki, h, &mut sums[i], &mut y_rows[i]);
                    if s + 1 < stages {
                        write_row(&mut ys, i, &y_rows[i]);
                        continue;
                    }
                    integrator.combine(&x_rows[i], h, &mut sums[i]);
                    if has_domain {
                        // the domain is asked of every stepped state before the substep ends
                        write_row(&mut ys, i, &sums[i]);
                        continue;
                    }
                    let rows = (&sums[i], &mut x_rows[i]);
                    let xs_row = &mut xs[i * nx..(i + 1) * nx];
                    running[i] = end_substep(
                        &mut cases[i],
                        cfg,
                        (tj, h),
                        &mut buffers[i],
                        rows,
                        xs_row,
                        closes,
                    );
                }
            }
            if has_domain {
                plant.in_domain(tj + h, &ys, &mut inside).map_err(fail)?;
                for i in 0..n {
                    if !running[i] {
                        continue;
                    }
                    if let Some(c) = cases.get(i + AHEAD) {
                        prefetch(c);
                    }
                    cases[i].view.inside = inside[i] != 0.0;
                    let rows = (&sums[i], &mut x_rows[i]);
                    let xs_row = &mut xs[i * nx..(i + 1) * nx];
                    running[i] = end_substep(
                        &mut cases[i],
                        cfg,
                        (tj, h),
                        &mut buffers[i],
                        rows,
                        xs_row,
                        closes,
                    );
                }
            }
        }
        // the law's input at t_(k+1), from the plant's model there
        if has_model {
            plant.model(t1, &xs, &mut model).map_err(fail)?;
            for i in 0..n {
                if !running[i] {
                    continue;
                }
                if let Some(c) = cases.get(i + AHEAD) {
                    prefetch(c);
                }
                from_model(&model, i, &mut cases[i].view);
                cases[i].with(cfg, |b, set| b.end_period(set, k));
            }
        }
        k += 1;
    }
    drop(buffers);
    Ok(outputs.finish(cfg, nx, nd, Level::Baseline))
}
