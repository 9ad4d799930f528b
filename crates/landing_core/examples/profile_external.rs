//! The engine's own share of a law computed outside the core ([`run_external`], the path of a
//! Python law), with no interpreter: W1's Mars cases under a law that returns zeros, the
//! batch a slice of 4096 cases at a time (a Python law's default), one thread. What it
//! measures is the round trip a Python law pays beyond its function: the law's inputs written
//! at every control instant and every block's period run between two calls, one slice's blocks
//! after another's. `cargo build --release -p landing_core --example profile_external`, then
//! `./target/release/examples/profile_external [cases] [level] [repeat] [cases per call]`.

use std::time::Instant;

use landing_core::batch::{Batch, PerCase, RunOptions};
use landing_core::disturbance::Disturbance;
use landing_core::external::{ExternalLaw, Inputs, run_external};
use landing_core::plant::MarsLander;
use landing_core::reference::Reference;
use landing_core::workloads::mars_dispersed;
use landing_core::{Level, SimConfig};
use nalgebra::Vector3;

/// A law returning zeros, the slice `per_call` cases at a time.
struct Zeros {
    per_call: usize,
}

impl ExternalLaw<3> for Zeros {
    type Error = String;

    fn diagnostic_width(&self) -> usize {
        0
    }

    fn cases_per_call(&self) -> usize {
        self.per_call
    }

    fn command(&mut self, _: &Inputs<3>, command: &mut [f64], _: &mut [f64]) -> Result<(), String> {
        command.fill(0.0);
        Ok(())
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let cases = args.next().and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let level = args
        .next()
        .map(|n| Level::from_name(&n).expect("a level name"));
    let repeat: usize = args
        .next()
        .map_or(1, |r| r.parse().expect("a repeat count"));
    let per_call = args
        .next()
        .map_or(4096, |c| c.parse().expect("cases per call"));
    let batch = Batch {
        plants: PerCase::shared(MarsLander {
            thrust_limit: Vector3::repeat(50_000.0),
            ..Default::default()
        }),
        laws: (),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: mars_dispersed(cases, 2024),
    };
    let cfg = SimConfig::new(1.0, 1e-3, 1, 0, 0).unwrap();
    let options = RunOptions {
        threads: Some(1),
        level,
        cancel: None,
        recording: None,
    };
    for _ in 0..repeat {
        let start = Instant::now();
        let out = run_external(&batch, &cfg, &options, &mut Zeros { per_call }).unwrap();
        let el = start.elapsed().as_secs_f64();
        let checksum: f64 = out.final_state.iter().sum();
        println!(
            "{:.1} ns per case-step at {} (checksum {checksum})",
            el * 1e9 / (cases as f64 * (cfg.steps + 1) as f64),
            out.level.name()
        );
    }
}
