//! A batch under a law computed outside the core, for many cases at once.
//!
//! A built-in law runs inside each block's lanes, and a block runs through all its periods
//! ([`crate::rollout::rollout_block`]). A law written in Python needs the other order: it is
//! called once per control instant on the law inputs of many cases (the batch, or a slice of it:
//! [`ExternalLaw::cases_per_call`]), holding the interpreter, while the plant's periods between
//! two calls run without it. So every block of the slice is started and kept
//! ([`crate::rollout::Block`]: the plant's state, its integrator, the metric accumulators and
//! the recording cursor), and each control instant is one call of the law on the gathered
//! inputs, then one period of every block, with the commands the call returned. The blocks'
//! periods and metrics are the same code as a built-in law's, so a law computed outside gives
//! the bits that law built in would.
//!
//! The law's memory (integrators, adaptive terms) is the law's own business, kept outside
//! between calls; the core sees commands and diagnostics only.

mod plant;

pub use plant::{ExternalPlant, Laws, MAX_EXTERNAL_STATE, StateLayout, run_external_plant};

use std::any::Any;
use std::mem::MaybeUninit;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::parallel::{self, Job};
use nalgebra::SVector;

use crate::batch::{
    Batch, BatchError, BatchOutput, BlockCases, Outputs, RunOptions, check_cases, shared_table,
};
use crate::control::LawInput;
use crate::disturbance::Disturbance;
use crate::kernel::{self, LawCalls, Level, LevelJob};
use crate::lanes::Real;
use crate::plant::{Plant, PlantModel};
use crate::reference::Reference;
use crate::rollout::{
    Block, BlockBuffers, MAX_DIAGNOSTIC_WIDTH, Period, Setting, SimConfig, StageTable,
};

/// The law inputs of the cases of a call at one control instant: `n x D` row-major arrays,
/// case after case (the quantities of [`LawInput`]). A case that has stopped keeps its last
/// inputs; its commands are ignored.
#[derive(Clone, Debug)]
pub struct Inputs<const D: usize> {
    /// The index in the batch of the first case these inputs hold (a law called on the batch a
    /// slice at a time, [`ExternalLaw::cases_per_call`], sees each slice's).
    pub first: usize,
    /// Which of the driver's two interleaved slices these inputs belong to, 0 or 1 (0 when
    /// the slices run one after another): calls for the two alternate, so a law that keeps
    /// buffers or state per slice keys them by it. A track's next slice starts at `k = 0`.
    pub track: usize,
    /// Whether the driver has written these inputs into the memory the law's
    /// [`ExternalLaw::staging`] lent for this call (the fields here are then stale).
    pub staged: bool,
    /// The control instant, s.
    pub t: f64,
    /// Index of the control instant, `t = k dt` (`k = steps` at t_final, whose command is
    /// recorded and checked but not applied).
    pub k: u64,
    pub e: Vec<f64>,
    pub de: Vec<f64>,
    /// The reference's position, velocity and acceleration.
    pub position: Vec<f64>,
    pub velocity: Vec<f64>,
    pub acceleration: Vec<f64>,
    pub drift: Vec<f64>,
    pub inertia: Vec<f64>,
}

impl<const D: usize> Inputs<D> {
    fn new(n: usize) -> Self {
        let z = || vec![0.0; n * D];
        Self {
            first: 0,
            track: 0,
            staged: false,
            t: 0.0,
            k: 0,
            e: z(),
            de: z(),
            position: z(),
            velocity: z(),
            acceleration: z(),
            drift: z(),
            inertia: z(),
        }
    }

    /// The cases these inputs hold.
    pub fn cases(&self) -> usize {
        self.e.len() / D
    }

    /// The fields in the order of [`LawInput`]'s quantities: e, de, the reference's position,
    /// velocity and acceleration, drift, inertia.
    pub fn fields(&self) -> [&[f64]; 7] {
        let Self {
            e,
            de,
            position,
            velocity,
            acceleration,
            drift,
            inertia,
            ..
        } = self;
        [e, de, position, velocity, acceleration, drift, inertia].map(|v| v.as_slice())
    }

    /// The fields as [`fields`](Self::fields) orders them, to write.
    pub fn fields_mut(&mut self) -> [&mut [f64]; 7] {
        let Self {
            e,
            de,
            position,
            velocity,
            acceleration,
            drift,
            inertia,
            ..
        } = self;
        [e, de, position, velocity, acceleration, drift, inertia].map(|v| v.as_mut_slice())
    }

