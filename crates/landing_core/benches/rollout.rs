//! The hot loop (SPEC section 10, workloads W1 and W2): seed-001 fixed-time guidance on 300
//! dispersed Mars cases, 10 s at dt = 1 ms, RK4, drag, 50 kN per axis, a_p = 20 sin t.
//!
//! `cargo bench -p landing_core` runs it; the figures go to BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use landing_core::SimConfig;
use landing_core::batch::run_with_threads;
use landing_core::integrator::Rk4;
use landing_core::workloads::{eros_w3, mars_w1};

const CASES: usize = 300;
const T_FINAL: f64 = 10.0;
const DT: f64 = 1e-3;

fn bench(c: &mut Criterion) {
    let batch = mars_w1(CASES, 2024);
    let steps = (CASES as f64 * T_FINAL / DT) as u64;
    let mut g = c.benchmark_group("mars_fixed_time_300x10s");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(30))
        .throughput(Throughput::Elements(steps));
    let final_only = SimConfig::new(T_FINAL, DT, 1, 0, 0).unwrap();
    let every_10ms = SimConfig::new(T_FINAL, DT, 1, 10, 0).unwrap();
    g.bench_function("W1_final_only_1_thread", |b| {
        b.iter(|| run_with_threads(black_box(&batch), Rk4, &final_only, Some(1)).unwrap())
    });
    g.bench_function("W1_final_only_all_threads", |b| {
        b.iter(|| run_with_threads(black_box(&batch), Rk4, &final_only, None).unwrap())
    });
    g.bench_function("W2_record_10ms_all_threads", |b| {
        b.iter(|| run_with_threads(black_box(&batch), Rk4, &every_10ms, None).unwrap())
    });
    g.finish();

    let eros = eros_w3(CASES, 2024);
    let cfg = SimConfig::new(15.0, 0.01, 1, 0, 0).unwrap();
    let mut g = c.benchmark_group("eros_fuzzy_ftsmc_300x15s");
    g.sample_size(10)
        .measurement_time(Duration::from_secs(10))
        .throughput(Throughput::Elements(CASES as u64 * cfg.steps));
    g.bench_function("W3_final_only_1_thread", |b| {
        b.iter(|| run_with_threads(black_box(&eros), Rk4, &cfg, Some(1)).unwrap())
    });
    g.bench_function("W3_final_only_all_threads", |b| {
        b.iter(|| run_with_threads(black_box(&eros), Rk4, &cfg, None).unwrap())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
