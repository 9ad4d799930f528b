//! W3 or W5 (the two asteroid papers' fuzzy laws on 433 Eros, as the criterion bench runs them:
//! W3 for 15 s at 10 ms on the two-point mass, W5 for 100 s at 0.1 s on the harmonic field) on
//! one thread, for profilers and for A/B timings of two builds alternated:
//! `cargo build --release -p landing_core --example profile_small_body`, then
//! `./target/release/examples/profile_small_body W3|W5 [cases] [level] [repeat]`, or under
//! `perf record` or `valgrind --tool=callgrind` (instructions, repeatable on a loaded machine).

use std::time::Instant;

use landing_core::batch::{RunOptions, run};
use landing_core::workloads::{eros_w3, eros_w5};
use landing_core::{Level, SimConfig};

fn main() {
    let mut args = std::env::args().skip(1);
    let workload = args.next().unwrap_or_else(|| "W3".into());
    let cases = args.next().and_then(|a| a.parse().ok()).unwrap_or(96);
    let level = args
        .next()
        .map(|n| Level::from_name(&n).expect("a level name"));
    let repeat: usize = args
        .next()
        .map_or(1, |r| r.parse().expect("a repeat count"));
    let options = RunOptions {
        threads: Some(1),
        level,
        cancel: None,
        recording: None,
    };
    for _ in 0..repeat {
        let (cfg, start, out) = match workload.as_str() {
            "W3" => {
                let (batch, cfg) = (eros_w3(cases, 2024), SimConfig::new(15.0, 0.01, 1, 0, 0));
                let cfg = cfg.unwrap();
                (cfg, Instant::now(), run(&batch, &cfg, &options).unwrap())
            }
            "W5" => {
                let (batch, cfg) = (eros_w5(cases, 2024), SimConfig::new(100.0, 0.1, 1, 0, 2024));
                let cfg = cfg.unwrap();
                (cfg, Instant::now(), run(&batch, &cfg, &options).unwrap())
            }
            other => panic!("unknown workload {other:?}: W3 or W5"),
        };
        let el = start.elapsed().as_secs_f64();
        let checksum: f64 = out.final_state.iter().sum();
        println!(
            "{:.1} ns per case-step at {} (checksum {checksum})",
            el * 1e9 / (cases as f64 * cfg.steps as f64),
            out.level.name()
        );
    }
}