    /// Writes case `i`'s row of every field.
    fn write(&mut self, i: usize, input: &LawInput<D, f64>) {
        let rows = i * D..(i + 1) * D;
        for (to, from) in self.fields_mut().into_iter().zip(quantities(input)) {
            to[rows.clone()].copy_from_slice(from.as_slice());
        }
    }

    /// Disjoint views of `w` cases each, one per block.
    fn rows(&mut self, w: usize) -> Vec<InputRows<'_>> {
        InputRows::split(self.fields_mut(), w * D)
    }
}

/// The quantities of a law's input in the order of [`Inputs::fields`].
fn quantities<const D: usize, R: Real>(input: &LawInput<D, R>) -> [&SVector<R, D>; 7] {
    let r = &input.reference;
    [
        &input.e,
        &input.de,
        &r.position,
        &r.velocity,
        &r.acceleration,
        &input.drift,
        &input.inertia,
    ]
}

/// One block's rows of [`Inputs`], field after field.
struct InputRows<'a>([&'a mut [f64]; 7]);

impl<'a> InputRows<'a> {
    /// Views of `len` values of each field, one per block (the last may be shorter).
    fn split(fields: [&'a mut [f64]; 7], len: usize) -> Vec<Self> {
        let mut chunks = fields.map(|v| v.chunks_mut(len));
        // every field has as many chunks as `e`
        (0..chunks[0].len())
            .map(|_| {
                InputRows(
                    chunks
                        .each_mut()
                        .map(|c| c.next().expect("the input fields have one length")),
                )
            })
            .collect()
    }

    /// Writes the first `used` lanes of `input`, field after field: the rows of each field are
    /// `D` consecutive values per case, so each field's `used x D` values go out in one run
    /// ([`Real::write_rows`]: for a whole block of three axes, shuffled whole registers). Inlined
    /// into the period, so that it runs with the level's instructions: out of line, the values
    /// went out one at a time, 13 % of a Python law's run (BENCHMARKS.md).
    #[inline(always)]
    fn write<const D: usize, R: Real>(&mut self, input: &LawInput<D, R>, used: usize) {
        for (to, from) in self.0.iter_mut().zip(quantities(input)) {
            R::write_rows(&from.data.0[0], to, used);
        }
    }
}

/// Memory a law lends the driver for the inputs of its next call on a track: seven buffers of
/// `len` values, one per field of [`Inputs::fields`], in that order, holding the inputs of the
/// call just made on the track. The driver writes the rows of the cases still running there,
/// straight from their blocks; a case that has stopped keeps its last inputs.
pub struct Staging {
    fields: [*mut f64; 7],
    len: usize,
}

// SAFETY: the lender promises (`Staging::new`) that the memory is the driver's alone until the
// track's next call, so the thread that writes it may be any
unsafe impl Send for Staging {}

impl Staging {
    /// # Safety
    ///
    /// Each pointer must be valid for writes of `len` f64 values, and nothing else may read or
    /// write that memory until the next [`ExternalLaw::command`] on the track it was lent for.
    pub unsafe fn new(fields: [*mut f64; 7], len: usize) -> Self {
        Self { fields, len }
    }

    /// The lent memory as views of `w` cases each, one per block.
    fn rows<const D: usize>(&mut self, w: usize) -> Vec<InputRows<'_>> {
        let len = self.len;
        // SAFETY: `new`'s contract: `len` values each, ours alone until the next call; the
        // views borrow `self` mutably, so none outlives the loan or aliases another
        let fields = self
            .fields
            .map(|p| unsafe { std::slice::from_raw_parts_mut(p, len) });
        InputRows::split(fields, w * D)
    }
}

/// A law computed outside the core: once per control instant, for the cases of a call (the
/// batch, or a slice of it).
pub trait ExternalLaw<const D: usize>: Send {
    /// What the law's failure carries (the bindings: the Python exception).
    type Error: Send;

    /// Diagnostic values per case and instant (at most [`MAX_DIAGNOSTIC_WIDTH`]).
    fn diagnostic_width(&self) -> usize;

