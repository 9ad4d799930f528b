//! W1 for profilers, on one thread unless told:
//! `cargo build --release -p landing_core --example profile_w1` then
//! `perf record ./target/release/examples/profile_w1`, or, counting instructions (repeatable
//! on a loaded machine), `valgrind --tool=callgrind ./target/release/examples/profile_w1 16`.
//! A second argument forces the instruction-set level (`baseline`, `avx2`, `avx512`), a third
//! the number of threads (one by default).

use std::time::Instant;

use landing_core::batch::{RunOptions, run};
use landing_core::workloads::mars_w1;
use landing_core::{Level, SimConfig};

fn main() {
    let mut args = std::env::args().skip(1);
    let cases = args.next().and_then(|a| a.parse().ok()).unwrap_or(96);
    let level = args
        .next()
        .map(|n| Level::from_name(&n).expect("a level name"));
    let threads = args
        .next()
        .map_or(1, |t| t.parse().expect("a number of threads"));
    let batch = mars_w1(cases, 2024);
    let cfg = SimConfig::new(10.0, 1e-3, 1, 0, 0).unwrap();
    let options = RunOptions {
        threads: Some(threads),
        level,
        cancel: None,
        recording: None,
    };
    let start = Instant::now();
    let out = run(&batch, &cfg, &options).unwrap();
    let el = start.elapsed().as_secs_f64();
    let checksum: f64 = out.final_state.iter().sum();
    println!(
        "{:.1} ns per case-step at {} on {threads} thread(s) (checksum {checksum})",
        el * 1e9 / (cases as f64 * cfg.steps as f64),
        out.level.name()
    );
}
