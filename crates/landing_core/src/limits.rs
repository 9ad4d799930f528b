//! The documented caps on the sizes a request may ask for, defined once here: the binding
//! checks requests against them (and exposes them to Python as `landing._core.LIMITS`), and
//! docs/parameters.md lists them. Each cap is far above any preset or study, and low enough
//! that a request within it is refused for memory (up front) rather than by overflowing a
//! size computation, hanging for hours or aborting the interpreter.

/// Largest number of cases in one batch, campaign or dispersion sample (2^32). A case's
/// initial state alone takes 56 bytes (the Mars lander), so 2^32 cases are 240 GB before
/// anything is recorded: a larger count is a typo, not a workload (split a
/// campaign into chunks with `first_case` instead).
pub const MAX_CASES: u64 = 1 << 32;

/// Largest number of control periods a batch may ask for (keeps k dt exact in f64 terms of
/// the integer counter and guards against an accidental t_final / dt of 1e15).
pub const MAX_STEPS: u64 = 1 << 40;

/// Largest number of integrator substeps per control period. The stiffest preset (the
/// flexible tether with 16 nodes at dt = 0.01 s) needs 10; 10 000 leaves three
/// orders of magnitude for studies while a mistyped 10^9 is refused instead of running for
/// hours per control period.
pub const MAX_SUBSTEPS: u64 = 10_000;

/// Largest worker-thread count. Each worker has its own stack and a block of cases in
/// flight; 1024 is above the cores of any single machine the library targets, and a
/// larger request (e.g. `threads=10**9`) would try to spawn that many OS threads.
pub const MAX_THREADS: u64 = 1024;

/// Largest number of points sampling a fuzzy system's output universe. The centroid keeps
/// one membership per output set and point (16 sets at most), so 100 000 points are 12.8 MB
/// and about a millisecond per evaluation; the presets use 401. A larger resolution changes
/// the centroid by less than the floating-point error while costing time and memory.
pub const MAX_FUZZY_RESOLUTION: u64 = 100_000;

/// The caps by name (the names Python sees in `landing._core.LIMITS`).
pub const LIMITS: [(&str, u64); 5] = [
    ("max_cases", MAX_CASES),
    ("max_steps", MAX_STEPS),
    ("max_substeps", MAX_SUBSTEPS),
    ("max_threads", MAX_THREADS),
    ("max_fuzzy_resolution", MAX_FUZZY_RESOLUTION),
];

/// A count (cases, substeps, threads, resolution) checked against its cap: the error names
/// the count, its value and the cap by its name in [`LIMITS`].
pub fn within_cap(
    name: &str,
    value: u64,
    cap_name: &str,
    cap: u64,
) -> Result<(), crate::error::ReadError> {
    if value > cap {
        return Err(crate::error::ReadError::Value(format!(
            "{name} = {value} violates {name} <= {cap_name} ({cap}); see landing._core.LIMITS"
        )));
    }
    Ok(())
}
