//! Ctrl-C for long runs: the work runs on a scoped thread while the calling
//! thread, mostly without the GIL, polls Python's pending signals; on
//! KeyboardInterrupt it sets the run's cancel flag (the core stops at its
//! next block and returns an error, never a panic) and re-raises.
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Runs `work`, letting Ctrl-C cancel it through `cancel`.
pub fn run_interruptible<T: Send>(
    py: Python<'_>,
    cancel: &Arc<AtomicBool>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    std::thread::scope(|s| {
        let handle = s.spawn(work);
        loop {
            let finished = py.detach(|| {
                let start = Instant::now();
                while !handle.is_finished() && start.elapsed() < Duration::from_millis(20) {
                    std::thread::sleep(Duration::from_millis(2));
                }
                handle.is_finished()
            });
            if finished {
                break;
            }
            if let Err(e) = py.check_signals() {
                cancel.store(true, Ordering::Relaxed);
                let _ = py.detach(|| handle.join());
                return Err(e);
            }
        }
        handle
            .join()
            .map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("septa: internal error (a worker panicked)"))
    })
}
