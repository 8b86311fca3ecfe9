//! The step loop of the runs on groups (a rigid body, jointed bodies): steps until the grid's
//! end, a failure or a stop request, a sample every `every` steps and always the last state
//! taken, the progress callback and the stop flag looked at every [`CHECK_EVERY`] steps.

use std::time::Instant;

use crate::controls::{CHECK_EVERY, Controls, Progress};

/// A stepper the loop drives.
pub(crate) trait GroupStepper {
    /// One step; on failure the message (the state is left as before the step).
    fn advance(&mut self) -> Result<(), String>;
    /// Newton iterations so far.
    fn iterations(&self) -> usize;
}

/// What the loop did.
pub(crate) struct LoopOutcome {
    /// Steps taken.
    pub steps: usize,
    /// The most Newton iterations of one step.
    pub most: usize,
    /// Whether a stop was requested.
    pub interrupted: bool,
    /// The failure (a step, or a sample that could not be written or was not finite).
    pub error: Option<String>,
    /// Wall-clock seconds of the integration.
    pub wall_seconds: f64,
}

/// Runs `total` steps of `stepper`, calling `sample` on the initial state, every `every` steps,
/// and on the last state taken (a failed or stopped run's too).
pub(crate) fn drive<S: GroupStepper>(
    stepper: &mut S,
    total: usize,
    every: usize,
    controls: &Controls<'_>,
    mut sample: impl FnMut(&S) -> Option<String>,
) -> LoopOutcome {
    let started = Instant::now();
    let every = every.max(1);
    let mut error = sample(stepper);
    let mut interrupted = false;
    let (mut steps, mut sampled, mut most) = (0, 0, 0);
    while error.is_none() && steps < total {
        if controls.is_active() && steps % CHECK_EVERY == 0 {
            if let Some(progress) = controls.progress {
                progress(Progress {
                    step: steps,
                    total,
                    elapsed: started.elapsed(),
                    done: false,
                });
            }
            if controls.stop_requested() {
                interrupted = true;
                break;
            }
        }
        let before = stepper.iterations();
        if let Err(e) = stepper.advance() {
            error = Some(e);
            break;
        }
        most = most.max(stepper.iterations() - before);
        steps += 1;
        if steps % every == 0 || steps == total {
            error = sample(stepper);
            sampled = steps;
        }
    }
    if sampled != steps
        && let Some(e) = sample(stepper)
    {
        error.get_or_insert(e);
    }
    let wall_seconds = started.elapsed().as_secs_f64();
    if let Some(progress) = controls.progress {
        progress(Progress {
            step: steps,
            total,
            elapsed: started.elapsed(),
            done: true,
        });
    }
    LoopOutcome {
        steps,
        most,
        interrupted,
        error,
        wall_seconds,
    }
}
