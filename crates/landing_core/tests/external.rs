//! A law computed outside the core ([`run_external`]) against the same law built in: a second
//! driver of the same blocks must give the same bits, whatever the threads or the level.

mod common;

use common::*;
use landing_core::batch::{Batch, BatchOutput, PerCase, RunOptions, run};
use landing_core::control::{
    AnyLaw, AnyMemory, FixedTimeMss, LawInput, MssVariant, SuperTwisting, SuperTwistingVariant,
};
use landing_core::disturbance::Disturbance;
use landing_core::external::{ExternalError, ExternalLaw, Inputs, Staging, run_external};
use landing_core::metrics::Divergence;
use landing_core::plant::{MarsLander, PlantModel};
use landing_core::reference::{RefPoint, Reference};
use landing_core::workloads::{mars_dispersed, mars_storm};
use landing_core::{Level, SimConfig};
use nalgebra::{SVector, Vector3};

/// The built-in laws evaluated case by case with `f64` numbers, as an external law: what a
/// user's Python function does for a block of cases, written with the core's own laws.
struct CaseByCase {
    laws: Vec<AnyLaw<3>>,
    memory: Vec<AnyMemory<3, f64>>,
    dt: f64,
    /// (first case, cases, t) of every call.
    calls: Vec<(usize, usize, f64)>,
    /// The track of every call ([`Inputs::track`]).
    tracks: Vec<usize>,
    fail_at: Option<u64>,
    per_call: usize,
    /// The bits of every call's inputs, (first case, k, the seven fields), when recording.
    seen: Option<Vec<(usize, u64, Vec<u64>)>>,
}

impl CaseByCase {
    fn new(laws: Vec<AnyLaw<3>>, dt: f64) -> Self {
        Self {
            laws,
            memory: Vec::new(),
            dt,
            calls: Vec::new(),
            tracks: Vec::new(),
            fail_at: None,
            per_call: usize::MAX,
            seen: None,
        }
    }
}

fn row(v: &[f64], i: usize) -> SVector<f64, 3> {
    SVector::from_column_slice(&v[3 * i..3 * i + 3])
}

impl ExternalLaw<3> for CaseByCase {
    type Error = String;

    fn diagnostic_width(&self) -> usize {
        self.laws[0].diagnostic_width()
    }

    fn cases_per_call(&self) -> usize {
        self.per_call
    }

    fn command(
        &mut self,
        inputs: &Inputs<3>,
        command: &mut [f64],
        diagnostics: &mut [f64],
    ) -> Result<(), String> {
        if self.fail_at == Some(inputs.k) {
            return Err(format!("failed at t = {}", inputs.t));
        }
        let n = inputs.e.len() / 3;
        self.calls.push((inputs.first, n, inputs.t));
        self.tracks.push(inputs.track);
        if let Some(seen) = &mut self.seen {
            let fields = inputs.fields();
            let bits = fields.iter().flat_map(|f| f.iter().map(|x| x.to_bits()));
            seen.push((inputs.first, inputs.k, bits.collect()));
        }
        let nd = self.diagnostic_width();
        for i in 0..n {
            // case `c` of the batch, row `i` of the call's arrays
            let c = inputs.first + i;
            let input = LawInput {
                t: inputs.t,
                dt: self.dt,
                e: row(&inputs.e, i),
                de: row(&inputs.de, i),
                reference: RefPoint {
                    position: row(&inputs.position, i),
                    velocity: row(&inputs.velocity, i),
                    acceleration: row(&inputs.acceleration, i),
                },
                drift: row(&inputs.drift, i),
                inertia: row(&inputs.inertia, i),
            };
            if inputs.k == 0 {
                assert_eq!(self.memory.len(), c, "the slices come in order");
                self.memory.push(self.laws[c].start(&input));
            }
            let law = &self.laws[c];
            let a = law.command(&self.memory[c], &input);
            command[3 * i..3 * i + 3].copy_from_slice(a.as_slice());
            law.diagnostics(
                &self.memory[c],
                &input,
                &mut diagnostics[i * nd..(i + 1) * nd],
            );
            law.advance(&mut self.memory[c], &input);
        }
        Ok(())
    }
}

