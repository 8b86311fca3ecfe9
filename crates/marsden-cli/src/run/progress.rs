//! The progress bar: on stderr, only when stderr is a terminal, and only once a run has
//! lasted about a second (short runs print nothing extra).

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes before the bar appears.
const DELAY: Duration = Duration::from_secs(1);
/// The clock is read every this many steps.
const CHECK_EVERY: usize = 256;
/// The rate and the remaining time are recomputed every this many steps.
const RATE_EVERY: usize = 16 * CHECK_EVERY;

/// A progress bar that shows up only for long runs on a terminal.
#[derive(Debug)]
pub struct Progress {
    enabled: bool,
    total: usize,
    start: Instant,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar for `total` steps, enabled if stderr is a terminal and `allowed`.
    pub fn new(total: usize, allowed: bool) -> Self {
        Self {
            enabled: allowed && std::io::stderr().is_terminal(),
            total,
            start: Instant::now(),
            bar: None,
        }
    }

    /// A bar that never shows.
    pub fn hidden() -> Self {
        Self::new(0, false)
    }

    /// Reports that `step` steps are done.
    #[inline]
    pub fn tick(&mut self, step: usize) {
        if !self.enabled || !step.is_multiple_of(CHECK_EVERY) {
            return;
        }
        match &self.bar {
            Some(bar) => {
                bar.set_position(step as u64);
                if step.is_multiple_of(RATE_EVERY) {
                    bar.set_message(self.rate(step));
                }
            }
            None if self.start.elapsed() >= DELAY => self.bar = Some(self.show(step)),
            None => {}
        }
    }

    /// `1234567 steps/s, 3 s left`, measured from the start of the run (the bar appears late,
    /// so indicatif's own estimate would count the steps before it as instantaneous).
    fn rate(&self, step: usize) -> String {
        let elapsed = self.start.elapsed().as_secs_f64();
        let rate = step as f64 / elapsed.max(1e-9);
        let left = self.total.saturating_sub(step) as f64 / rate.max(1e-9);
        format!("{rate:.0} steps/s, {left:.0} s left")
    }

    fn show(&self, step: usize) -> ProgressBar {
        let target = ProgressDrawTarget::stderr();
        let bar = ProgressBar::with_draw_target(Some(self.total as u64), target)
            .with_elapsed(self.start.elapsed());
        let template = "{elapsed_precise} [{bar:40}] {pos}/{len} steps ({msg})";
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_position(step as u64);
        bar.set_message(self.rate(step));
        bar
    }

    /// Removes the bar (if it was shown).
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
