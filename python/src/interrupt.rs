//! Ctrl-C during long calls. The work runs on a thread of its own while the calling thread,
//! the GIL released, waits for it and every [`POLL`] takes the GIL back to let Python handle
//! its signals (`Python::check_signals`). A signal whose handler raises (Ctrl-C:
//! `KeyboardInterrupt`) sets the [`Stop`] flag the work polls: the work stops (returning early,
//! or unwinding out of the engines through their progress callbacks, [`Stop::check`]), its
//! partial results are dropped, and the call raises the handler's exception. Nothing is left
//! half-written: the call's results are built only after the work has finished. Off the main
//! thread (a Dask worker's task, a Python thread) Python handles no signals, and the work runs
//! to its end as before.

use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the calling thread looks for signals while the work runs.
pub const POLL: Duration = Duration::from_millis(100);

/// Stack of the work's thread: the main thread's usual 8 MiB, which the work had when it ran
/// there.
const STACK: usize = 8 << 20;

/// Set when the call is to stop (a signal handler raised).
pub struct Stop(AtomicBool);

/// What a stopped engine unwinds with ([`Stop::check`]); never seen by Python.
struct Stopped;

impl Stop {
    /// Whether the work should stop now.
    pub fn requested(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// Unwinds out of the work if it should stop: for engines that report progress but have no
    /// way to return early (the Monte Carlo engine's Rayon batches all stop at their next
    /// report, and Rayon passes the unwinding on to the caller). `resume_unwind` runs no panic
    /// hook: nothing is printed.
    pub fn check(&self) {
        if self.requested() {
            panic::resume_unwind(Box::new(Stopped));
        }
    }
}

/// Runs `work` on its own thread, as described above; returns its value, or the exception a
/// signal handler raised meanwhile. A panic in `work` is passed on (PyO3 raises it as
/// `pyo3_runtime.PanicException`, as before).
pub fn run<T, F>(py: Python<'_>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&Stop) -> T + Send,
{
    let stop = Stop(AtomicBool::new(false));
    let done = (Mutex::new(false), Condvar::new());
    std::thread::scope(|s| {
        let (stop, done) = (&stop, &done);
        let worker = std::thread::Builder::new()
            .name("rins".into())
            .stack_size(STACK)
            .spawn_scoped(s, move || {
                let r = panic::catch_unwind(AssertUnwindSafe(|| work(stop)));
                *done.0.lock().unwrap_or_else(|e| e.into_inner()) = true;
                done.1.notify_all();
                r
            })
            .map_err(|e| PyRuntimeError::new_err(format!("starting the work's thread: {e}")))?;
        let mut raised = None;
        loop {
            let finished = py.detach(|| {
                let g = done.0.lock().unwrap_or_else(|e| e.into_inner());
                let (g, _) = done
                    .1
                    .wait_timeout_while(g, POLL, |d| !*d)
                    .unwrap_or_else(|e| e.into_inner());
                *g
            });
            if finished {
                break;
            }
            if let Err(e) = py.check_signals() {
                stop.0.store(true, Ordering::Relaxed);
                raised = Some(e);
                break;
            }
        }
        let out = py
            .detach(|| worker.join())
            .unwrap_or_else(|p| panic::resume_unwind(p));
        match (raised, out) {
            (Some(e), _) => Err(e),
            (None, Ok(v)) => Ok(v),
            (None, Err(p)) => panic::resume_unwind(p),
        }
    })
}
