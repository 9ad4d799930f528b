//! W1 on one thread, for profilers: `cargo run --release -p landing_core --example profile_w1`.

use std::time::Instant;

use landing_core::batch::{Batch, PerCase, run_with_threads};
use landing_core::control::{FixedTimeMss, MssVariant};
use landing_core::disturbance::{Disturbance, Sinusoid};
use landing_core::integrator::Rk4;
use landing_core::plant::MarsLander;
use landing_core::reference::Reference;
use landing_core::rng::{CaseStream, streams};
use landing_core::SimConfig;
use nalgebra::{SVector, Vector3};

fn main() {
    let cases = 100;
    let mean = [-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0];
    let sd = [100.0, 100.0, 100.0, 10.0, 10.0, 10.0, 20.0];
    let x0 = (0..cases)
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
        .with_sinusoid(Sinusoid { amplitude: Vector3::repeat(20.0), omega: Vector3::repeat(1.0), phase: Vector3::zeros() })
        .unwrap();
    let batch = Batch {
        plants: PerCase::shared(MarsLander { thrust_limit: Vector3::repeat(50_000.0), ..Default::default() }),
        laws: PerCase::shared(law),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(storm),
        x0,
    };
    let cfg = SimConfig::new(10.0, 1e-3, 1, 0, 0).unwrap();
    let start = Instant::now();
    let out = run_with_threads(&batch, Rk4, &cfg, Some(1)).unwrap();
    let el = start.elapsed().as_secs_f64();
    println!("{:.1} ns per case-step (checksum {})", el * 1e9 / (cases as f64 * 1e4), out.final_state.iter().sum::<f64>());
}
