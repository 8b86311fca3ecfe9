//! The progress bar: on stderr, only when stderr is a terminal, and only once a run has
//! lasted about a second (short runs print nothing extra).

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes before the bar appears.
const DELAY: Duration = Duration::from_secs(1);
/// The clock is read every this many steps.
const CHECK_EVERY: usize = 256;

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
            Some(bar) => bar.set_position(step as u64),
            None if self.start.elapsed() >= DELAY => self.bar = Some(self.show(step)),
            None => {}
        }
    }

    fn show(&self, step: usize) -> ProgressBar {
        let bar =
            ProgressBar::with_draw_target(Some(self.total as u64), ProgressDrawTarget::stderr());
        let template = "{elapsed_precise} [{bar:40}] {pos}/{len} steps ({per_sec}, eta {eta})";
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_position(step as u64);
        bar
    }

    /// Removes the bar (if it was shown).
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