    /// At most this many cases per call. A batch larger than that runs a slice of cases at a
    /// time through all its control instants: the slice's blocks and the law's arrays then
    /// stay in the caches between two calls, where the whole batch's would stream through
    /// memory at every instant. The slices hold whole blocks, in order; on one thread they run
    /// one after another, on more two at a time, their calls alternating ([`Inputs::track`]);
    /// each slice's calls come in time order, and the slices start in order.
    fn cases_per_call(&self) -> usize {
        usize::MAX
    }

    /// Called with `true` on the thread that is about to call [`command`](Self::command), before
    /// the batch's first call, and with `false` after its last, on the same thread, whether
    /// the batch ran to its end or stopped (cancelled, the law failed). Every call is made on
    /// that thread. (The bindings keep the interpreter's record of the thread between the two:
    /// made and dropped at every call, it cost more than the call.)
    fn on_thread(&mut self, _entering: bool) {}

    /// Memory of the law's own into which the driver may write the inputs of the next call on
    /// `track` (of `cases` cases) before making it: asked after every call on the track, on
    /// the thread that made it. A law that hands its inputs on in buffers of its own (the
    /// bindings: numpy arrays) lends them, holding the inputs of the call just made
    /// ([`Staging`]), so that each running block writes its rows there as it ends its period,
    /// on whichever thread advances the plant, and no copy is made on the thread that calls
    /// the law ([`Inputs::staged`] says that they were written there; the fields of the
    /// [`Inputs`] are then stale). A law that lends memory for a slice lends it at each of the
    /// slice's later calls. None, the default: the law reads the [`Inputs`].
    fn staging(&mut self, _track: usize, _cases: usize) -> Option<Staging> {
        None
    }

    /// Writes the commanded generalized accelerations of the call's cases at `inputs.t` into
    /// `command` (`n x D`) and its diagnostics into `diagnostics` (`n x width`).
    fn command(
        &mut self,
        inputs: &Inputs<D>,
        command: &mut [f64],
        diagnostics: &mut [f64],
    ) -> Result<(), Self::Error>;
}

/// Why a batch under an external law stopped.
#[derive(Debug)]
pub enum ExternalError<E> {
    Batch(BatchError),
    /// The law failed; the batch's output is dropped.
    Law(E),
    /// The plant failed (a plant computed outside, [`run_external_plant`]); the batch's output
    /// is dropped.
    Plant(E),
}

impl<E> From<BatchError> for ExternalError<E> {
    fn from(e: BatchError) -> Self {
        Self::Batch(e)
    }
}

/// A block kept between control periods, with the parts of its setting the batch gives per
/// case, typed by the level's lane type (held as `dyn Any` by the driver, which knows only the
/// level).
struct Kept<const D: usize, R: Real, P: Plant<R, D>> {
    own: Parts<D, R, P>,
    block: Block<D, R, P>,
}

type Held = Box<dyn Any + Send>;

/// Some of a block's plant, reference and disturbance, gathered into lanes: a [`Kept`] block
/// holds those the batch gives per case, and the batch those it shares among its cases,
/// gathered once at its level ([`GatherShared`]). Every block of a slice reads the one shared
/// copy at each period, where each kept its own: the lines of them a period touches, a
/// quarter of a Mars block's, came back from beyond the second-level cache for every block of
/// a slice that the cache does not hold (a law returning zeros, 10^4 Mars cases, 4096 a call,
/// one thread: 0.85x; BENCHMARKS.md). A shared value's lanes are the same whichever block
/// gathers them, so the same bits.
struct Parts<const D: usize, R: Real, P: Plant<R, D>> {
    plant: Option<P>,
    reference: Option<Reference<D, R>>,
    disturbance: Option<Disturbance<D, R>>,
}

impl<const D: usize, R: Real, P: Plant<R, D>> Parts<D, R, P> {
    /// A block's setting: each part its own, or else the batch's shared one.
    fn setting<'s>(
        &'s self,
        shared: &'s Self,
        common: &'s Common<'s, D, impl PlantModel<D>>,
    ) -> Setting<'s, D, R, P> {
        const GATHERED: &str = "each part of a block's setting is its own or shared";
        Setting {
            plant: self
                .plant
                .as_ref()
                .or(shared.plant.as_ref())
                .expect(GATHERED),
            reference: self
                .reference
                .as_ref()
                .or(shared.reference.as_ref())
                .expect(GATHERED),
            disturbance: self
                .disturbance
                .as_ref()
                .or(shared.disturbance.as_ref())
                .expect(GATHERED),
            table: common.table,
            cfg: common.cfg,
        }
    }
}

