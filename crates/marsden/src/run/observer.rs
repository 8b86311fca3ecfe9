//! Watching a run step by step: monitors, streaming writers, progress bars, stopping rules.

use std::ops::ControlFlow;

use super::trajectory::Termination;
use crate::integrator::IntegratorCheckpoint;
use crate::integrator::StepReport;
use crate::mechanics::State;

/// What an observer sees after each completed step.
#[derive(Debug, Clone, Copy)]
pub struct StepView<'a> {
    /// Number of steps completed (1 after the first step).
    pub step: usize,
    /// Time of the new state.
    pub t: f64,
    /// Positions of the new state.
    pub q: &'a [f64],
    /// Momenta of the new state.
    pub p: &'a [f64],
    /// Multipliers of the step just taken (length d).
    pub multipliers: &'a [f64],
    /// The continuous multipliers `λ(t)` at the new state, `μ_k / w` (length d; empty before
    /// the first step and without a projection; [`crate::Integrator::end_multipliers`]).
    pub end_multipliers: &'a [f64],
    /// Newton report of the step.
    pub report: &'a StepReport,
}

/// Watches a run step by step (monitors, streaming writers, progress bars, stopping rules).
pub trait Observer {
    /// Called once with the initial state (`step = 0`) before stepping.
    fn start(&mut self, _initial: &StepView<'_>) {}
    /// Called after every completed step; return `ControlFlow::Break(())` to stop the run.
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()>;
    /// Whether [`Observer::observe`] must see every step (default: true). When false, it may
    /// see only the stored samples, and [`simulate`](crate::run::simulate()) hands the stepper
    /// the steps between samples in one call ([`crate::run::stepper::Stepper::advance_on`]).
    fn every_step(&self) -> bool {
        true
    }
    /// When [`Observer::every_step`] is false: besides the stored samples and the last step,
    /// [`Observer::observe`] sees every step that is a multiple of this number (a progress
    /// report, a stop flag, a sampling stride of its own). Default: `usize::MAX` (none).
    fn cadence(&self) -> usize {
        usize::MAX
    }
    /// When [`Observer::every_step`] is false: the first step after `step` that
    /// [`Observer::observe`] must see besides the stored samples and the last step. Default:
    /// the next multiple of [`Observer::cadence`]; an observer with two periods (a sampling
    /// stride and a check of a stop flag) says the nearer of their next multiples, so that the
    /// run loop does not stop at every multiple of their greatest common divisor.
    fn next_stop(&self, step: usize) -> usize {
        next_multiple(step, self.cadence())
    }
    /// Why the run ends, asked once when [`Observer::observe`] returned
    /// `ControlFlow::Break(())`. Default: `None`, which the run loop records as
    /// [`Termination::Stopped`]; an event detector names its event
    /// ([`Termination::Event`]) or the failure to locate it ([`Termination::Failed`]).
    fn termination(&self) -> Option<Termination> {
        None
    }
    /// When [`Observer::every_step`] is false: whether it checks each step the stepper takes
    /// between the steps shown to [`Observer::observe`], lightly, taking those steps itself
    /// ([`Observer::watch_steps`]); where it stops, the run loop ends the stretch and shows that
    /// step to [`Observer::observe`]. An event detector watches each step so, at the cost of
    /// one evaluation of its `g`, without the run loop's every-step path. Default: false.
    fn watches_steps(&self) -> bool {
        false
    }
    /// When [`Observer::watches_steps`]: takes the steps of `steps` (a stretch the run loop
    /// hands the stepper) one by one, looking at each new state, and stops taking them at the
    /// first step it wants shown to [`Observer::observe`] (the run loop then shows it) or when
    /// `steps` has none left; takes at least one step when there is one. Generic over the
    /// stretch, so that the loop is compiled together with the stepper's step (the run loop
    /// and the stretch are of concrete types: no call through a `dyn` at each step).
    /// Default: takes them all.
    fn watch_steps<W: WatchedSteps>(&mut self, steps: &mut W)
    where
        Self: Sized,
    {
        while steps.next_step().is_some() {}
    }
    /// When [`Observer::every_step`] is true: a time `τ` strictly inside the next step, from
    /// grid point `step` (at `t`) to the one at `next`, at which the observer wants the state
    /// reached by a variational step of its own size `τ − t` from `t` — the state a run ending
    /// at `τ` would reach ([`crate::TimeGrid::ending_at`]). The run loop takes that step
    /// aside, shows its state to [`Observer::landed`], and restores the stepper
    /// ([`Stepper::restore_carried`](crate::run::Stepper::restore_carried)), so the run goes on
    /// bit for bit as if it had not been taken; it asks again until this returns `None`.
    /// Default: `None`.
    fn landing(&self, _step: usize, _t: f64, _next: f64) -> Option<f64> {
        None
    }
    /// The state of the step aside that [`Observer::landing`] asked for (its `step` is the
    /// grid step it lies in, `k + 1`), or why it could not be taken. Return
    /// `ControlFlow::Break(())` to stop the run. Default: nothing.
    fn landed(&mut self, _reached: Result<&StepView<'_>, &crate::Error>) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// Whether the run should be checkpointed where [`Observer::observe`] stopped it, because
    /// the stop was asked from outside (a signal), not reached (an event that ends the run):
    /// a resume then continues from there. Default: `false`.
    fn checkpoint_at_stop(&self) -> bool {
        false
    }
    /// Whether the run should be checkpointed after `step` (default: never). The run loop
    /// then hands [`Observer::checkpoint`] what the stepper carries; an observer that asks
    /// for checkpoints also makes its [`Observer::cadence`] stop the loop at those steps.
    fn checkpoint_due(&self, _step: usize) -> bool {
        false
    }
    /// Saves a checkpoint of the run after the step `view` shows, with what the stepper
    /// carries to its next step (`carried`); called after [`Observer::observe`] let the run
    /// go on, or stopped it and [`Observer::checkpoint_at_stop`] asked for one. Return
    /// `ControlFlow::Break(())` to stop the run (the checkpoint could not be saved). Default:
    /// nothing.
    fn checkpoint(
        &mut self,
        _view: &StepView<'_>,
        _carried: &IntegratorCheckpoint,
    ) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

/// The steps of a stretch, as [`Observer::watch_steps`] takes them.
pub trait WatchedSteps {
    /// Takes the next step: its number (steps completed) and the new state; `None` when the
    /// stretch is done or the step failed (the stepper keeps the error for the run loop, and
    /// the state is the last good one).
    fn next_step(&mut self) -> Option<(usize, &State)>;

    /// Asks the stepper to keep the start `(q, p)` of each step from now on, to be read after
    /// the step by [`WatchedSteps::step_start`] (so that a watch that needs the start of the
    /// step where it stops does not copy every state); whether it does. Default: it does not.
    fn keep_starts(&mut self) -> bool {
        false
    }

    /// The start `(q, p)` of the last step taken, when the stepper keeps them
    /// ([`WatchedSteps::keep_starts`]). Default: `None`.
    fn step_start(&self) -> Option<(&[f64], &[f64])> {
        None
    }

    /// The current state and its step number: the last step's new state, or the last good
    /// state when a step failed, or the stretch's start before the first step.
    fn current(&self) -> (usize, &State);
}

/// The first multiple of `period` after `step` (`usize::MAX` when there is none).
pub fn next_multiple(step: usize, period: usize) -> usize {
    let period = period.max(1);
    step.saturating_add(period - step % period)
}

/// Observes nothing.
impl Observer for () {
    fn observe(&mut self, _view: &StepView<'_>) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    fn every_step(&self) -> bool {
        false
    }
}

impl<F: FnMut(&StepView<'_>) -> ControlFlow<()>> Observer for F {
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self(view)
    }
}