/// [`CaseByCase`] reading its inputs from memory it lends the driver ([`ExternalLaw::staging`]),
/// as the bindings do with their numpy arrays: after a call the lent memory holds that call's
/// inputs (copied in when the driver did not write them there), and the driver writes the next
/// instant's inputs of the cases still running into it.
struct Lending {
    inner: CaseByCase,
    /// Per track, the seven fields.
    lent: [[Vec<f64>; 7]; 2],
    /// Calls whose inputs the driver wrote into the lent memory.
    staged: usize,
}

impl ExternalLaw<3> for Lending {
    type Error = String;

    fn diagnostic_width(&self) -> usize {
        self.inner.diagnostic_width()
    }

    fn cases_per_call(&self) -> usize {
        self.inner.per_call
    }

    fn staging(&mut self, track: usize, cases: usize) -> Option<Staging> {
        let fields = &mut self.lent[track];
        assert!(
            fields.iter().all(|f| f.len() == 3 * cases),
            "lent after a call on the same slice"
        );
        let pointers = std::array::from_fn(|j| fields[j].as_mut_ptr());
        // SAFETY: each buffer holds 3 x cases values, and only `command` touches them, at the
        // track's next call
        Some(unsafe { Staging::new(pointers, 3 * cases) })
    }

    fn command(
        &mut self,
        inputs: &Inputs<3>,
        command: &mut [f64],
        diagnostics: &mut [f64],
    ) -> Result<(), String> {
        let lent = &mut self.lent[inputs.track];
        let mut view = inputs.clone();
        if inputs.staged {
            self.staged += 1;
            for (to, from) in view.fields_mut().into_iter().zip(lent.iter()) {
                to.copy_from_slice(from);
            }
        } else {
            for (to, from) in lent.iter_mut().zip(inputs.fields()) {
                *to = from.to_vec();
            }
        }
        self.inner.command(&view, command, diagnostics)
    }
}

fn fingerprint(out: &BatchOutput<3>) -> (Vec<u64>, Vec<u64>, Vec<u64>, Vec<u64>, String) {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    (
        bits(&out.final_state),
        bits(&out.states),
        bits(&out.controls),
        bits(&out.diagnostics),
        format!("{:?}", out.metrics),
    )
}

fn plant() -> MarsLander {
    MarsLander {
        thrust_limit: Vector3::repeat(50_000.0),
        ..Default::default()
    }
}

fn builtin(
    laws: &[AnyLaw<3>],
    x0: &[MarsState],
    disturbance: &Disturbance<3>,
) -> Batch<3, MarsLander> {
    Batch {
        plants: PerCase::shared(plant()),
        laws: PerCase::from_vec(laws.to_vec()),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(*disturbance),
        x0: x0.to_vec(),
    }
}

fn outside(x0: &[MarsState], disturbance: &Disturbance<3>) -> Batch<3, MarsLander, ()> {
    Batch {
        plants: PerCase::shared(plant()),
        laws: (),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(*disturbance),
        x0: x0.to_vec(),
    }
}

fn at(threads: usize, level: Level) -> RunOptions<'static> {
    RunOptions {
        threads: Some(threads),
        level: Some(level),
        cancel: None,
        recording: None,
    }
}

/// 21 dispersed cases (one with an absurd speed, which diverges), per-case gains.
fn cases<F: Fn(usize) -> AnyLaw<3>>(law: F) -> (Vec<AnyLaw<3>>, Vec<MarsState>) {
    let mut x0 = mars_dispersed(21, 42);
    x0[3][3] = 1e200;
    ((0..21).map(law).collect(), x0)
}

