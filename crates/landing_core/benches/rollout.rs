//! The hot loop (BENCHMARKS.md): the workloads W1 to W3, W5 and W6, and W1 at every
//! instruction-set level this CPU has.
//!
//! - W1: seed-001 fixed-time guidance on 300 dispersed Mars cases, 10 s at dt = 1 ms, RK4,
//!   drag, 50 kN per axis, a_p = 20 sin t, final states only; W2: the same recording every
//!   10 ms.
//! - W3: seed-000 fuzzy FTSMC on the two-point-mass Eros plant, 300 cases, 15 s at dt = 0.01 s.
//! - W5: seed-002 fuzzy variable-rate law (a Mamdani system per axis and step) on the C20/C22
//!   Eros plant, 300 cases, 100 s at dt = 0.1 s, 1 % command noise.
//! - W6: seed-003 fixed-time NTSMC with its RBF network on the flexible tether (8 nodes),
//!   300 cases, 10 s at dt = 0.01 s with 6 RK4 substeps.
//!
//! `cargo bench -p landing_core --bench rollout`; the figures go to BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use landing_core::batch::{RunOptions, run};
use landing_core::workloads::{eros_w3, eros_w5, mars_w1, tether_w6};
use landing_core::{Level, SimConfig};

const CASES: usize = 300;

fn options(threads: Option<usize>, level: Option<Level>) -> RunOptions<'static> {
    RunOptions {
        threads,
        level,
        cancel: None,
        recording: None,
    }
}

fn bench(c: &mut Criterion) {
    let batch = mars_w1(CASES, 2024);
    let final_only = SimConfig::new(10.0, 1e-3, 1, 0, 0).unwrap();
    let every_10ms = SimConfig::new(10.0, 1e-3, 1, 10, 0).unwrap();
    let mut g = c.benchmark_group("mars_fixed_time_300x10s");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(10))
        .throughput(Throughput::Elements(CASES as u64 * final_only.steps));
    g.bench_function("W1_1_thread", |b| {
        b.iter(|| run(black_box(&batch), &final_only, &options(Some(1), None)).unwrap())
    });
    g.bench_function("W1_all_threads", |b| {
        b.iter(|| run(black_box(&batch), &final_only, &options(None, None)).unwrap())
    });
    g.bench_function("W2_record_10ms_all_threads", |b| {
        b.iter(|| run(black_box(&batch), &every_10ms, &options(None, None)).unwrap())
    });
    for level in Level::supported() {
        g.bench_function(format!("W1_1_thread_{}", level.name()), |b| {
            b.iter(|| {
                run(
                    black_box(&batch),
                    &final_only,
                    &options(Some(1), Some(level)),
                )
                .unwrap()
            })
        });
    }
    g.finish();

    for (name, cfg, batch) in [
        (
            "W3_eros_fuzzy_ftsmc_300x15s",
            SimConfig::new(15.0, 0.01, 1, 0, 0).unwrap(),
            Workload::Three(eros_w3(CASES, 2024)),
        ),
        (
            "W5_eros_fuzzy_variable_rate_300x100s",
            SimConfig::new(100.0, 0.1, 1, 0, 2024).unwrap(),
            Workload::Five(eros_w5(CASES, 2024)),
        ),
        (
            "W6_tether_fntsmc_300x10s",
            SimConfig::new(10.0, 0.01, 6, 0, 0).unwrap(),
            Workload::Six(tether_w6(CASES, 2024)),
        ),
    ] {
        let mut g = c.benchmark_group(name);
        g.sample_size(10)
            .measurement_time(Duration::from_secs(10))
            .throughput(Throughput::Elements(CASES as u64 * cfg.steps));
        g.bench_function("1_thread", |b| b.iter(|| batch.run(&cfg, Some(1))));
        g.bench_function("all_threads", |b| b.iter(|| batch.run(&cfg, None)));
        g.finish();
    }
}

enum Workload {
    Three(
        landing_core::Batch<3, landing_core::plant::SmallBody<landing_core::gravity::TwoPointMass>>,
    ),
    Five(landing_core::Batch<3, landing_core::plant::SmallBody<landing_core::gravity::Harmonic2>>),
    Six(landing_core::Batch<2, landing_core::plant::tether::TetheredFlexible8>),
}

impl Workload {
    fn run(&self, cfg: &SimConfig, threads: Option<usize>) {
        let o = options(threads, None);
        match self {
            Self::Three(b) => drop(black_box(run(b, cfg, &o).unwrap())),
            Self::Five(b) => drop(black_box(run(b, cfg, &o).unwrap())),
            Self::Six(b) => drop(black_box(run(b, cfg, &o).unwrap())),
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
