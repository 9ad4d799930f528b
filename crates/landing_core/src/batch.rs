//! Many cases at once: blocks of lanes, in parallel on rayon.
//!
//! The cases are cut into blocks of as many cases as the kernel's lanes (the last block padded
//! with copies of its last case); each block runs the rollout in lockstep, compiled for the
//! instruction-set level chosen at run time ([`crate::kernel`]). Cases are independent and each
//! draws its random numbers from streams keyed by its own index, and no lane's arithmetic
//! depends on another's, so the output is bit-identical whatever the thread count, the batch
//! size, the chunking, a case's position in its block, or the level.
//!
//! Output buffers are allocated once, up front, and handed out as disjoint per-block slices. A
//! deterministic disturbance shared by every case is evaluated once per integrator stage for the
//! whole batch ([`StageTable`]).

use std::sync::atomic::AtomicBool;

use crate::control::AnyLaw;
use crate::disturbance::Disturbance;
use crate::error::ReadError;
use crate::event::Event;
use crate::integrator::IntegratorKind;
use crate::kernel::{self, LawCalls, Level, LevelError, LevelJob};
use crate::lanes::{Gather, Real};
use crate::limits::{MAX_CASES, MAX_SUBSTEPS, MAX_THREADS, within_cap};
use crate::memory::{available_bytes, gib};
use crate::metrics::CaseMetrics;
use crate::parallel::{self, Job};
use crate::params::Named;
use crate::plant::{Plant, PlantModel};
use crate::reference::Reference;
use crate::rollout::{
    BlockBuffers, Cancelled, MAX_DIAGNOSTIC_WIDTH, Setting, SimConfig, StageTable, Tolerance,
    rollout_block,
};
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

    /// Whether one value serves every case.
    pub fn is_shared(&self) -> bool {
        self.0.len() == 1
    }

    pub fn iter(&self) -> impl Iterator<Item = &T> {
        self.0.iter()
    }

    /// The value every case shares, or an error saying that `what` needs one.
    pub fn single(&self, what: &str) -> Result<&T, ReadError> {
        match self.0.as_slice() {
            [value] => Ok(value),
            _ => Err(ReadError::value(format!(
                "{what} needs parameters shared by all cases"
            ))),
        }
    }
}

/// Everything that varies between the cases of a batch. `L` is its laws: built-in ones per
/// case (the default), or `()` for a batch whose law is computed outside the core
/// ([`run_external`]).
pub struct Batch<const D: usize, P: PlantModel<D>, L = PerCase<AnyLaw<D>>> {
    pub plants: PerCase<P>,
    pub laws: L,
    pub references: PerCase<Reference<D>>,
    pub disturbances: PerCase<Disturbance<D>>,
    pub x0: Vec<<P as Plant<f64, D>>::State>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum BatchError {
    /// A per-case table whose length is neither 1 nor the number of cases.
    Length {
        what: &'static str,
        len: usize,
        cases: usize,
    },
    /// Cases of one batch that differ in what a block must share (a law's kind or variant, a
    /// switching function, a reference's kind, a network's size...).
    Shape { what: &'static str, case: usize },
    /// The batch's output would not fit in memory: `bytes` needed, `available` left (when
    /// known), of which `recording` bytes are the recorded trajectories.
    Allocation {
        bytes: u128,
        recording: u128,
        available: Option<u64>,
    },
    /// The requested thread pool could not be built.
    ThreadPool(String),
    /// The requested instruction-set level cannot run here.
    Level(LevelError),
    /// The run was cancelled (its output is incomplete and dropped).
    Cancelled,
    /// The run's event cannot happen on this plant (a touchdown without an altitude).
    Event(Event),
    /// A lent recording buffer ([`Lent`]) whose shape is not the batch's.
    Lent {
        what: &'static str,
        shape: [usize; 3],
        expected: [usize; 3],
    },
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
            Self::Shape { what, case } => write!(
                f,
                "{what} of case {case} differs from case 0 in what every case of a batch shares \
                 (its kind, variant, switching function, network size or fuzzy system)"
            ),
            Self::Allocation {
                bytes,
                recording,
                available,
            } => {
                write!(
                    f,
                    "the batch's output needs {:.2} GiB ({:.2} GiB of it the recording)",
                    gib(*bytes),
                    gib(*recording)
                )?;
                if let Some(a) = available {
                    write!(f, " but {:.2} GiB of memory are available", gib(*a as u128))?;
                }
                write!(
                    f,
                    "; record fewer instants (a larger record_every, or 0 for final states \
                     only) or run fewer cases per call (monte_carlo runs them in chunks)"
                )
            }
            Self::ThreadPool(e) => write!(f, "could not start the thread pool: {e}"),
            Self::Level(e) => write!(f, "{e}"),
            Self::Cancelled => write!(f, "the batch was cancelled"),
            Self::Event(e) => write!(
                f,
                "stop_at = '{}' needs a plant with an altitude (a lander); this plant has none",
                e.name()
            ),
            Self::Lent {
                what,
                shape,
                expected,
            } => write!(
                f,
                "the {what} lent for the recording have shape {shape:?}; this batch records \
                 {expected:?} (cases, recorded instants, values)"
            ),
        }
    }
}

