//! W1 on one thread, for profilers:
//! `cargo build --release -p landing_core --example profile_w1` then
//! `perf record ./target/release/examples/profile_w1`, or, counting instructions (repeatable
//! on a loaded machine), `valgrind --tool=callgrind ./target/release/examples/profile_w1 10`.

use std::time::Instant;

use landing_core::SimConfig;
use landing_core::batch::run_with_threads;
use landing_core::integrator::Rk4;
use landing_core::workloads::mars_w1;

fn main() {
    let cases = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100);
    let batch = mars_w1(cases, 2024);
    let cfg = SimConfig::new(10.0, 1e-3, 1, 0, 0).unwrap();
    let start = Instant::now();
    let out = run_with_threads(&batch, Rk4, &cfg, Some(1)).unwrap();
    let el = start.elapsed().as_secs_f64();
    let checksum: f64 = out.final_state.iter().sum();
    println!(
        "{:.1} ns per case-step (checksum {checksum})",
        el * 1e9 / (cases as f64 * cfg.steps as f64)
    );
}