/// The parts of a gathered block that the batch shares (`shared`), or those it gives per case.
fn parts<const D: usize, R: Real, P: PlantModel<D>>(
    cases: BlockCases<D, R, P>,
    batch: &Batch<D, P, ()>,
    shared: bool,
) -> Parts<D, R, P::At<R>> {
    let keep = |is_shared: bool| is_shared == shared;
    Parts {
        plant: keep(batch.plants.is_shared()).then_some(cases.plant),
        reference: keep(batch.references.is_shared()).then_some(cases.reference),
        disturbance: keep(batch.disturbances.is_shared()).then_some(cases.disturbance),
    }
}

/// Gathers the batch's shared [`Parts`] at the level (held as `dyn Any`, as a [`Kept`] block is).
struct GatherShared<'a, const D: usize, P: PlantModel<D>> {
    batch: &'a Batch<D, P, ()>,
    cfg: &'a SimConfig,
}

impl<const D: usize, P: PlantModel<D>> LevelJob<D> for GatherShared<'_, D, P> {
    type Blocks = P::Blocks;
    type Output = Box<dyn Any + Send + Sync>;

    #[inline(always)]
    fn run<R: Real, K: LawCalls<D, R>>(self) -> Self::Output {
        let cases = BlockCases::<D, R, P>::gather(self.batch, self.cfg, 0, 1);
        Box::new(parts(cases, self.batch, true))
    }
}

/// What every block job reads.
struct Common<'a, const D: usize, P: PlantModel<D>> {
    batch: &'a Batch<D, P, ()>,
    cfg: &'a SimConfig,
    table: Option<&'a StageTable<D>>,
    nd: usize,
    level: Level,
    /// The batch's shared [`Parts`] at `level`.
    shared: Box<dyn Any + Send + Sync>,
}

/// Starts the block of cases `first .. first + used` and writes its inputs at t = 0.
struct Start<'a, 'b, const D: usize, P: PlantModel<D>> {
    common: &'a Common<'a, D, P>,
    first: usize,
    used: usize,
    rows: InputRows<'b>,
}

impl<const D: usize, P: PlantModel<D>> LevelJob<D> for Start<'_, '_, D, P> {
    type Blocks = P::Blocks;
    type Output = Held;

    #[inline(always)]
    fn run<R: Real, K: LawCalls<D, R>>(mut self) -> Held {
        let co = self.common;
        let g = BlockCases::<D, R, P>::gather(co.batch, co.cfg, self.first, self.used);
        let set = Setting {
            plant: &g.plant,
            reference: &g.reference,
            disturbance: &g.disturbance,
            table: co.table,
            cfg: co.cfg,
        };
        let block = Block::start(&set, &g.x0, &g.cases, self.used);
        self.rows.write(block.input(), self.used);
        Box::new(Kept {
            own: parts(g, co.batch, false),
            block,
        })
    }
}

/// One block's control period `k` under the commands the law returned; at `k = steps`, or once
/// every lane has stopped, the block's finish.
struct Step<'a, 'b, 'c, const D: usize, P: PlantModel<D>> {
    common: &'a Common<'a, D, P>,
    k: u64,
    held: &'b mut Held,
    used: usize,
    command: &'b [f64],
    diagnostics: &'b [f64],
    rows: InputRows<'b>,
    out: &'b mut BlockBuffers<'c, D>,
}