impl std::error::Error for BatchError {}

impl From<LevelError> for BatchError {
    fn from(e: LevelError) -> Self {
        Self::Level(e)
    }
}

/// The recording and metrics of a batch, in flat row-major buffers.
#[derive(Debug, Clone)]
pub struct BatchOutput<const D: usize> {
    pub n_cases: usize,
    pub state_dim: usize,
    pub diagnostic_dim: usize,
    /// Recorded instants (length n_records).
    pub times: Vec<f64>,
    /// n_cases x n_records x state_dim (empty when the caller lent the recording:
    /// [`RunOptions::recording`]; so are the controls and the diagnostics).
    pub states: Vec<f64>,
    /// n_cases x n_records x D: the applied (saturated) commands.
    pub controls: Vec<f64>,
    /// n_cases x n_records x diagnostic_dim.
    pub diagnostics: Vec<f64>,
    /// n_cases x state_dim.
    pub final_state: Vec<f64>,
    pub metrics: Vec<CaseMetrics<D>>,
    /// The instruction-set level the batch ran at.
    pub level: Level,
}

impl<const D: usize> BatchOutput<D> {
    pub fn n_records(&self) -> usize {
        self.times.len()
    }
}

/// How to run a batch (not what to run: that is the [`Batch`] and its [`SimConfig`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions<'a> {
    /// Worker threads; `None` for rayon's global pool (all cores).
    pub threads: Option<usize>,
    /// Instruction-set level; `None` for `LANDING_KERNEL` or the best the CPU has.
    pub level: Option<Level>,
    /// Raised by another thread to stop the batch early ([`BatchError::Cancelled`]).
    pub cancel: Option<&'a AtomicBool>,
    /// The caller's buffers to write the recording into, instead of fresh ones: a campaign
    /// lends each chunk its rows of the campaign's output, so that the recording's pages are
    /// faulted in once, by the pool, and never copied ([`Lent`]).
    pub recording: Option<Lent>,
}

/// A batch's recording buffers lent by the caller: states (n, records, state_dim), controls
/// (n, records, D) and diagnostics (n, records, diagnostic_dim), each C-ordered `f64`. The
/// batch checks each shape against its own and fills every value (NaN where nothing is
/// recorded), as it does its own buffers.
#[derive(Clone, Copy, Debug)]
pub struct Lent {
    buffers: [(*mut f64, [usize; 3]); 3],
}

// SAFETY: the pointers are written only by the batch that runs with them, each block's rows by
// one thread at a time; `Lent::new`'s contract rules out any other access while it runs
unsafe impl Send for Lent {}
unsafe impl Sync for Lent {}

