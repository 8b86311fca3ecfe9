//! The progress bar: on stderr, only when stderr is a terminal, and only once a run has
//! lasted about a second (short runs print nothing extra). It is drawn from the run's
//! progress callback ([`marsden_spec::Progress`], every 256 steps).

use std::cell::RefCell;
use std::io::IsTerminal;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use marsden_spec::{CHECK_EVERY, Progress};

/// How long a run goes before the bar appears.
const DELAY: Duration = Duration::from_secs(1);
/// The rate and the remaining time are recomputed every this many steps.
const RATE_EVERY: usize = 16 * CHECK_EVERY;

/// A progress bar that shows up only for long runs on a terminal.
#[derive(Debug, Default)]
pub struct Bar {
    bar: RefCell<Option<ProgressBar>>,
}

impl Bar {
    /// A bar, if stderr is a terminal and `allowed` (`None`: the run needs no callback).
    pub fn new(allowed: bool) -> Option<Self> {
        (allowed && std::io::stderr().is_terminal()).then(Self::default)
    }

    /// The run's progress callback: shows, moves or removes the bar.
    pub fn update(&self, progress: Progress) {
        let mut bar = self.bar.borrow_mut();
        if progress.done {
            if let Some(bar) = bar.take() {
                bar.finish_and_clear();
            }
            return;
        }
        match bar.as_ref() {
            Some(bar) => {
                bar.set_position(progress.step as u64);
                if progress.step.is_multiple_of(RATE_EVERY) {
                    bar.set_message(rate(&progress));
                }
            }
            None if progress.elapsed >= DELAY => *bar = Some(show(&progress)),
            None => {}
        }
    }
}

/// `1234567 steps/s, 3 s left`, measured from the start of the run (the bar appears late,
/// so indicatif's own estimate would count the steps before it as instantaneous).
fn rate(progress: &Progress) -> String {
    let elapsed = progress.elapsed.as_secs_f64();
    let rate = progress.step as f64 / elapsed.max(1e-9);
    let left = progress.total.saturating_sub(progress.step) as f64 / rate.max(1e-9);
    format!("{rate:.0} steps/s, {left:.0} s left")
}

fn show(progress: &Progress) -> ProgressBar {
    let target = ProgressDrawTarget::stderr();
    let bar = ProgressBar::with_draw_target(Some(progress.total as u64), target)
        .with_elapsed(progress.elapsed);
    let template = "{elapsed_precise} [{bar:40}] {pos}/{len} steps ({msg})";
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_position(progress.step as u64);
    bar.set_message(rate(progress));
    bar
}
