//! W6 (the tether paper's fixed-time NTSMC with its RBF network on the flexible tethered
//! satellite, 10 s at 10 ms with 6 substeps, as the criterion bench runs it) on one thread, for
//! profilers and for A/B timings of two builds alternated:
//! `cargo build --release -p landing_core --example profile_w6`, then
//! `./target/release/examples/profile_w6 [cases] [level]`, or under
//! `valgrind --tool=callgrind` (instructions, repeatable on a loaded machine).

use std::time::Instant;

use landing_core::batch::{RunOptions, run};
use landing_core::workloads::tether_w6;
use landing_core::{Level, SimConfig};

fn main() {
    let mut args = std::env::args().skip(1);
    let cases = args.next().and_then(|a| a.parse().ok()).unwrap_or(96);
    let level = args
        .next()
        .map(|n| Level::from_name(&n).expect("a level name"));
    let batch = tether_w6(cases, 2024);
    let cfg = SimConfig::new(10.0, 0.01, 6, 0, 0).unwrap();
    let options = RunOptions {
        threads: Some(1),
        level,
        cancel: None,
        recording: None,
    };
    let start = Instant::now();
    let out = run(&batch, &cfg, &options).unwrap();
    let el = start.elapsed().as_secs_f64();
    let checksum: f64 = out.final_state.iter().sum();
    println!(
        "{:.1} ns per case-step at {} (checksum {checksum})",
        el * 1e9 / (cases as f64 * cfg.steps as f64),
        out.level.name()
    );
}
