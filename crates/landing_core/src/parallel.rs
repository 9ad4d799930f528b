//! The batches' parallel loops, compiled once.
//!
//! Rayon's machinery (its job, join and bridge types) is generic over the closure it runs: a
//! loop written inline in a driver is compiled again for every plant, axis count and job
//! type, and was a tenth of the extension's code (`cargo llvm-lines -p landing_py`: about
//! 100 000 of 868 000 lines). The drivers box their jobs instead, so that the loops below are
//! compiled once per result type. A box per block and period costs an allocation and an
//! indirect call against a block's period of microseconds at least.

use rayon::prelude::*;

/// One block's work.
pub(crate) type Job<'a, T> = Box<dyn FnOnce() -> T + Send + 'a>;

/// Runs the jobs on the current rayon pool, one task each, and returns their results in
/// order.
pub(crate) fn each<T: Send>(jobs: Vec<Job<'_, T>>) -> Vec<T> {
    jobs.into_par_iter()
        .with_max_len(1)
        .map(|job| job())
        .collect()
}

/// [`each`] for jobs that may fail: the first error (in no particular order) stops the jobs
/// not yet started.
pub(crate) fn try_each<T: Send, E: Send>(jobs: Vec<Job<'_, Result<T, E>>>) -> Result<Vec<T>, E> {
    jobs.into_par_iter()
        .with_max_len(1)
        .map(|job| job())
        .collect()
}

/// Runs `a` on this thread and `b` on the pool (or after `a`, when no other thread takes it),
/// and returns both results.
pub(crate) fn both<A: Send, B: Send>(a: Job<'_, A>, b: Job<'_, B>) -> (A, B) {
    rayon::join(a, b)
}

/// Runs `f` on `pool`, or on the current pool when there is none.
pub(crate) fn on_pool<T: Send>(pool: Option<&rayon::ThreadPool>, f: Job<'_, T>) -> T {
    match pool {
        Some(p) => p.install(f),
        None => f(),
    }
}

/// A pool of `threads` workers, or none for rayon's global pool.
pub(crate) fn pool(threads: Option<usize>) -> Result<Option<rayon::ThreadPool>, String> {
    threads
        .map(|k| rayon::ThreadPoolBuilder::new().num_threads(k).build())
        .transpose()
        .map_err(|e| e.to_string())
}