#[test]
fn an_external_law_gives_the_bits_of_the_same_law_built_in() {
    let noisy = mars_storm().with_noise(Vector3::repeat(0.5));
    let mss = |i: usize| -> AnyLaw<3> {
        FixedTimeMss {
            alpha1: Vector3::repeat(0.5 + 0.05 * i as f64),
            ..reconstructed_gains(MssVariant::Printed)
        }
        .into()
    };
    // a law with memory: the integrator of the super-twisting law
    let twisting = |i: usize| -> AnyLaw<3> {
        SuperTwisting {
            b1: Vector3::repeat(2.0 + 0.1 * i as f64),
            b2: Vector3::repeat(1.0),
            c: Vector3::repeat(0.4),
            variant: SuperTwistingVariant::Standard,
            s_floor: 1e-6,
        }
        .into()
    };
    let cfg = SimConfig::new(0.5, 0.001, 2, 37, 7).unwrap();
    for (name, make) in [
        ("fixed-time MSS", &mss as &dyn Fn(usize) -> AnyLaw<3>),
        ("super-twisting", &twisting),
    ] {
        let (laws, x0) = cases(make);
        let reference = run(&builtin(&laws, &x0, &noisy), &cfg, &at(2, Level::Baseline)).unwrap();
        assert!(
            reference.metrics[3].diverged.is_some(),
            "the absurd case diverges"
        );
        for level in Level::supported() {
            for threads in [1, 2] {
                let mut law = CaseByCase::new(laws.clone(), cfg.dt);
                let out = run_external(&outside(&x0, &noisy), &cfg, &at(threads, level), &mut law)
                    .unwrap_or_else(|_| panic!("{name} runs"));
                assert_eq!(out.level, level);
                assert_eq!(
                    fingerprint(&out),
                    fingerprint(&reference),
                    "{name} at {level:?} on {threads} threads"
                );
                // once per control instant, the last at t_final
                assert_eq!(law.calls.len() as u64, cfg.steps + 1);
                assert_eq!(law.calls.last(), Some(&(0, 21, cfg.t_final())));
            }
            // a slice of the cases at a time: the same bits, on one thread (the slices one
            // after another) and on two (two at a time, their calls alternating)
            for (per_call, threads) in [1, 8, 9, 16, 21].into_iter().flat_map(|p| [(p, 1), (p, 2)])
            {
                let mut law = CaseByCase::new(laws.clone(), cfg.dt);
                law.per_call = per_call;
                let out = run_external(&outside(&x0, &noisy), &cfg, &at(threads, level), &mut law)
                    .unwrap_or_else(|_| panic!("{name} runs"));
                let what =
                    format!("{name} at {level:?}, {per_call} cases per call, {threads} threads");
                assert_eq!(fingerprint(&out), fingerprint(&reference), "{what}");
                check_slices(&law, 21, per_call, threads, level, &cfg, &what);
            }
            // the recording written into buffers the caller lends: the same bits there
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let widths = [reference.state_dim, 3, reference.diagnostic_dim];
            let mut lent = LentBuffers::new(21, reference.n_records(), widths);
            let mut law = CaseByCase::new(laws.clone(), cfg.dt);
            law.per_call = 8;
            let options = RunOptions {
                level: Some(level),
                ..lent.options(2)
            };
            let out = run_external(&outside(&x0, &noisy), &cfg, &options, &mut law)
                .unwrap_or_else(|_| panic!("{name} runs"));
            assert!(out.states.is_empty() && out.controls.is_empty());
            assert_eq!(bits(&lent.states), bits(&reference.states), "{name}");
            assert_eq!(bits(&lent.controls), bits(&reference.controls), "{name}");
            assert_eq!(
                bits(&lent.diagnostics),
                bits(&reference.diagnostics),
                "{name}"
            );
            assert_eq!(
                bits(&out.final_state),
                bits(&reference.final_state),
                "{name}"
            );
        }
    }
}

