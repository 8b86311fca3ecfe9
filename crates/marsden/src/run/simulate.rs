//! Running an integrator over a time grid: storage stride and observers.
//!
//! [`simulate`] steps a [`Stepper`] (the Lagrangian or the Hamiltonian integrator) from a starting [`State`] over a [`TimeGrid`], stores every
//! `stride`-th state in a [`Trajectory`] (always the first and the last), and shows every step to
//! an [`Observer`], which can monitor, stream to disk, report progress or stop the run. Times are
//! computed as `t₀ + k h`, never accumulated.

use std::ops::ControlFlow;

use super::grid::{RunOptions, TimeGrid};
use super::observer::{Observer, StepView};
use super::stepper::{Stepper, watched_stretch};
use super::trajectory::{StepMultipliers, Termination, Trajectory};
use crate::error::{Error, InputError};
use crate::integrator::{Statistics, StepReport};
use crate::mechanics::State;

/// Steps `stepper` from `start` over `grid`, storing every `options.stride`-th state and showing
/// each step to `observer`. Never fails as a call: a failing step ends the run with
/// [`Termination::Failed`] and the trajectory up to the last good state.
pub fn simulate<S, O>(
    stepper: &mut S,
    start: State,
    grid: &TimeGrid,
    options: &RunOptions,
    observer: &mut O,
) -> Trajectory
where
    S: Stepper + ?Sized,
    O: Observer,
{
    let initial = StepReport::default();
    observer.start(&StepView {
        step: 0,
        t: start.t,
        q: &start.q,
        p: &start.p,
        multipliers: &[],
        end_multipliers: &[],
        report: &initial,
    });
    let before = stepper.statistics();
    let from = Resumed {
        step: 0,
        state: start,
    };
    run_loop(stepper, from, grid, options, observer, &before)
}

/// Where a resumed run starts: after `step` steps of its grid, at `state` (whose `t` is
/// `grid.time(step)`), exactly as a checkpoint recorded them.
#[derive(Debug, Clone, PartialEq)]
pub struct Resumed {
    /// Steps completed before the checkpoint.
    pub step: usize,
    /// The state after them.
    pub state: State,
}

/// [`simulate`] from a checkpoint: `stepper` has been restored
/// ([`Stepper::restore_carried`]) and `observer` holds what it had accumulated when the
/// checkpoint was taken; the loop goes on from step `from.step` of `grid`, and the run is bit
/// for bit the one that was checkpointed. The observer's [`Observer::start`] is not called
/// again, and the trajectory's first sample is the resumed state; its statistics count the
/// whole run (the restored stepper's counters include the steps before the checkpoint).
pub fn simulate_from<S, O>(
    stepper: &mut S,
    from: Resumed,
    grid: &TimeGrid,
    options: &RunOptions,
    observer: &mut O,
) -> Trajectory
where
    S: Stepper + ?Sized,
    O: Observer,
{
    run_loop(
        stepper,
        from,
        grid,
        options,
        observer,
        &Statistics::default(),
    )
}