impl Lent {
    /// The buffers `(pointer, shape)` of the states, the controls and the diagnostics.
    ///
    /// # Safety
    ///
    /// Each pointer is valid for writes of as many `f64` as its shape's product (any pointer
    /// when that is 0) for as long as any batch runs with this value or a copy of it; nothing
    /// else reads or writes them meanwhile; and no two batches run with copies of it at once.
    pub unsafe fn new(
        states: (*mut f64, [usize; 3]),
        controls: (*mut f64, [usize; 3]),
        diagnostics: (*mut f64, [usize; 3]),
    ) -> Self {
        Self {
            buffers: [states, controls, diagnostics],
        }
    }

    /// Buffer `i` as a slice, checked against the `expected` shape (`what` names it).
    fn take(
        &self,
        i: usize,
        what: &'static str,
        expected: [usize; 3],
    ) -> Result<Buffer, BatchError> {
        let (ptr, shape) = self.buffers[i];
        if shape != expected {
            return Err(BatchError::Lent {
                what,
                shape,
                expected,
            });
        }
        let len = expected.iter().product();
        Ok(Buffer::Lent(
            if len == 0 {
                std::ptr::NonNull::dangling().as_ptr()
            } else {
                ptr
            },
            len,
        ))
    }
}

/// One recording buffer: the batch's own, or the caller's ([`Lent`]).
enum Buffer {
    Owned(Vec<f64>),
    Lent(*mut f64, usize),
}

// SAFETY: a lent buffer is written by one thread at a time (`Lent`'s contract)
unsafe impl Send for Buffer {}

impl Buffer {
    fn as_mut_slice(&mut self) -> &mut [f64] {
        match self {
            Self::Owned(v) => v,
            // SAFETY: `Lent::new`'s contract: valid for `len` writes, no one else's meanwhile;
            // `&mut self` makes this the only slice of it
            Self::Lent(ptr, len) => unsafe { std::slice::from_raw_parts_mut(*ptr, *len) },
        }
    }

    /// The values of a buffer of the batch's own; nothing for a lent one (the caller has them).
    fn into_vec(self) -> Vec<f64> {
        match self {
            Self::Owned(v) => v,
            Self::Lent(..) => Vec::new(),
        }
    }
}

/// A batch's run options as a caller outside Rust gives them (counts as signed integers,
/// choices by name), checked in one place by [`RunRequest::compile`]: each against its rule
/// and its cap ([`crate::limits`]), the errors naming the option.
#[derive(Clone, Copy, Debug)]
pub struct RunRequest<'a> {
    pub t_final: f64,
    pub dt: f64,
    /// One of [`IntegratorKind::NAMES`].
    pub integrator: &'a str,
    pub substeps: i64,
    pub record_every: i64,
    pub seed: u64,
    pub first_case: u64,
    pub settle_tolerance: f64,
    /// Whether the settle tolerance is relative to the initial error norm.
    pub settle_relative: bool,
    pub chatter_cutoff: Option<f64>,
    pub threads: Option<i64>,
    /// One of [`Level::NAMES`].
    pub kernel: Option<&'a str>,
    /// One of [`Event::NAMES`]: the event that ends each case.
    pub stop_at: Option<&'a str>,
}

