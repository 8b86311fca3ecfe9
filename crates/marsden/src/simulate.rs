//! Running an integrator over a time grid: storage stride and observers.
//!
//! [`simulate`] steps an [`Integrator`] from a starting [`State`] over a [`TimeGrid`], stores every
//! `stride`-th state in a [`Trajectory`] (always the first and the last), and shows every step to
//! an [`Observer`], which can monitor, stream to disk, report progress or stop the run. Times are
//! computed as `t₀ + k h`, never accumulated.

use std::ops::ControlFlow;

use crate::holonomic::MomentumProjection;
use crate::{
    Constraint, DiscreteAction, DiscreteForce, Error, Integrator, State, StepReport, Termination,
    Trajectory,
};

/// A uniform time grid `t_k = t₀ + k h`, `k = 0 … steps`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TimeGrid {
    /// Initial time.
    pub t0: f64,
    /// Time step (positive).
    pub h: f64,
    /// Number of steps.
    pub steps: usize,
}

impl TimeGrid {
    /// `steps` steps of size `h` from `t0`.
    pub fn new(t0: f64, h: f64, steps: usize) -> Result<Self, Error> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(Error::InvalidStep { h });
        }
        Error::check_finite("t0", &[t0])?;
        Ok(Self { t0, h, steps })
    }

    /// Steps of size `h` from `t0` until `t_end`: the last grid time is the first one at or after
    /// `t_end` (within a relative 1e-9, so `t_end = 10, h = 0.1` gives exactly 100 steps).
    pub fn until(t0: f64, t_end: f64, h: f64) -> Result<Self, Error> {
        let grid = Self::new(t0, h, 0)?;
        Error::check_finite("t_end", &[t_end])?;
        if t_end <= t0 {
            return Err(Error::InvalidTimeSpan {
                reason: format!("t_end = {t_end} must be after t0 = {t0}"),
            });
        }
        let n = (t_end - t0) / h;
        let steps = if (n - n.round()).abs() <= 1e-9 * n.max(1.0) {
            n.round()
        } else {
            n.ceil()
        };
        Ok(Self {
            steps: steps as usize,
            ..grid
        })
    }

    /// Time of grid point `k`.
    pub fn time(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.h
    }

    /// Final time.
    pub fn t_end(&self) -> f64 {
        self.time(self.steps)
    }
}

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
    /// see only the stored samples, and [`simulate`] takes explicit steps between samples in
    /// one loop ([`Integrator::advance`]).
    fn every_step(&self) -> bool {
        true
    }
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

/// Options of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RunOptions {
    /// Store every `stride`-th state (default 1: every state). The first and last states are
    /// always stored; `usize::MAX` stores only those.
    pub stride: usize,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self { stride: 1 }
    }
}

/// Steps `integrator` from `start` over `grid`, storing every `options.stride`-th state and showing
/// each step to `observer`. Never fails as a call: a failing step ends the run with
/// [`Termination::Failed`] and the trajectory up to the last good state.
pub fn simulate<A, F, C, P, O>(
    integrator: &mut Integrator<A, F, C, P>,
    start: State,
    grid: &TimeGrid,
    options: &RunOptions,
    observer: &mut O,
) -> Trajectory
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
    O: Observer + ?Sized,
{
    let shape = integrator.shape();
    let mut traj = Trajectory::new(shape.n, shape.d, grid.h);
    let stride = options.stride.max(1);
    let mut state = start;
    let initial = StepReport::default();
    traj.push(0, state.t, &state.q, &state.p, &[], initial);
    observer.start(&StepView {
        step: 0,
        t: state.t,
        q: &state.q,
        p: &state.p,
        multipliers: &[],
        report: &initial,
    });
    let before = *integrator.statistics();
    let mut last_report = initial;
    // Explicit steps between stored samples run in one loop when nobody watches each step.
    let chunked = integrator.is_explicit() && !observer.every_step();
    let mut k = 0;
    while k < grid.steps {
        let chunk = if chunked {
            (stride - k % stride).min(grid.steps - k)
        } else {
            1
        };
        let done_before = integrator.statistics().steps;
        let outcome = integrator.advance(&mut state, grid.h, chunk);
        k += integrator.statistics().steps - done_before;
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
            multipliers: integrator.multipliers(),
            report: &last_report,
        };
        let stop = observer.observe(&view).is_break();
        if k % stride == 0 || k == grid.steps || stop {
            traj.push_sample(
                k,
                (state.t, &state.q, &state.p),
                (
                    integrator.multipliers(),
                    integrator.projection_multipliers(),
                ),
                last_report,
            );
        }
        if stop {
            traj.termination = Termination::Stopped { steps: k };
            break;
        }
    }
    let multipliers = (
        integrator.multipliers(),
        integrator.projection_multipliers(),
    );
    store_last_good(&mut traj, &state, multipliers, last_report);
    traj.statistics = difference(integrator.statistics(), &before);
    traj
}

/// After a failure, makes sure the last good state is the last sample.
fn store_last_good(
    traj: &mut Trajectory,
    state: &State,
    multipliers: (&[f64], &[f64]),
    report: StepReport,
) {
    if traj.step_indices.last() != Some(&traj.steps) {
        let sample = (state.t, state.q.as_slice(), state.p.as_slice());
        traj.push_sample(traj.steps, sample, multipliers, report);
    }
}

fn difference(after: &crate::Statistics, before: &crate::Statistics) -> crate::Statistics {
    crate::Statistics {
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
