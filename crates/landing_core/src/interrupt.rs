//! Running a batch while the caller watches for a request to stop (Ctrl-C in Python).
//!
//! A batch polls its cancel flag between blocks and control periods ([`crate::RunOptions`]);
//! something must raise the flag while the batch holds the calling thread. [`supervised`] runs
//! a large job on a scoped thread and lets the calling thread poll the caller (Python's signal
//! handlers, for the binding) until the job ends; a small job runs where it is called, since it
//! ends within milliseconds anyway.

use std::any::Any;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

/// Jobs of fewer integrator steps than this (cases x periods x substeps) run on the calling
/// thread, unwatched: they take milliseconds.
pub const WATCHED_WORK: u128 = 1 << 17;

/// How often the calling thread polls while a job runs: well under the second a user waits
/// for Ctrl-C to act.
pub const POLL_INTERVAL: Duration = Duration::from_millis(50);

/// Why a supervised job gave no result.
pub enum Stopped<E> {
    /// `poll` asked to stop (with its reason); the job was cancelled and its result dropped.
    Interrupted(E),
    /// The job panicked (the payload), caught rather than unwound into the caller.
    Panicked(Box<dyn Any + Send>),
}

/// Runs `job` (`work` integrator steps) and returns its result, catching its panics. A job of
/// [`WATCHED_WORK`] steps or more runs on a scoped thread while this thread calls `poll` every
/// [`POLL_INTERVAL`]; the first error `poll` returns raises `cancel`, the job stops at its
/// next poll of the flag, and the error is returned once the job has ended.
pub fn supervised<'a, T: Send, E>(
    work: u128,
    cancel: &AtomicBool,
    mut poll: impl FnMut() -> Result<(), E>,
    job: Box<dyn FnOnce() -> T + Send + 'a>,
) -> Result<T, Stopped<E>> {
    let caught = || std::panic::catch_unwind(std::panic::AssertUnwindSafe(job));
    if work < WATCHED_WORK {
        return caught().map_err(Stopped::Panicked);
    }
    // the result comes back through a channel, which wakes this thread as it is sent: a
    // thread parked until the job's thread had finished (woken by an unpark just before the
    // job's thread returned) found it still running at times, parked again and slept out the
    // poll interval: up to 50 ms added to a run (BENCHMARKS.md)
    let (send, result) = std::sync::mpsc::sync_channel(1);
    std::thread::scope(|scope| {
        let worker = scope.spawn(move || {
            // the receiver outlives the scope, so the send cannot fail
            let _ = send.send(caught());
        });
        let mut raised = None;
        let out = loop {
            match result.recv_timeout(POLL_INTERVAL) {
                Ok(out) => break out,
                Err(RecvTimeoutError::Timeout) => {
                    if raised.is_none()
                        && let Err(e) = poll()
                    {
                        cancel.store(true, Ordering::Relaxed);
                        raised = Some(e);
                    }
                }
                // the job's panics are caught inside it, so its thread sends before it ends;
                // should it end without sending, its panic is the job's
                Err(RecvTimeoutError::Disconnected) => {
                    break Err(worker
                        .join()
                        .err()
                        .unwrap_or_else(|| Box::new("the job's thread ended without a result")));
                }
            }
        };
        match (raised, out) {
            (Some(e), _) => Err(Stopped::Interrupted(e)),
            (None, out) => out.map_err(Stopped::Panicked),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_job_runs_unwatched_and_its_panic_is_caught() {
        let cancel = AtomicBool::new(false);
        let polled = std::cell::Cell::new(0);
        let poll = || -> Result<(), ()> {
            polled.set(polled.get() + 1);
            Ok(())
        };
        assert!(matches!(
            supervised(1, &cancel, poll, Box::new(|| 7)),
            Ok(7)
        ));
        let r = supervised(
            1,
            &cancel,
            || Err::<(), ()>(()),
            Box::new(|| panic!("boom")),
        );
        assert!(matches!(r, Err(Stopped::Panicked(_))));
        assert_eq!(polled.get(), 0);
    }

    #[test]
    fn a_poll_error_cancels_a_large_job_and_is_returned() {
        let cancel = AtomicBool::new(false);
        let job = Box::new(|| {
            // a job that runs until it is cancelled, as a batch does
            while !cancel.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(1));
            }
            1
        });
        let r = supervised(u128::MAX, &cancel, || Err::<(), &str>("stop"), job);
        assert!(matches!(r, Err(Stopped::Interrupted("stop"))));
        assert!(cancel.load(Ordering::Relaxed));
    }

    #[test]
    fn the_caller_is_woken_when_a_large_job_ends_not_at_its_next_poll() {
        // a job that ends at once is never polled: the caller's wait ends with it. Parked until
        // the job's thread had finished, the caller was woken just before, found the thread
        // still running at times, polled and slept out the interval (up to 50 ms a run)
        let cancel = AtomicBool::new(false);
        let polled = std::cell::Cell::new(0);
        for i in 0..200 {
            let poll = || -> Result<(), ()> {
                polled.set(polled.get() + 1);
                Ok(())
            };
            assert!(matches!(
                supervised(u128::MAX, &cancel, poll, Box::new(move || i)),
                Ok(j) if j == i
            ));
        }
        assert_eq!(polled.get(), 0, "polls after jobs that had ended");
    }

    #[test]
    fn a_large_job_that_ends_returns_its_result() {
        let cancel = AtomicBool::new(false);
        let job = Box::new(|| {
            std::thread::sleep(Duration::from_millis(120));
            5
        });
        let r = supervised(u128::MAX, &cancel, || Ok::<(), ()>(()), job);
        assert!(matches!(r, Ok(5)));
        let r = supervised(
            u128::MAX,
            &cancel,
            || Ok::<(), ()>(()),
            Box::new(|| panic!("x")),
        );
        assert!(matches!(r, Err(Stopped::Panicked(_))));
    }
}