impl RunRequest<'_> {
    /// The configuration and the options of the batch the request describes.
    pub fn compile(&self) -> Result<(SimConfig, RunOptions<'static>), ReadError> {
        let bad = |msg: String| ReadError::Value(msg);
        let integrator = IntegratorKind::from_name(self.integrator).ok_or_else(|| {
            let names = IntegratorKind::NAMES;
            bad(format!(
                "integrator = {:?} is not one of {names:?}",
                self.integrator
            ))
        })?;
        let substeps = self.substeps;
        if substeps < 1 {
            return Err(bad(format!("substeps = {substeps} violates substeps >= 1")));
        }
        within_cap("substeps", substeps as u64, "max_substeps", MAX_SUBSTEPS)?;
        let record_every = self.record_every;
        if record_every < 0 {
            let rule = "record_every >= 0";
            return Err(bad(format!(
                "record_every = {record_every} violates {rule}"
            )));
        }
        let threads = match self.threads {
            None => None,
            Some(k) if k >= 1 => {
                within_cap("threads", k as u64, "max_threads", MAX_THREADS)?;
                Some(k as usize)
            }
            Some(k) => return Err(bad(format!("threads = {k} violates threads >= 1"))),
        };
        let level = self.kernel.map(Level::from_name).transpose();
        let level = level.map_err(|e| bad(format!("kernel: {e}")))?;
        let settle = match self.settle_relative {
            true => Tolerance::Relative(self.settle_tolerance),
            false => Tolerance::Absolute(self.settle_tolerance),
        };
        let cfg = SimConfig::new(
            self.t_final,
            self.dt,
            substeps as u32,
            record_every as u64,
            self.seed,
        )?
        .with_first_case(self.first_case)
        .with_integrator(integrator)
        .with_settle(settle)?;
        let cfg = match self.chatter_cutoff {
            None => cfg,
            Some(hz) => cfg.with_chatter_cutoff(hz)?,
        };
        let stop_at = self.stop_at.map(|name| {
            Event::from_name(name).ok_or_else(|| {
                bad(format!(
                    "stop_at = {name:?} is not one of {:?} or None",
                    Event::NAMES
                ))
            })
        });
        let cfg = cfg.with_stop_at(stop_at.transpose()?);
        let options = RunOptions {
            threads,
            level,
            cancel: None,
            recording: None,
        };
        Ok((cfg, options))
    }
}

/// The memory a batch's output takes, in bytes: the recording, the final states, the
/// per-case metrics, and their conversion to one column per metric (about as large again),
/// which the bindings make while the output is alive.
pub fn output_bytes<const D: usize>(
    cases: usize,
    records: usize,
    state_dim: usize,
    diagnostic_dim: usize,
) -> (u128, u128) {
    let n = cases as u128;
    let recording = n * records as u128 * (state_dim + D + diagnostic_dim) as u128 * 8;
    let per_case = state_dim as u128 * 8 + 2 * std::mem::size_of::<CaseMetrics<D>>() as u128;
    (recording + n * per_case, recording)
}

/// `len` zeros whose pages are not touched yet (the allocator's zeroed memory: fresh pages of
/// the system's), so the threads that write them first fault them in, in parallel.
fn untouched(len: usize, bytes: u128, recording: u128) -> Result<Vec<f64>, BatchError> {
    let refused = || BatchError::Allocation {
        bytes,
        recording,
        available: available_bytes(),
    };
    if len == 0 {
        return Ok(Vec::new());
    }
    let layout = std::alloc::Layout::array::<f64>(len).map_err(|_| refused())?;
    // SAFETY: the layout has a non-zero size; the memory, if given, is `len` f64 of all-zero
    // bits (0.0), allocated by the global allocator with the layout `Vec<f64>` of capacity
    // `len` frees it with
    let ptr = unsafe { std::alloc::alloc_zeroed(layout) }.cast::<f64>();
    if ptr.is_null() {
        return Err(refused());
    }
    // SAFETY: as above: `len` initialised f64 at `ptr`, allocated with `Vec<f64>`'s layout
    Ok(unsafe { Vec::from_raw_parts(ptr, len, len) })
}

fn nan_filled(len: usize, bytes: u128, recording: u128) -> Result<Vec<f64>, BatchError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| BatchError::Allocation {
            bytes,
            recording,
            available: available_bytes(),
        })?;
    v.resize(len, f64::NAN);
    Ok(v)
}

/// `len`-sized disjoint chunks (empty slices when `len` is 0).
fn chunks(buf: &mut [f64], len: usize, n: usize) -> Vec<&mut [f64]> {
    if len == 0 {
        (0..n).map(|_| -> &mut [f64] { &mut [] }).collect()
    } else {
        buf.chunks_mut(len).collect()
    }
}

/// Everything a block reads, shared by the blocks of a batch.
struct Shared<'a, const D: usize, P: PlantModel<D>> {
    batch: &'a Batch<D, P>,
    cfg: &'a SimConfig,
    table: Option<&'a StageTable<D>>,
    cancel: &'a AtomicBool,
}

