//! The time spent compiling on each thread, so that a run can report it apart from its steps.
//!
//! Tapes are compiled at their first use, which falls inside a run's clock: a short run's time
//! per step would otherwise include milliseconds of Cranelift. Each thread keeps its own total
//! (a run and its lazily compiled tapes share a thread; parallel sweep members do not mix), and
//! a caller reads it before and after the run ([`compile_seconds`]).

use std::cell::Cell;
use std::time::Instant;

thread_local! {
    /// Seconds spent in [`timed`] on this thread.
    static COMPILE_SECONDS: Cell<f64> = const { Cell::new(0.0) };
}

/// Seconds this thread has spent compiling native code since it started (successful or not).
///
/// ```
/// let before = marsden_jit::compile_seconds();
/// // ... a run that compiles its tapes ...
/// let compiling = marsden_jit::compile_seconds() - before;
/// assert!(compiling >= 0.0);
/// ```
pub fn compile_seconds() -> f64 {
    COMPILE_SECONDS.with(Cell::get)
}

/// Runs `compile`, adding its duration to this thread's total.
pub(crate) fn timed<T>(compile: impl FnOnce() -> T) -> T {
    let started = Instant::now();
    let result = compile();
    let elapsed = started.elapsed().as_secs_f64();
    COMPILE_SECONDS.with(|total| total.set(total.get() + elapsed));
    result
}