/// A plant, reference and disturbance given per case or shared, in each of the eight
/// combinations: the driver keeps a block's own parts for what is given per case and one copy
/// of the batch's for what is shared, and must give the bits of the law built in (which
/// gathers every part per block) either way. A block that read the shared copy of a part given
/// per case would see case 0's values.
#[test]
fn plants_references_and_disturbances_given_per_case_or_shared_give_the_bits_of_the_law_built_in() {
    let n = 21;
    let (laws, x0) = cases(|i| -> AnyLaw<3> {
        FixedTimeMss {
            alpha1: Vector3::repeat(0.5 + 0.05 * i as f64),
            ..reconstructed_gains(MssVariant::Printed)
        }
        .into()
    });
    // case i's value for each of the n cases, or case `k`'s shared by all
    fn given<T>(per_case: bool, n: usize, k: usize, each: impl Fn(usize) -> T) -> PerCase<T> {
        if per_case {
            PerCase::from_vec((0..n).map(each).collect())
        } else {
            PerCase::shared(each(k))
        }
    }
    let plants = |per_case: bool| {
        given(per_case, n, 3, |i| MarsLander {
            thrust_limit: Vector3::new(40_000.0 + 500.0 * i as f64, 45_000.0, 50_000.0),
            isp: 225.0 + i as f64,
            ..Default::default()
        })
    };
    let references = |per_case: bool| {
        given(per_case, n, 5, |i| {
            let p = Vector3::new(10.0 * i as f64, -5.0, 0.0);
            let v = Vector3::new(0.0, 0.0, -1.0 - 0.1 * i as f64);
            Reference::cubic_from_boundary(p, v, Vector3::zeros(), Vector3::zeros(), 0.08).unwrap()
        })
    };
    let disturbances = |per_case: bool| {
        given(per_case, n, 7, |i| {
            Disturbance::none()
                .with_constant(Vector3::new(0.01 * i as f64, -0.02, 0.03))
                .with_noise(Vector3::repeat(0.1 + 0.01 * i as f64))
        })
    };
    let cfg = SimConfig::new(0.1, 0.001, 2, 37, 11).unwrap();
    for mask in 0..8 {
        let (p, r, d) = (mask & 1 != 0, mask & 2 != 0, mask & 4 != 0);
        let inside = Batch {
            plants: plants(p),
            laws: PerCase::from_vec(laws.clone()),
            references: references(r),
            disturbances: disturbances(d),
            x0: x0.clone(),
        };
        let reference = run(&inside, &cfg, &at(1, Level::Baseline)).unwrap();
        let batch = Batch {
            plants: plants(p),
            laws: (),
            references: references(r),
            disturbances: disturbances(d),
            x0: x0.clone(),
        };
        for level in Level::supported() {
            for (per_call, threads) in [(usize::MAX, 1), (8, 1), (8, 2), (usize::MAX, 2)] {
                let mut law = CaseByCase::new(laws.clone(), cfg.dt);
                law.per_call = per_call;
                let out = run_external(&batch, &cfg, &at(threads, level), &mut law)
                    .unwrap_or_else(|_| panic!("the batch runs"));
                assert_eq!(
                    fingerprint(&out),
                    fingerprint(&reference),
                    "per case: plant {p}, reference {r}, disturbance {d}; at {level:?}, \
                     {per_call} cases per call, {threads} threads"
                );
            }
        }
    }
}

/// Slices of thousands of cases, whose periods run in many groups of blocks: the bits of the
/// law built in, recorded states included. 4200 cases in one slice on one thread, in two
/// interleaved slices of 2100 on two (each period spread over the pool), in slices of 2048,
/// 2048 and 104 on one.
#[test]
fn slices_of_thousands_of_cases_give_the_same_bits() {
    let n = 4200;
    let mut x0 = mars_dispersed(n, 7);
    x0[1000][3] = 1e200;
    let laws: Vec<AnyLaw<3>> = (0..n)
        .map(|i| {
            FixedTimeMss {
                alpha1: Vector3::repeat(0.5 + 1e-4 * i as f64),
                ..reconstructed_gains(MssVariant::Printed)
            }
            .into()
        })
        .collect();
    let noisy = mars_storm().with_noise(Vector3::repeat(0.5));
    let cfg = SimConfig::new(0.02, 0.001, 1, 3, 5).unwrap();
    let reference = run(&builtin(&laws, &x0, &noisy), &cfg, &at(2, Level::Baseline)).unwrap();
    assert!(
        reference.metrics[1000].diverged.is_some(),
        "the absurd case diverges"
    );
    let level = *Level::supported().last().unwrap();
    for (per_call, threads) in [(usize::MAX, 1), (usize::MAX, 2), (2048, 1)] {
        let mut law = CaseByCase::new(laws.clone(), cfg.dt);
        law.per_call = per_call;
        let out = run_external(&outside(&x0, &noisy), &cfg, &at(threads, level), &mut law).unwrap();
        assert_eq!(
            fingerprint(&out),
            fingerprint(&reference),
            "{per_call} cases per call, {threads} threads"
        );
    }
}