/// The cases `first .. first + used` of a batch gathered into the lanes of `R`: lane i is case
/// `first + i`, the padding lanes repeat the last case.
pub(crate) struct BlockCases<const D: usize, R: Real, P: PlantModel<D>> {
    pub plant: P::At<R>,
    pub reference: Reference<D, R>,
    pub disturbance: Disturbance<D, R>,
    pub x0: <P::At<R> as Plant<R, D>>::State,
    /// The global index of each lane's case (its random streams' key).
    pub cases: Vec<u64>,
    first: usize,
    used: usize,
}

impl<const D: usize, R: Real, P: PlantModel<D>> BlockCases<D, R, P> {
    #[inline(always)]
    pub(crate) fn gather<L>(
        batch: &Batch<D, P, L>,
        cfg: &SimConfig,
        first: usize,
        used: usize,
    ) -> Self {
        let case = |i: usize| first + i.min(used - 1);
        Self {
            plant: <P::At<R> as Gather<R>>::gather(&|i| batch.plants.get(case(i))),
            reference: Reference::<D, R>::gather(&|i| batch.references.get(case(i))),
            disturbance: Disturbance::<D, R>::gather(&|i| batch.disturbances.get(case(i))),
            x0: <<P::At<R> as Plant<R, D>>::State as State<R>>::from_components(|c| {
                R::from_fn(|i| batch.x0[case(i)].component(c))
            }),
            cases: (0..R::LANES)
                .map(|i| cfg.first_case + case(i) as u64)
                .collect(),
            first,
            used,
        }
    }

    /// The batch's case in lane i.
    #[inline(always)]
    pub(crate) fn case(&self, i: usize) -> usize {
        self.first + i.min(self.used - 1)
    }
}

/// One block's cases: `first .. first + used` of the batch.
struct BlockJob<'a, 'b, const D: usize, P: PlantModel<D>> {
    shared: &'a Shared<'a, D, P>,
    first: usize,
    used: usize,
    out: BlockBuffers<'b, D>,
}

impl<const D: usize, P: PlantModel<D>> LevelJob<D> for BlockJob<'_, '_, D, P> {
    type Blocks = P::Blocks;
    type Output = Result<(), Cancelled>;

    /// Gathers the block's cases into the lanes of `R` and runs them. `#[inline(always)]`: it
    /// is compiled inside each level's function ([`crate::kernel`]), with that level's target
    /// features.
    #[inline(always)]
    fn run<R: Real, K: LawCalls<D, R>>(mut self) -> Result<(), Cancelled> {
        let sh = self.shared;
        let block = BlockCases::<D, R, P>::gather(sh.batch, sh.cfg, self.first, self.used);
        let law = AnyLaw::<D, R>::gather(&|i| sh.batch.laws.get(block.case(i)));
        let set = Setting {
            plant: &block.plant,
            reference: &block.reference,
            disturbance: &block.disturbance,
            table: sh.table,
            cfg: sh.cfg,
        };
        let (x0, cases) = (&block.x0, &block.cases);
        // the outputs were allocated untouched, or lent (`Outputs::allocate_untouched`)
        self.out.fill_nan();
        rollout_block::<D, R, _, K>(&set, &law, x0, cases, self.used, sh.cancel, &mut self.out)
    }
}

/// Checks that the per-case tables have 1 or `n` entries and agree on what a block shares.
fn check_shapes<const D: usize, P: PlantModel<D>>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
) -> Result<(), BatchError> {
    check_cases(batch, cfg, &[("controller", batch.laws.len())])?;
    same(
        "controller",
        &batch.laws,
        <AnyLaw<D> as Gather<f64>>::same_shape,
    )?;
    let width = batch.laws.get(0).diagnostic_width();
    assert!(
        width <= MAX_DIAGNOSTIC_WIDTH,
        "a law records {width} diagnostics, more than {MAX_DIAGNOSTIC_WIDTH}"
    );
    Ok(())
}