impl<const D: usize, P: PlantModel<D>> LevelJob<D> for Step<'_, '_, '_, D, P> {
    type Blocks = P::Blocks;
    /// Whether the block goes on (false once it is finished).
    type Output = bool;

    #[inline(always)]
    fn run<R: Real, K: LawCalls<D, R>>(mut self) -> bool {
        let co = self.common;
        let kept = self
            .held
            .downcast_mut::<Kept<D, R, P::At<R>>>()
            .expect("a block is stepped at the level it was started at");
        let shared = co
            .shared
            .downcast_ref::<Parts<D, R, P::At<R>>>()
            .expect("the shared parts are gathered at the batch's level");
        let set = kept.own.setting(shared, co);
        let (used, nd) = (self.used, co.nd);
        // whole registers of rows, shuffled: read a lane at a time, the commands took 12 % of
        // the samples of a run under a law returning zeros, and read so the engine's share is
        // 3 % smaller (BENCHMARKS.md)
        let a = SVector::<R, D>::from(R::read_rows::<D>(self.command, used));
        // only the law's `nd` diagnostics are set: zeroing all the room (1 kB a block at
        // AVX-512) showed in a profile of a Python law's run
        let mut room = [const { MaybeUninit::<R>::uninit() }; MAX_DIAGNOSTIC_WIDTH];
        for (c, d) in room[..nd].iter_mut().enumerate() {
            d.write(crate::lanes::column(self.diagnostics, used, nd, c));
        }
        // SAFETY: the first `nd` values were written just above
        let diag = unsafe { std::slice::from_raw_parts(room.as_ptr().cast::<R>(), nd) };
        if self.k == co.cfg.steps {
            kept.block.finish(&set, Some((&a, diag)), self.out);
            return false;
        }
        let period = Period {
            block: &mut kept.block,
            set: &set,
            k: self.k,
            a: &a,
            diag,
            out: &mut *self.out,
        };
        if !K::out_of_line(period) {
            kept.block.finish(&set, None, self.out);
            return false;
        }
        self.rows.write(kept.block.input(), used);
        true
    }
}

/// Runs every case of the batch under `law`, a slice of at most `law.cases_per_call()` cases at
/// a time: the law is called once per control instant (`steps + 1` times, the last at t_final,
/// while a case of the slice still runs) with the inputs of the slice's cases; between two
/// calls every block's period of the slice runs. On one thread the slices run one after
/// another. On more, two slices run interleaved ([`Driver::interleaved`]): while the law is
/// called on one, the other thread advances the other's plant, so the law's calls, which hold
/// the interpreter on one core, overlap the periods. Cancelled, at the next instant, when
/// `options.cancel` is raised; stopped when the law fails. The output and its bits are those
/// [`crate::batch::run`] gives for the same law built in, whatever the slices or threads.
pub fn run_external<const D: usize, P: PlantModel<D>, X: ExternalLaw<D>>(
    batch: &Batch<D, P, ()>,
    cfg: &SimConfig,
    options: &RunOptions<'_>,
    law: &mut X,
) -> Result<BatchOutput<D>, ExternalError<X::Error>> {
    check_cases(batch, cfg, &[])?;
    let level = Level::resolve(options.level).map_err(BatchError::from)?;
    let pool = parallel::pool(options.threads).map_err(BatchError::ThreadPool)?;
    let pool = pool.as_ref();
    let never = AtomicBool::new(false);
    let cancel = options.cancel.unwrap_or(&never);

    let n = batch.x0.len();
    let nx = P::STATE_DIM;
    let nd = law.diagnostic_width();
    assert!(
        nd <= MAX_DIAGNOSTIC_WIDTH,
        "a law records {nd} diagnostics, more than {MAX_DIAGNOSTIC_WIDTH}"
    );
    let nr = cfg.n_records();
    // the output's rows: the law's diagnostics, then the navigation's estimate
    let out_nd = nd + batch.plants.get(0).navigation_width();
    let mut outputs = Outputs::<D>::allocate(n, nr, nx, out_nd, options.recording)?;
    if n == 0 {
        return Ok(outputs.finish(cfg, nx, out_nd, level));
    }
    let table = shared_table(batch, cfg);
    let common = Common {
        batch,
        cfg,
        table: table.as_ref(),
        nd,
        level,
        shared: kernel::dispatch(level, GatherShared { batch, cfg }),
    };
    let w = level.lanes::<P::Blocks>();
    let threads = pool.map_or_else(rayon::current_num_threads, |p| p.current_num_threads());
    let (slices, interleaved) = plan(n, w, law.cases_per_call(), threads);
    let driver = Driver {
        common: &common,
        w,
        n,
        threads,
        cancel,
    };
    let mut buffers = outputs.blocks(w, nr, nx, out_nd);
    // each slice's output blocks
    let mut rest = &mut buffers[..];
    let mut parts = Vec::with_capacity(slices.len());
    for s in &slices {
        let (part, tail) = rest.split_at_mut(s.len());
        parts.push((s.clone(), part));
        rest = tail;
    }
    parallel::on_pool(
        pool,
        Box::new(|| {
            law.on_thread(true);
            let out = if interleaved {
                driver.interleaved(law, parts)
            } else {
                parts
                    .into_iter()
                    .try_for_each(|(s, part)| driver.one_after_another(law, s, part))
            };
            law.on_thread(false);
            out
        }),
    )?;
    drop(buffers);
    Ok(outputs.finish(cfg, nx, out_nd, level))
}

