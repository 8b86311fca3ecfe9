//! What the run loop steps: anything that advances a [`State`] on a uniform grid — the
//! Lagrangian [`Integrator`] (a discrete Hamiltonian map `F̃_{L_d}`) and the Hamiltonian
//! integrator ([`crate::hamiltonian::HamiltonianIntegrator`]) — so that one loop
//! ([`super::simulate()`]) serves both and their trajectories are alike.

use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::{Error, InputError};
use crate::holonomic::MomentumProjection;
use crate::integrator::IntegratorCheckpoint;
use crate::integrator::{Integrator, Statistics, StepReport};
use crate::mechanics::{Constraint, State};

use super::grid::TimeGrid;
use super::observer::{Observer, WatchedSteps};

/// A one-step method with its buffers, as the run loop sees it.
pub trait Stepper {
    /// Degrees of freedom `n` and number of constraints `d` of the states it steps.
    fn dims(&self) -> (usize, usize);

    /// `steps` steps of size `h` from `state` on the grid `t_k = t₀ + k h` (`t₀ = state.t`);
    /// the report of the last one. On error `state` holds the last good state.
    fn advance(&mut self, state: &mut State, h: f64, steps: usize) -> Result<StepReport, Error>;

    /// Steps completed over the stepper's life (the loop counts a chunk's steps by it).
    fn steps_done(&self) -> usize;

    /// `steps` steps from grid point `k` of `grid` (`state.t = grid.time(k)`), each new state
    /// at the grid's own time `grid.time(k + j)`: the times of a step-by-step run, bit for bit.
    /// The run loop hands a stepper all the steps between two samples in one call when no
    /// observer watches each step. Default: one [`Stepper::advance`] per step.
    fn advance_on(
        &mut self,
        state: &mut State,
        grid: &TimeGrid,
        k: usize,
        steps: usize,
    ) -> Result<StepReport, Error> {
        step_by_step(self, state, grid, k, steps)
    }

    /// One step of size `h` from `state` (advanced in place; unchanged on error), as a stretch
    /// of steps watched by an observer takes it ([`Observer::watch_steps`]). Default:
    /// [`Stepper::advance`] by one step.
    fn single_step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        self.advance(state, h, 1)
    }

    /// Keeps (`keep = true`) or stops keeping the start `(q, p)` of each step, for a watch of
    /// the steps to read after the step ([`Stepper::kept_start`]) instead of copying every
    /// state; whether the starts are kept. Default: never.
    fn keep_step_starts(&mut self, _keep: bool) -> bool {
        false
    }

    /// The start `(q, p)` of the last step, when the starts are kept
    /// ([`Stepper::keep_step_starts`]). Default: `None`.
    fn kept_start(&self) -> Option<(&[f64], &[f64])> {
        None
    }

    /// The multipliers `λ` of the last step (length d; default: none).
    fn multipliers(&self) -> &[f64] {
        &[]
    }

    /// The projection multipliers `μ` of the last step (length d; default: none).
    fn projection_multipliers(&self) -> &[f64] {
        &[]
    }

    /// The multipliers `λ(t)` of the continuous equations at the state the last step reached
    /// (length d; default: none; [`Integrator::end_multipliers`]).
    fn end_multipliers(&self) -> &[f64] {
        &[]
    }

    /// Work counters so far (default: none kept).
    fn statistics(&self) -> Statistics {
        Statistics::default()
    }

    /// What the stepper carries from one step to the next, for a checkpoint of the run
    /// ([`IntegratorCheckpoint`]; default: `None`, a stepper that cannot be checkpointed).
    fn carried(&self) -> Option<IntegratorCheckpoint> {
        None
    }

    /// Restores what [`Stepper::carried`] returned, so that the next step is bit for bit the
    /// one the checkpointed stepper would have taken.
    ///
    /// # Errors
    /// The checkpoint belongs to another kind of step; default: this stepper cannot restore
    /// checkpoints.
    fn restore_carried(&mut self, _carried: &IntegratorCheckpoint) -> Result<(), Error> {
        Err(Error::Input(InputError::InvalidOption {
            name: "checkpoint",
            value: f64::NAN,
            reason: "this stepper cannot resume from a checkpoint",
        }))
    }
}