fn same<T, F: Fn(&T, &T) -> bool>(
    what: &'static str,
    v: &PerCase<T>,
    f: F,
) -> Result<(), BatchError> {
    let first = v.get(0);
    match v.iter().position(|x| !f(first, x)) {
        Some(case) => Err(BatchError::Shape { what, case }),
        None => Ok(()),
    }
}

/// The checks of [`check_shapes`] on everything but the laws (whose lengths are `laws`).
pub(crate) fn check_cases<const D: usize, P: PlantModel<D>, L>(
    batch: &Batch<D, P, L>,
    cfg: &SimConfig,
    laws: &[(&'static str, usize)],
) -> Result<(), BatchError> {
    let n = batch.x0.len();
    if let (Some(event), Some(x0)) = (cfg.stop_at, batch.x0.first())
        && batch.plants.get(0).altitude(x0).is_none()
    {
        return Err(BatchError::Event(event));
    }
    let tables = [
        ("plant", batch.plants.len()),
        ("reference", batch.references.len()),
        ("disturbance", batch.disturbances.len()),
    ];
    for &(what, len) in tables.iter().chain(laws) {
        if len != 1 && len != n {
            return Err(BatchError::Length {
                what,
                len,
                cases: n,
            });
        }
    }
    same(
        "plant",
        &batch.plants,
        <P::At<f64> as Gather<f64>>::same_shape,
    )?;
    same(
        "reference",
        &batch.references,
        <Reference<D> as Gather<f64>>::same_shape,
    )?;
    same(
        "disturbance",
        &batch.disturbances,
        <Disturbance<D> as Gather<f64>>::same_shape,
    )?;
    Ok(())
}

/// What runs the blocks: a level's lane kernel, or the width-1 instance of the same rollout. A
/// type, not a value, so that the extension, which only ever runs the lanes, does not compile
/// the width-1 rollout for every plant beside them (the Rust tests' [`run_scalar`] does).
trait Kernel: Copy + Send + Sync {
    /// Cases per block for blocks of width `B`.
    fn width<B: kernel::Blocks>(self) -> usize;
    /// The level the output reports.
    fn level(self) -> Level;
    fn run<const D: usize, J: LevelJob<D>>(self, job: J) -> J::Output;
}

impl Kernel for Level {
    fn width<B: kernel::Blocks>(self) -> usize {
        self.lanes::<B>()
    }
    fn level(self) -> Level {
        self
    }
    fn run<const D: usize, J: LevelJob<D>>(self, job: J) -> J::Output {
        kernel::dispatch(self, job)
    }
}

/// The width-1 instance: one case per block, `f64` numbers.
#[derive(Clone, Copy)]
struct Scalar;

impl Kernel for Scalar {
    fn width<B: kernel::Blocks>(self) -> usize {
        1
    }
    fn level(self) -> Level {
        Level::Baseline
    }
    fn run<const D: usize, J: LevelJob<D>>(self, job: J) -> J::Output {
        kernel::run_scalar(job)
    }
}

/// Runs every case of the batch on the current rayon pool.
fn run_here<const D: usize, P: PlantModel<D>, K: Kernel>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
    kernel: K,
    cancel: &AtomicBool,
    lent: Option<Lent>,
) -> Result<BatchOutput<D>, BatchError> {
    let n = batch.x0.len();
    let nx = P::STATE_DIM;
    // the law's diagnostics, then the navigation's estimate when the plant has a sensor
    let nd = batch.laws.get(0).diagnostic_width() + batch.plants.get(0).navigation_width();
    let nr = cfg.n_records();
    let mut o = Outputs::<D>::allocate_untouched(n, nr, nx, nd, lent)?;
    let table = shared_table(batch, cfg);
    let shared = Shared {
        batch,
        cfg,
        table: table.as_ref(),
        cancel,
    };
    let (w, level) = (kernel.width::<P::Blocks>(), kernel.level());
    let shared = &shared;
    let jobs = o
        .blocks(w, nr, nx, nd)
        .into_iter()
        .enumerate()
        .map(|(b, out)| -> Job<'_, Result<(), Cancelled>> {
            let job = BlockJob {
                shared,
                first: b * w,
                used: w.min(n - b * w),
                out,
            };
            Box::new(move || kernel.run(job))
        })
        .collect();
    parallel::try_each(jobs).map_err(|Cancelled| BatchError::Cancelled)?;
    Ok(o.finish(cfg, nx, nd, level))
}