/// The batch's slices (ranges of whole blocks), and whether two run interleaved. One after
/// another, every slice but the last holds `per_call` cases' worth of whole blocks (at least
/// one). Interleaved (more than one thread, and enough cases that two calls per instant cost
/// less than what the overlap saves: [`MIN_INTERLEAVED`]), the slices are an even number
/// of near-equal ones, so that no slice runs alone at the end.
fn plan(
    n: usize,
    w: usize,
    per_call: usize,
    threads: usize,
) -> (Vec<std::ops::Range<usize>>, bool) {
    let blocks = n.div_ceil(w);
    let per_slice = if per_call >= n {
        blocks
    } else {
        (per_call / w).max(1)
    };
    let count = blocks.div_ceil(per_slice);
    let interleaved = threads > 1 && blocks > 1 && (count > 1 || n >= 2 * MIN_INTERLEAVED);
    if !interleaved {
        let slices = (0..count)
            .map(|i| i * per_slice..blocks.min((i + 1) * per_slice))
            .collect();
        return (slices, false);
    }
    let count = (count.max(2).next_multiple_of(2)).min(blocks);
    let (size, more) = (blocks / count, blocks % count);
    let mut first = 0;
    let slices = (0..count)
        .map(|i| {
            let len = size + usize::from(i < more);
            first += len;
            first - len..first
        })
        .collect();
    (slices, true)
}

/// A batch that fits in one call is cut in two interleaved slices from twice this many cases
/// on (with more than one thread): below, the second call per instant costs more than the
/// overlap saves. (A batch cut into slices anyway, by `cases_per_call`, always interleaves.)
const MIN_INTERLEAVED: usize = 512;

/// How the slices of a batch are run (see [`run_external`]).
struct Driver<'a, 'c, const D: usize, P: PlantModel<D>> {
    common: &'a Common<'c, D, P>,
    /// Lanes per block.
    w: usize,
    /// Cases in the batch.
    n: usize,
    threads: usize,
    cancel: &'a AtomicBool,
}

impl<const D: usize, P: PlantModel<D>> Driver<'_, '_, D, P> {
    fn check<E>(&self) -> Result<(), ExternalError<E>> {
        if self.cancel.load(Ordering::Relaxed) {
            return Err(BatchError::Cancelled.into());
        }
        Ok(())
    }

