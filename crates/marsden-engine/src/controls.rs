//! What the caller of a run controls while it goes: a progress callback and a stop flag.
//!
//! Both are optional and cost nothing when absent. When present, they are looked at every
//! [`CHECK_EVERY`] steps (the callback is called, the flag is read) and the flag again at each
//! stored sample, so a run stops within 256 steps of the request. A stopped run keeps what it
//! computed: the trajectory up to the last step taken (that state included), and a summary
//! whose status is `"interrupted"`. The `marsden` command draws its progress bar from the
//! callback; a Python binding can raise `KeyboardInterrupt` by setting the flag.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// The callback and the stop flag are looked at every this many steps.
pub const CHECK_EVERY: usize = 256;

/// How far a run has got, as the callback sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Steps completed.
    pub step: usize,
    /// Steps requested.
    pub total: usize,
    /// Wall-clock time since the integration started.
    pub elapsed: Duration,
    /// True once, after the last step (completed, failed or stopped).
    pub done: bool,
}

/// The caller's hold on a run (default: none).
#[derive(Clone, Default)]
pub struct Controls<'a> {
    /// Called every [`CHECK_EVERY`] steps and once at the end (`done = true`).
    pub progress: Option<&'a dyn Fn(Progress)>,
    /// Set it (from another thread, a signal handler, the callback) to stop the run.
    pub stop: Option<Arc<AtomicBool>>,
}

impl Controls<'_> {
    /// No callback, no stop flag.
    pub fn none() -> Self {
        Self::default()
    }

    /// Whether a stop was requested.
    pub fn stop_requested(&self) -> bool {
        self.stop
            .as_ref()
            .is_some_and(|s| s.load(Ordering::Relaxed))
    }

    /// Whether anything has to be looked at during the run.
    pub fn is_active(&self) -> bool {
        self.progress.is_some() || self.stop.is_some()
    }
}

impl std::fmt::Debug for Controls<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Controls")
            .field("progress", &self.progress.map(|_| "callback"))
            .field("stop", &self.stop)
            .finish()
    }
}