/// The calls of a batch of `n` cases run a slice at a time: slices of whole blocks (at most
/// `per_call` cases, at least one block), starting in order and covering the batch, each
/// called at every instant in time order (but the absurd case 3, which stops at once, when a
/// slice holds it alone). On one thread the slices come one after another, every one but the
/// last of the same size; on two (with more than one slice) two at a time, on two tracks whose
/// calls alternate while both run.
fn check_slices(
    law: &CaseByCase,
    n: usize,
    per_call: usize,
    threads: usize,
    level: Level,
    cfg: &SimConfig,
    what: &str,
) {
    let w = level.lanes::<<MarsLander as PlantModel<3>>::Blocks>();
    let instants = cfg.steps as usize + 1;
    let calls = &law.calls;
    let alternate = threads > 1 && per_call < n && n.div_ceil(w) > 1;
    let on = |t: usize| -> Vec<_> {
        calls
            .iter()
            .zip(&law.tracks)
            .filter(|c| *c.1 == t)
            .map(|c| *c.0)
            .collect()
    };
    let tracks = if alternate {
        assert_eq!(law.tracks[..2], [0, 1], "{what}");
        vec![on(0), on(1)]
    } else {
        assert!(law.tracks.iter().all(|&t| t == 0), "{what}");
        vec![on(0)]
    };
    // (first, cases) of each slice, in the order each track ran them
    let mut slices = Vec::new();
    for track in &tracks {
        let mut at = 0;
        while at < track.len() {
            let (first, m, _) = track[at];
            let mut k = 0;
            while at < track.len() && track[at].0 == first {
                assert_eq!(track[at], (first, m, k as f64 * cfg.dt), "{what}");
                at += 1;
                k += 1;
            }
            if (first, m) != (3, 1) {
                assert_eq!(k, instants, "{what}: slice {first} through every instant");
            }
            slices.push((first, m));
        }
    }
    slices.sort();
    let mut next = 0;
    for &(first, m) in &slices {
        assert_eq!(first, next, "{what}: the slices cover the batch");
        assert!(m <= per_call.max(w), "{what}: slice {first} of {m} cases");
        assert!(
            first % w == 0 && (m % w == 0 || first + m == n),
            "{what}: whole blocks"
        );
        next = first + m;
    }
    assert_eq!(next, n, "{what}");
    if !alternate {
        let sizes: Vec<_> = slices.iter().map(|s| s.1).collect();
        assert!(
            sizes[..sizes.len() - 1].windows(2).all(|p| p[0] == p[1]),
            "{what}"
        );
    } else {
        assert!(slices.len() > 1, "{what}");
    }
    // the slices start in order
    let starts: Vec<_> = calls
        .iter()
        .enumerate()
        .filter(|(i, c)| calls[..*i].iter().all(|d| d.0 != c.0))
        .map(|(_, c)| c.0)
        .collect();
    assert!(starts.windows(2).all(|p| p[0] < p[1]), "{what}: {starts:?}");
}