/// The loop of [`simulate`] and [`simulate_from`]: steps from `from` to the end of the grid,
/// storing every `stride`-th state and the last, showing the steps to `observer`, checkpointing
/// where it asks; the trajectory's statistics are the stepper's counters less `before`.
fn run_loop<S, O>(
    stepper: &mut S,
    from: Resumed,
    grid: &TimeGrid,
    options: &RunOptions,
    observer: &mut O,
    before: &Statistics,
) -> Trajectory
where
    S: Stepper + ?Sized,
    O: Observer,
{
    let (n, d) = stepper.dims();
    let mut traj = Trajectory::new(n, d, grid.h);
    let stride = options.stride.max(1);
    let Resumed { step: mut k, state } = from;
    let mut state = state;
    let initial = StepReport::default();
    traj.push(k, state.t, &state.q, &state.p, &[], initial);
    traj.steps = k;
    let mut last_report = initial;
    // Steps between stored samples run in one call when nobody watches each step.
    let chunked = !observer.every_step();
    while k < grid.steps {
        let chunk = if chunked {
            let to_sample = (stride - k % stride).min(observer.next_stop(k) - k);
            to_sample.min(grid.steps - k)
        } else {
            1
        };
        if !chunked && side_steps(stepper, &state, k, grid.time(k + 1), observer).is_break() {
            traj.termination =
                (observer.termination()).unwrap_or(Termination::Stopped { steps: k });
            break;
        }
        let done_before = stepper.steps_done();
        // A stretch of one step is shown to the observer as it is: a watch would add its entry
        // and exit to the same look at the state.
        let outcome = match chunked && chunk > 1 && observer.watches_steps() {
            true => watched_stretch(stepper, &mut state, grid, k..k + chunk, observer),
            false => stepper.advance_on(&mut state, grid, k, chunk),
        };
        k += stepper.steps_done() - done_before;
        state.t = grid.time(k);
        traj.steps = k;
        match outcome {
            Ok(report) => last_report = report,
            Err(e) => {
                traj.termination = Termination::Failed(e);
                break;
            }
        }
        let view = StepView {
            step: k,
            t: state.t,
            q: &state.q,
            p: &state.p,
            multipliers: stepper.multipliers(),
            end_multipliers: stepper.end_multipliers(),
            report: &last_report,
        };
        let mut stop = observer.observe(&view).is_break();
        if k % stride == 0 || k == grid.steps || stop {
            let multipliers = step_multipliers(stepper);
            traj.push_sample(k, state.t, &state.q, &state.p, multipliers, last_report);
        }
        let due = match stop {
            false => observer.checkpoint_due(k),
            true => observer.checkpoint_at_stop(),
        };
        if due
            && k < grid.steps
            && let Some(carried) = stepper.carried()
        {
            stop |= observer.checkpoint(&view, &carried).is_break();
        }
        if stop {
            traj.termination = observer
                .termination()
                .unwrap_or(Termination::Stopped { steps: k });
            break;
        }
    }
    store_last_good(&mut traj, &state, step_multipliers(stepper), last_report);
    traj.statistics = difference(&stepper.statistics(), before);
    traj
}

/// The steps aside that `observer` asks for inside the step from grid point `k` to the time
/// `next` ([`Observer::landing`]): each from `state` with a step of its own size `τ − t_k`,
/// shown to [`Observer::landed`], the stepper restored after it to what it carried before, so
/// the run's own steps are those of a run without them, bit for bit.
fn side_steps<S, O>(
    stepper: &mut S,
    state: &State,
    k: usize,
    next: f64,
    observer: &mut O,
) -> ControlFlow<()>
where
    S: Stepper + ?Sized,
    O: Observer,
{
    while let Some(tau) = observer.landing(k, state.t, next) {
        let Some(carried) = stepper.carried() else {
            let error = Error::Input(InputError::InvalidOption {
                name: "landing",
                value: tau,
                reason: "this stepper cannot step aside to a time between its grid points (it \
                         cannot be restored after the step)",
            });
            return observer.landed(Err(&error));
        };
        let mut aside = state.clone();
        let flow = match stepper.advance(&mut aside, tau - state.t, 1) {
            Ok(report) => observer.landed(Ok(&StepView {
                step: k + 1,
                t: tau,
                q: &aside.q,
                p: &aside.p,
                multipliers: stepper.multipliers(),
                end_multipliers: stepper.end_multipliers(),
                report: &report,
            })),
            Err(error) => observer.landed(Err(&error)),
        };
        if let Err(error) = stepper.restore_carried(&carried) {
            return observer.landed(Err(&error));
        }
        flow?;
    }
    ControlFlow::Continue(())
}

/// After a failure, makes sure the last good state is the last sample.
fn store_last_good(
    traj: &mut Trajectory,
    state: &State,
    multipliers: StepMultipliers<'_>,
    report: StepReport,
) {
    if traj.step_indices.last() != Some(&traj.steps) {
        let (t, q, p) = (state.t, &state.q, &state.p);
        traj.push_sample(traj.steps, t, q, p, multipliers, report);
    }
}

/// The multipliers of the stepper's last step.
fn step_multipliers<S: Stepper + ?Sized>(stepper: &S) -> StepMultipliers<'_> {
    StepMultipliers {
        lambda: stepper.multipliers(),
        mu: stepper.projection_multipliers(),
    }
}

fn difference(
    after: &crate::integrator::Statistics,
    before: &crate::integrator::Statistics,
) -> crate::integrator::Statistics {
    Statistics {
        steps: after.steps - before.steps,
        newton_iterations: after.newton_iterations - before.newton_iterations,
        max_newton_iterations: after.max_newton_iterations,
        system_evaluations: after.system_evaluations - before.system_evaluations,
        action_evaluations: after.action_evaluations - before.action_evaluations,
        failed_steps: after.failed_steps - before.failed_steps,
        explicit_steps: after.explicit_steps - before.explicit_steps,
        jacobian_factorizations: after.jacobian_factorizations - before.jacobian_factorizations,
        potential_gradients: after.potential_gradients - before.potential_gradients,
    }
}