    /// The slice `blocks` through all its control instants: at each, the law's call, then one
    /// period of every block still running, with the commands it returned.
    fn one_after_another<X: ExternalLaw<D>>(
        &self,
        law: &mut X,
        blocks: std::ops::Range<usize>,
        buffers: &mut [BlockBuffers<'_, D>],
    ) -> Result<(), ExternalError<X::Error>> {
        let mut slice = Running::start(self, blocks, buffers, 0);
        // On one thread the periods run on the calling thread. On more, the slice is the whole
        // batch (a batch cut into slices runs them interleaved, `plan`): one too small to be
        // cut in two, or a single block. It runs its first two periods on the calling thread
        // too and spreads the rest over the pool only if the second (the first touches fresh
        // memory) took at least `SPREAD_MIN`: handing a short period to the pool and waiting
        // for it costs more than the period. The same bits either way.
        let mut spread = (self.threads == 1).then_some(false);
        while slice.live() {
            self.check()?;
            slice.call(law).map_err(ExternalError::Law)?;
            match spread {
                Some(spread) => slice.advance(spread),
                None => {
                    let (start, second) = (Instant::now(), slice.k == 1);
                    slice.advance(false);
                    if second {
                        spread = Some(start.elapsed() >= SPREAD_MIN);
                    }
                }
            }
        }
        Ok(())
    }

    /// The slices two at a time, on two tracks. At each turn the law is called, on this
    /// thread, on the inputs of one track's slice, while the pool advances the other track's
    /// slice by the period its last call commanded (or, once that slice has ended, starts the
    /// track's next slice); then the tracks change roles. Each slice sees the calls and periods
    /// it would see alone, in the same order, so the bits are those of
    /// [`one_after_another`](Self::one_after_another).
    fn interleaved<X: ExternalLaw<D>>(
        &self,
        law: &mut X,
        slices: Vec<(std::ops::Range<usize>, &mut [BlockBuffers<'_, D>])>,
    ) -> Result<(), ExternalError<X::Error>> {
        let mut next = slices.into_iter();
        let mut tracks: [Option<Running<'_, '_, '_, '_, D, P>>; 2] = [None, None];
        tracks[0] = next.next().map(|(s, b)| Running::start(self, s, b, 0));
        let mut turn = 0;
        while tracks.iter().any(Option::is_some) {
            self.check()?;
            let [a, b] = &mut tracks;
            let (calling, stepping, track) = if turn == 0 { (a, b, 1) } else { (b, a, 0) };
            let next = &mut next;
            let (called, ()) = parallel::both(
                Box::new(|| match calling.as_mut().filter(|s| s.live()) {
                    Some(s) => s.call(law),
                    None => Ok(()),
                }),
                Box::new(move || {
                    if let Some(s) = stepping.as_mut().filter(|s| s.commanded) {
                        s.advance(true);
                    }
                    if !stepping.as_ref().is_some_and(Running::live) {
                        *stepping = next.next().map(|(s, b)| Running::start(self, s, b, track));
                    }
                }),
            );
            called.map_err(ExternalError::Law)?;
            turn = 1 - turn;
        }
        Ok(())
    }
}

/// A slice of consecutive blocks of the batch on its way through the control instants: its
/// blocks, the law's inputs for its cases at instant `k`, and the commands of the last call.
struct Running<'a, 'b, 'c, 'd, const D: usize, P: PlantModel<D>> {
    driver: &'a Driver<'a, 'd, D, P>,
    /// The slice's cases.
    m: usize,
    inputs: Inputs<D>,
    command: Vec<f64>,
    diagnostics: Vec<f64>,
    held: Vec<Held>,
    running: Vec<bool>,
    buffers: &'b mut [BlockBuffers<'c, D>],
    /// Blocks per task when the period is spread over the pool.
    group: usize,
    k: u64,
    /// The law was called at `k`, and the period `k` has not run.
    commanded: bool,
    /// Where the law reads the next call's inputs, when it lent memory for them.
    staging: Option<Staging>,
}

impl<'a, 'b, 'c, 'd, const D: usize, P: PlantModel<D>> Running<'a, 'b, 'c, 'd, D, P> {
    /// Starts the blocks `blocks` (their inputs at t = 0 written), on `track` (see
    /// [`Inputs::track`]).
    fn start(
        driver: &'a Driver<'a, 'd, D, P>,
        blocks: std::ops::Range<usize>,
        buffers: &'b mut [BlockBuffers<'c, D>],
        track: usize,
    ) -> Self {
        let (common, w) = (driver.common, driver.w);
        let first = blocks.start * w;
        let m = driver.n.min(blocks.end * w) - first;
        let used = |b: usize| w.min(m - b * w);
        let mut inputs = Inputs::<D>::new(m);
        inputs.first = first;
        inputs.track = track;
        let jobs = inputs
            .rows(w)
            .into_iter()
            .enumerate()
            .map(|(b, rows)| -> Job<'_, Held> {
                let job = Start {
                    common,
                    first: first + b * w,
                    used: used(b),
                    rows,
                };
                Box::new(move || kernel::dispatch(common.level, job))
            })
            .collect();
        let held = parallel::each(jobs);
        let count = blocks.len();
        Self {
            driver,
            m,
            command: vec![0.0; m * D],
            diagnostics: vec![0.0; m * common.nd],
            running: vec![true; held.len()],
            held,
            inputs,
            buffers,
            group: count
                .div_ceil(driver.threads * GROUPS_PER_THREAD)
                .clamp(1, MAX_GROUP),
            k: 0,
            commanded: false,
            staging: None,
        }
    }

    /// Whether the slice has an instant left: `k <= steps` and a case still running.
    fn live(&self) -> bool {
        self.k <= self.driver.common.cfg.steps && self.running.contains(&true)
    }