/// A law that lends memory for its inputs sees, at every call, the bits a law reading the
/// driver's own inputs sees, and the run gives the same bits. The first 32 of 40 cases, whole
/// blocks at every level, diverge at once while the others run: their rows must keep their
/// first inputs.
#[test]
fn a_law_lending_memory_for_its_inputs_sees_the_same_inputs() {
    let laws: Vec<AnyLaw<3>> = vec![reconstructed_gains(MssVariant::Printed).into(); 40];
    let mut x0 = mars_dispersed(40, 42);
    for level in Level::supported() {
        let w = level.lanes::<<MarsLander as PlantModel<3>>::Blocks>();
        assert!(32 % w == 0 && w < 32, "{level:?}: {w} lanes");
    }
    for x in &mut x0[..32] {
        x[3] = 1e200;
    }
    let noisy = mars_storm().with_noise(Vector3::repeat(0.5));
    let cfg = SimConfig::new(0.2, 0.001, 2, 37, 7).unwrap();
    for level in Level::supported() {
        for (per_call, threads) in [(usize::MAX, 1), (usize::MAX, 2), (16, 1), (16, 2), (17, 2)] {
            let what = format!("{level:?}, {per_call} cases per call, {threads} threads");
            let mut plain = CaseByCase::new(laws.clone(), cfg.dt);
            plain.per_call = per_call;
            plain.seen = Some(Vec::new());
            let reference =
                run_external(&outside(&x0, &noisy), &cfg, &at(threads, level), &mut plain)
                    .unwrap_or_else(|_| panic!("{what}"));
            let mut inner = CaseByCase::new(laws.clone(), cfg.dt);
            inner.per_call = per_call;
            inner.seen = Some(Vec::new());
            let mut lending = Lending {
                inner,
                lent: Default::default(),
                staged: 0,
            };
            let out = run_external(
                &outside(&x0, &noisy),
                &cfg,
                &at(threads, level),
                &mut lending,
            )
            .unwrap_or_else(|_| panic!("{what}"));
            assert_eq!(fingerprint(&out), fingerprint(&reference), "{what}");
            let sorted = |law: &CaseByCase| {
                let mut seen = law.seen.clone().expect("recorded");
                seen.sort_by_key(|s| (s.0, s.1));
                seen
            };
            let (a, b) = (sorted(&plain), sorted(&lending.inner));
            assert_eq!(a.len(), b.len(), "{what}");
            assert!(a == b, "{what}: the inputs differ");
            // every call but each slice's first was written into the lent memory
            let slices = b.iter().filter(|s| s.1 == 0).count();
            assert_eq!(lending.staged, b.len() - slices, "{what}");
        }
    }
}

#[test]
fn a_batch_whose_cases_all_stop_ends_the_calls() {
    let (laws, mut x0) = cases(|_| reconstructed_gains(MssVariant::Printed).into());
    for x in &mut x0 {
        x[3] = 1e200;
    }
    let cfg = SimConfig::new(0.5, 0.001, 1, 1, 0).unwrap();
    let none = Disturbance::none();
    let reference = run(&builtin(&laws, &x0, &none), &cfg, &at(2, Level::best())).unwrap();
    let mut law = CaseByCase::new(laws, cfg.dt);
    let out = run_external(&outside(&x0, &none), &cfg, &at(2, Level::best()), &mut law).unwrap();
    assert_eq!(fingerprint(&out), fingerprint(&reference));
    assert!(out.metrics.iter().all(|m| m.diverged.map(|d| d.reason)
        == Some(Divergence::NonFiniteState)
        || m.diverged.map(|d| d.reason) == Some(Divergence::OutOfDomain)));
    assert!(
        law.calls.len() < 10,
        "no call after every case stopped: {}",
        law.calls.len()
    );
}

#[test]
fn a_failing_law_stops_the_batch_with_its_error() {
    let (laws, x0) = cases(|_| reconstructed_gains(MssVariant::Printed).into());
    let cfg = SimConfig::new(0.5, 0.001, 1, 1, 0).unwrap();
    let mut law = CaseByCase::new(laws, cfg.dt);
    law.fail_at = Some(17);
    match run_external(
        &outside(&x0, &Disturbance::none()),
        &cfg,
        &RunOptions::default(),
        &mut law,
    ) {
        Err(ExternalError::Law(e)) => assert_eq!(e, "failed at t = 0.017"),
        other => panic!(
            "expected the law's error, got {:?}",
            other.map(|o| o.n_cases)
        ),
    }
    assert_eq!(law.calls.len(), 17);
}