/// A batch's output buffers, allocated once, before any case runs (the recording's may be the
/// caller's: [`Lent`]).
pub(crate) struct Outputs<const D: usize> {
    states: Buffer,
    controls: Buffer,
    diagnostics: Buffer,
    final_state: Vec<f64>,
    metrics: Vec<CaseMetrics<D>>,
}

impl<const D: usize> Outputs<D> {
    /// The buffers of `n` cases, `nr` records of `nx` states and `nd` diagnostics (the
    /// recording's `lent` when given, checked against these shapes and filled with NaN), refused
    /// before anything is allocated when they would not fit: Linux grants virtual memory freely
    /// and kills the process when the pages are touched, so a failed allocation is no
    /// protection.
    pub(crate) fn allocate(
        n: usize,
        nr: usize,
        nx: usize,
        nd: usize,
        lent: Option<Lent>,
    ) -> Result<Self, BatchError> {
        let mut o = Self::with_recording(n, nr, nx, nd, lent, nan_filled)?;
        if lent.is_some() {
            for b in [&mut o.states, &mut o.controls, &mut o.diagnostics] {
                b.as_mut_slice().fill(f64::NAN);
            }
        }
        Ok(o)
    }

    /// [`Outputs::allocate`] with the recording's pages left untouched (and a lent recording
    /// left as it is): each block job fills its own slices with NaN first
    /// ([`BlockBuffers::fill_nan`]), so the recording's pages are faulted in by the pool's
    /// threads in parallel, not by one thread before the run.
    pub(crate) fn allocate_untouched(
        n: usize,
        nr: usize,
        nx: usize,
        nd: usize,
        lent: Option<Lent>,
    ) -> Result<Self, BatchError> {
        Self::with_recording(n, nr, nx, nd, lent, untouched)
    }

    fn with_recording(
        n: usize,
        nr: usize,
        nx: usize,
        nd: usize,
        lent: Option<Lent>,
        recording_buffer: fn(usize, u128, u128) -> Result<Vec<f64>, BatchError>,
    ) -> Result<Self, BatchError> {
        let (mut bytes, recording) = output_bytes::<D>(n, nr, nx, nd);
        if lent.is_some() {
            // the caller holds the recording already
            bytes -= recording;
        }
        let available = available_bytes();
        if bytes > isize::MAX as u128 || available.is_some_and(|a| bytes > u128::from(a)) {
            return Err(BatchError::Allocation {
                bytes,
                recording,
                available,
            });
        }
        let mut metrics = Vec::new();
        metrics
            .try_reserve_exact(n)
            .map_err(|_| BatchError::Allocation {
                bytes,
                recording,
                available,
            })?;
        metrics.resize(n, CaseMetrics::new());
        let buffer = |i: usize, what: &'static str, width: usize| match lent {
            Some(l) => l.take(i, what, [n, nr, width]),
            None => recording_buffer(n * nr * width, bytes, recording).map(Buffer::Owned),
        };
        Ok(Self {
            states: buffer(0, "states", nx)?,
            controls: buffer(1, "controls", D)?,
            diagnostics: buffer(2, "diagnostics", nd)?,
            final_state: nan_filled(n * nx, bytes, recording)?,
            metrics,
        })
    }

    /// Disjoint per-block views of `w` cases each.
    pub(crate) fn blocks(
        &mut self,
        w: usize,
        nr: usize,
        nx: usize,
        nd: usize,
    ) -> Vec<BlockBuffers<'_, D>> {
        let blocks = self.metrics.len().div_ceil(w);
        chunks(self.states.as_mut_slice(), w * nr * nx, blocks)
            .into_iter()
            .zip(chunks(self.controls.as_mut_slice(), w * nr * D, blocks))
            .zip(chunks(self.diagnostics.as_mut_slice(), w * nr * nd, blocks))
            .zip(chunks(&mut self.final_state, w * nx, blocks))
            .zip(self.metrics.chunks_mut(w))
            .map(|((((s, c), d), f), m)| BlockBuffers {
                states: s,
                controls: c,
                diagnostics: d,
                final_state: f,
                metrics: m,
            })
            .collect()
    }

    pub(crate) fn finish(
        self,
        cfg: &SimConfig,
        nx: usize,
        nd: usize,
        level: Level,
    ) -> BatchOutput<D> {
        BatchOutput {
            n_cases: self.metrics.len(),
            state_dim: nx,
            diagnostic_dim: nd,
            times: cfg.record_times(),
            states: self.states.into_vec(),
            controls: self.controls.into_vec(),
            diagnostics: self.diagnostics.into_vec(),
            final_state: self.final_state,
            metrics: self.metrics,
            level,
        }
    }
}

