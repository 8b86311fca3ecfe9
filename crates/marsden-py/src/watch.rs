//! Long work off the interpreter's lock, stoppable with Ctrl-C.
//!
//! The work runs on a scoped thread while the calling thread, without the lock, waits for it
//! and every [`POLL`] takes the lock back just long enough to ask the interpreter whether a
//! signal arrived (`PyErr_CheckSignals`, which runs Python's handlers: Ctrl-C becomes a
//! `KeyboardInterrupt`). On a signal it sets the run's stop flag — the run then stops within
//! a few hundred steps, keeping what it computed — waits for the work to end, and raises the
//! signal's exception. Nothing is shared with the work but the flag, so nothing is left half
//! written. The waiting costs nothing when the work ends: the result arrives on a channel.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use marsden_spec::Progress;
use pyo3::prelude::*;

/// How often the waiting thread looks for signals.
pub const POLL: Duration = Duration::from_millis(50);

/// Runs `work` on another thread without the interpreter's lock; a signal handled meanwhile
/// (Ctrl-C) sets `stop`, and its exception is returned once `work` has ended.
///
/// # Errors
/// The exception of the signal handler (`KeyboardInterrupt` for Ctrl-C).
pub fn off_the_lock<T, W>(py: Python<'_>, stop: &Arc<AtomicBool>, work: W) -> PyResult<T>
where
    T: Send,
    W: FnOnce() -> T + Send,
{
    let (result, signal) = py.allow_threads(|| {
        std::thread::scope(|scope| {
            let (done, finished) = mpsc::channel();
            let worker = scope.spawn(move || {
                let result = work();
                // The receiver outlives the worker; a failed send needs no care.
                let _ = done.send(());
                result
            });
            let mut signal: Option<PyErr> = None;
            // Ends when the worker says it is done, or drops the sender by panicking.
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(POLL) {
                if signal.is_none()
                    && let Err(e) = Python::with_gil(|py| py.check_signals())
                {
                    stop.store(true, Ordering::Relaxed);
                    signal = Some(e);
                }
            }
            match worker.join() {
                Ok(result) => (result, signal),
                // The worker panicked: carry the panic on (pyo3 raises it as an exception).
                Err(panic) => std::panic::resume_unwind(panic),
            }
        })
    });
    match signal {
        Some(e) => Err(e),
        None => Ok(result),
    }
}

/// A Python function called with every progress report of a run, `f(step, total,
/// elapsed_seconds, done)`, with the interpreter's lock taken for the call. The first exception
/// it raises sets the run's stop flag (the run ends within a few hundred steps, as on Ctrl-C)
/// and is kept for the caller; no call follows it.
pub struct Reporter {
    callback: Py<PyAny>,
    stop: Arc<AtomicBool>,
    error: Mutex<Option<PyErr>>,
}

impl Reporter {
    /// Reports to `callback`; an exception in it sets `stop`.
    pub fn new(callback: Py<PyAny>, stop: Arc<AtomicBool>) -> Self {
        Self {
            callback,
            stop,
            error: Mutex::new(None),
        }
    }

    /// Calls the function with `p` (nothing once it has raised).
    pub fn report(&self, p: Progress) {
        let mut error = self.error.lock().unwrap_or_else(PoisonError::into_inner);
        if error.is_some() {
            return;
        }
        let args = (p.step, p.total, p.elapsed.as_secs_f64(), p.done);
        if let Err(e) = Python::with_gil(|py| self.callback.call1(py, args)) {
            self.stop.store(true, Ordering::Relaxed);
            *error = Some(e);
        }
    }

    /// The exception the function raised, if it did.
    pub fn into_error(self) -> Option<PyErr> {
        self.error
            .into_inner()
            .unwrap_or_else(PoisonError::into_inner)
    }
}
