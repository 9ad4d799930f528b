//! The hot loop (SPEC section 10, workloads W1 and W2): seed-001 fixed-time guidance on 300
//! dispersed Mars cases, 10 s at dt = 1 ms, RK4, drag, 50 kN per axis, a_p = 20 sin t.
//!
//! `cargo bench -p landing_core` runs it; the figures go to BENCHMARKS.md.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use landing_core::batch::{Batch, PerCase, run_with_threads};
use landing_core::control::{FixedTimeMss, MssVariant};
use landing_core::disturbance::{Disturbance, Sinusoid};
use landing_core::integrator::Rk4;
use landing_core::plant::MarsLander;
use landing_core::reference::Reference;
use landing_core::rng::{CaseStream, streams};
use landing_core::SimConfig;
use nalgebra::{SVector, Vector3};

const CASES: usize = 300;
const T_FINAL: f64 = 10.0;
const DT: f64 = 1e-3;

fn workload() -> Batch<3, MarsLander, FixedTimeMss<3>> {
    // Table II dispersions
    let mean = [-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0];
    let sd = [100.0, 100.0, 100.0, 10.0, 10.0, 10.0, 20.0];
    let x0 = (0..CASES)
        .map(|i| {
            let mut z = [0.0; 8];
            CaseStream::new(2024, streams::DISPERSION, i as u64).fill_normals(0, &mut z);
            SVector::<f64, 7>::from_fn(|j, _| mean[j] + sd[j] * z[j])
        })
        .collect();
    let law = FixedTimeMss {
        beta1: Vector3::repeat(0.8),
        beta2: Vector3::repeat(0.4),
        q1: Vector3::repeat(0.95),
        q2: Vector3::repeat(1.05),
        alpha1: Vector3::repeat(0.9),
        alpha2: Vector3::repeat(0.5),
        gamma1: Vector3::repeat(0.9),
        gamma2: Vector3::repeat(1.1),
        variant: MssVariant::Printed,
        s1_floor: 1e-3,
    };
    let storm = Disturbance::none()
        .with_sinusoid(Sinusoid {
            amplitude: Vector3::repeat(20.0),
            omega: Vector3::repeat(1.0),
            phase: Vector3::zeros(),
        })
        .expect("one sinusoid");
    Batch {
        plants: PerCase::shared(MarsLander {
            thrust_limit: Vector3::repeat(50_000.0),
            ..Default::default()
        }),
        laws: PerCase::shared(law),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(storm),
        x0,
    }
}

fn bench(c: &mut Criterion) {
    let batch = workload();
    let steps = (CASES as f64 * T_FINAL / DT) as u64;
    let mut g = c.benchmark_group("mars_fixed_time_300x10s");
    g.sample_size(10).measurement_time(Duration::from_secs(30)).throughput(Throughput::Elements(steps));
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
}

criterion_group!(benches, bench);
criterion_main!(benches);