/// The deterministic disturbance evaluated once per stage for the whole batch, when every
/// case shares it.
pub(crate) fn shared_table<const D: usize, P: PlantModel<D>, L>(
    batch: &Batch<D, P, L>,
    cfg: &SimConfig,
) -> Option<StageTable<D>> {
    let shared = batch.disturbances.is_shared() && batch.disturbances.get(0).is_time_varying();
    if shared {
        StageTable::new(batch.disturbances.get(0), cfg)
    } else {
        None
    }
}

/// Checks that initial states of shape `[n, columns]` suit a plant of `width` state
/// components: at least one case, at most the case cap.
pub fn check_initial_states([n, columns]: [usize; 2], width: usize) -> Result<(), ReadError> {
    if columns != width || n == 0 {
        return Err(ReadError::value(format!(
            "x0 has shape ({n}, {columns}); this plant takes (N, {width}), N >= 1"
        )));
    }
    within_cap("x0 cases N", n as u64, "max_cases", MAX_CASES)
}

/// Runs every case of the batch.
pub fn run<const D: usize, P: PlantModel<D>>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
    options: &RunOptions<'_>,
) -> Result<BatchOutput<D>, BatchError> {
    check_shapes(batch, cfg)?;
    let level = Level::resolve(options.level)?;
    let never = AtomicBool::new(false);
    let cancel = options.cancel.unwrap_or(&never);
    run_on(
        batch,
        cfg,
        level,
        options.threads,
        cancel,
        options.recording,
    )
}

fn run_on<const D: usize, P: PlantModel<D>, K: Kernel>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
    kernel: K,
    threads: Option<usize>,
    cancel: &AtomicBool,
    lent: Option<Lent>,
) -> Result<BatchOutput<D>, BatchError> {
    if batch.x0.is_empty() {
        return run_here(batch, cfg, kernel, cancel, lent);
    }
    let pool = parallel::pool(threads).map_err(BatchError::ThreadPool)?;
    parallel::on_pool(
        pool.as_ref(),
        Box::new(|| run_here(batch, cfg, kernel, cancel, lent)),
    )
}

/// Runs every case alone with `f64` numbers: the width-1 instance of the same generic
/// rollout the lane kernels run, which tests compare them with bit for bit. As slow as a
/// scalar loop; not for production. The output's `level` is `Baseline`.
pub fn run_scalar<const D: usize, P: PlantModel<D>>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
    threads: Option<usize>,
) -> Result<BatchOutput<D>, BatchError> {
    check_shapes(batch, cfg)?;
    run_on(batch, cfg, Scalar, threads, &AtomicBool::new(false), None)
}

/// [`run`] with `threads` worker threads (`None`: all cores) at the best level.
pub fn run_with_threads<const D: usize, P: PlantModel<D>>(
    batch: &Batch<D, P>,
    cfg: &SimConfig,
    threads: Option<usize>,
) -> Result<BatchOutput<D>, BatchError> {
    run(
        batch,
        cfg,
        &RunOptions {
            threads,
            ..Default::default()
        },
    )
}