impl<A, F, C, P> Stepper for Integrator<A, F, C, P>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    fn dims(&self) -> (usize, usize) {
        let shape = self.shape();
        (shape.n, shape.d)
    }
    fn advance(&mut self, state: &mut State, h: f64, steps: usize) -> Result<StepReport, Error> {
        Integrator::advance(self, state, h, steps)
    }
    fn steps_done(&self) -> usize {
        Integrator::statistics(self).steps
    }
    /// The explicit path runs the chunk in its own loop ([`Integrator::advance`]: times
    /// `state.t + j h` inside the chunk, as the explicit kernels count them), a shorter last
    /// step on its own; the others step one by one at the grid's times, each by
    /// [`Integrator::step`] (which checks its input itself: no second check per step).
    fn advance_on(
        &mut self,
        state: &mut State,
        grid: &TimeGrid,
        k: usize,
        steps: usize,
    ) -> Result<StepReport, Error> {
        let uniform = grid.uniform_steps(k, steps);
        match self.is_explicit() && uniform == steps {
            true => Integrator::advance(self, state, grid.h, steps),
            false if self.is_explicit() => {
                Integrator::advance(self, state, grid.h, uniform)?;
                step_by_step(self, state, grid, k + uniform, steps - uniform)
            }
            false => {
                let mut report = StepReport::default();
                for j in 1..=steps {
                    report = self.step(state, grid.step_size(k + j - 1))?;
                    state.t = grid.time(k + j);
                }
                Ok(report)
            }
        }
    }
    /// The Newton paths step by [`Integrator::step`], the explicit path by one
    /// [`Integrator::advance`] per step, as a run shown every step takes it.
    fn single_step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        match self.is_explicit() {
            true => Integrator::advance(self, state, h, 1),
            false => self.step(state, h),
        }
    }
    fn keep_step_starts(&mut self, keep: bool) -> bool {
        Integrator::keep_step_starts(self, keep)
    }
    fn kept_start(&self) -> Option<(&[f64], &[f64])> {
        Integrator::kept_start(self)
    }
    fn multipliers(&self) -> &[f64] {
        Integrator::multipliers(self)
    }
    fn projection_multipliers(&self) -> &[f64] {
        Integrator::projection_multipliers(self)
    }
    fn end_multipliers(&self) -> &[f64] {
        Integrator::end_multipliers(self)
    }
    fn statistics(&self) -> Statistics {
        *Integrator::statistics(self)
    }
    fn carried(&self) -> Option<IntegratorCheckpoint> {
        Some(Integrator::checkpoint(self))
    }
    fn restore_carried(&mut self, carried: &IntegratorCheckpoint) -> Result<(), Error> {
        Integrator::restore(self, carried)
    }
}

/// A stretch of steps handed to an observer that watches them, being taken: single steps
/// ([`Stepper::single_step`]), each of the grid's size for it ([`TimeGrid::step_size`]), the
/// time of each new state set to the grid's; the grid point `k` of the current state, the last one `end` (`k` itself once a step
/// failed), the report of the last step and the error of the one that failed.
struct Stretch<'a, S: ?Sized> {
    stepper: &'a mut S,
    state: &'a mut State,
    grid: &'a TimeGrid,
    k: usize,
    end: usize,
    report: StepReport,
    failure: Option<Error>,
}

impl<'a, S: Stepper + ?Sized> Stretch<'a, S> {
    /// The steps from grid point `points.start` of `grid` to `points.end` at most.
    fn new(
        stepper: &'a mut S,
        state: &'a mut State,
        grid: &'a TimeGrid,
        points: std::ops::Range<usize>,
    ) -> Self {
        Self {
            stepper,
            state,
            grid,
            k: points.start,
            end: points.end,
            report: StepReport::default(),
            failure: None,
        }
    }

    /// The stretch taken by `observer` until it has seen what it wants; the report of the last
    /// step taken. The stepper no longer keeps the starts of its steps afterwards.
    fn watched<O: Observer>(mut self, observer: &mut O) -> Result<StepReport, Error> {
        observer.watch_steps(&mut self);
        self.stepper.keep_step_starts(false);
        match self.failure {
            Some(error) => Err(error),
            None => Ok(self.report),
        }
    }
}

impl<S: Stepper + ?Sized> WatchedSteps for Stretch<'_, S> {
    #[inline(always)]
    fn next_step(&mut self) -> Option<(usize, &State)> {
        if self.k >= self.end {
            return None;
        }
        let h = self.grid.step_size(self.k);
        match self.stepper.single_step(self.state, h) {
            Ok(report) => self.report = report,
            Err(error) => {
                (self.failure, self.end) = (Some(error), self.k);
                return None;
            }
        }
        self.k += 1;
        self.state.t = self.grid.time(self.k);
        Some((self.k, self.state))
    }
    #[inline(always)]
    fn keep_starts(&mut self) -> bool {
        self.stepper.keep_step_starts(true)
    }
    #[inline(always)]
    fn step_start(&self) -> Option<(&[f64], &[f64])> {
        self.stepper.kept_start()
    }
    fn current(&self) -> (usize, &State) {
        (self.k, self.state)
    }
}

/// `steps` steps from grid point `k` of `grid` (`state.t = grid.time(k)`), each new state at
/// the grid's own time, taken by `observer` ([`Observer::watch_steps`]), which looks at each new
/// state: the stretch ends early at the first step it asks to see (the run loop counts the
/// steps taken by [`Stepper::steps_done`]). The report of the last step taken.
pub(crate) fn watched_stretch<S: Stepper + ?Sized, O: Observer>(
    stepper: &mut S,
    state: &mut State,
    grid: &TimeGrid,
    points: std::ops::Range<usize>,
    observer: &mut O,
) -> Result<StepReport, Error> {
    Stretch::new(stepper, state, grid, points).watched(observer)
}

/// `steps` single steps from grid point `k`, each of the grid's size for it
/// ([`TimeGrid::step_size`]), the time of each new state set to the grid's.
fn step_by_step<S: Stepper + ?Sized>(
    stepper: &mut S,
    state: &mut State,
    grid: &TimeGrid,
    k: usize,
    steps: usize,
) -> Result<StepReport, Error> {
    let mut report = StepReport::default();
    for j in 1..=steps {
        report = stepper.advance(state, grid.step_size(k + j - 1), 1)?;
        state.t = grid.time(k + j);
    }
    Ok(report)
}