    /// The law's call at instant `k`.
    fn call<X: ExternalLaw<D>>(&mut self, law: &mut X) -> Result<(), X::Error> {
        self.inputs.t = self.k as f64 * self.driver.common.cfg.dt;
        self.inputs.k = self.k;
        law.command(&self.inputs, &mut self.command, &mut self.diagnostics)?;
        self.commanded = true;
        self.staging = law.staging(self.inputs.track, self.m);
        Ok(())
    }

    /// Period `k` of every block still running, under the last call's commands, spread over
    /// the pool or on this thread; the inputs at `k + 1` written, into the memory the law lent
    /// when it lent some of the slice's size.
    fn advance(&mut self, spread: bool) {
        let (common, w, k) = (self.driver.common, self.driver.w, self.k);
        let (m, nd, blocks) = (self.m, common.nd, self.held.len());
        let used = |b: usize| w.min(m - b * w);
        let mut lent = self.staging.take().filter(|s| s.len == m * D);
        let staged = lent.is_some();
        let rows = match &mut lent {
            Some(s) => s.rows::<D>(w),
            None => self.inputs.rows(w),
        };
        let steps = self
            .held
            .iter_mut()
            .zip(self.buffers.iter_mut())
            .zip(self.command.chunks(w * D))
            .zip(chunks_or_empty(&self.diagnostics, w * nd, blocks))
            .zip(rows)
            .zip(self.running.iter_mut())
            .enumerate()
            .filter(|(_, (_, running))| **running)
            .map(
                |(b, (((((held, out), command), diagnostics), rows), running))| {
                    let job = Step {
                        common,
                        k,
                        held,
                        used: used(b),
                        command,
                        diagnostics,
                        rows,
                        out,
                    };
                    (job, running)
                },
            );
        let level = common.level;
        if spread {
            // runs of consecutive blocks, one task each: a task per block cost more in
            // scheduling than its period. (Asking for the next block's memory ahead, all 12 kB
            // of a Mars block, made a run slower: the period reads about half of it.)
            let mut jobs: Vec<Job<'_, ()>> = Vec::with_capacity(blocks.div_ceil(self.group));
            let mut run = Vec::with_capacity(self.group);
            for step in steps {
                run.push(step);
                if run.len() == self.group {
                    let group = std::mem::replace(&mut run, Vec::with_capacity(self.group));
                    jobs.push(Box::new(move || periods(level, group)));
                }
            }
            if !run.is_empty() {
                jobs.push(Box::new(move || periods(level, run)));
            }
            parallel::each(jobs);
        } else {
            periods(level, steps);
        }
        self.k += 1;
        self.commanded = false;
        self.inputs.staged = staged;
    }
}

/// Runs the periods `steps`, noting which blocks go on.
fn periods<'x, 'y, 'z: 'y, 'r, const D: usize, P: PlantModel<D>>(
    level: Level,
    steps: impl IntoIterator<Item = (Step<'x, 'y, 'z, D, P>, &'r mut bool)>,
) {
    for (job, running) in steps {
        *running = kernel::dispatch(level, job);
    }
}

/// A batch run whole on more than one thread spreads its periods over the pool when one
/// period on the calling thread takes at least this long. On a 2-core virtual machine, handing
/// a period to the pool and waiting for it cost 10 to 30 us: under a law returning zeros, 10^2
/// and 10^3 Mars cases (periods of about 2 and 19 us) took 16.9 and 60.6 us per instant with
/// their periods spread, 8.0 and 37.4 on the calling thread (BENCHMARKS.md). Every batch run
/// whole of 1024 cases or more runs interleaved instead ([`MIN_INTERLEAVED`]), so this decides
/// for the small batches of expensive plants.
const SPREAD_MIN: Duration = Duration::from_micros(60);

/// Tasks per pool thread at each instant: enough that a thread whose blocks stop early finds
/// others' work.
const GROUPS_PER_THREAD: usize = 4;

/// At most this many blocks in one task.
const MAX_GROUP: usize = 64;

/// `len`-sized chunks of `values`, or `n` empty slices when `len` is 0.
fn chunks_or_empty(values: &[f64], len: usize, n: usize) -> Vec<&[f64]> {
    if len == 0 {
        vec![&[][..]; n]
    } else {
        values.chunks(len).collect()
    }
}
