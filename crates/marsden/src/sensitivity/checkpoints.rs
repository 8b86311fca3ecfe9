//! Checkpoints of a run for the reverse sweep: every `m`-th state (with the stepper as it was
//! there), and the recomputation of the `m` steps after one of them with their Jacobians.
//!
//! Storing the stepper beside the state (its predictor history included) makes the
//! recomputed steps repeat the forward sweep's bit for bit, so the reverse sweep differentiates
//! exactly the run that was taken ([GW08] §12.3, *checkpointing*; here the uniform schedule:
//! `⌈K/m⌉` checkpoints plus one segment of `m` states and Jacobians).
//!
//! [GW08]: crate#references

use std::ops::ControlFlow;

use super::step::SensitiveStep;
use crate::error::Error;
use crate::mechanics::State;
use crate::run::TimeGrid;

/// The states (and steppers) at steps `0, m, 2m, …` of a run.
#[derive(Debug, Clone)]
pub struct Checkpoints<D> {
    /// The spacing `m`.
    pub every: usize,
    /// `(state, stepper)` at step `c·m`, `c = 0, 1, …`.
    stored: Vec<(State, D)>,
}

/// One recomputed segment: the states `x_{k₀} … x_{k₁}` and the step Jacobians between them.
#[derive(Debug, Clone, Default)]
pub struct Segment {
    /// First step index `k₀`.
    pub first: usize,
    /// `x_{k₀ + i}`, `i = 0 … len`.
    pub states: Vec<State>,
    /// `[DF_x | DF_θ]` of step `k₀ + i` (row-major `2n × (2n + P)`), `i = 0 … len − 1`.
    pub jacobians: Vec<Vec<f64>>,
}

impl<D: SensitiveStep + Clone> Checkpoints<D> {
    /// The forward sweep: runs `stepper` from `start` over `grid` with plain steps, keeping
    /// every `every`-th state and showing the steps taken to `watch` after each; returns the
    /// checkpoints, the state reached and, if `watch` asked to stop, the steps taken.
    pub fn record<W>(
        stepper: &mut D,
        start: State,
        grid: &TimeGrid,
        every: usize,
        mut watch: W,
    ) -> Result<(Self, State, Option<usize>), Error>
    where
        W: FnMut(usize) -> ControlFlow<()>,
    {
        let every = every.max(1);
        let mut stored = Vec::with_capacity(grid.steps / every + 1);
        let mut state = start;
        for k in 0..grid.steps {
            if k.is_multiple_of(every) {
                stored.push((state.clone(), stepper.clone()));
            }
            stepper.step(&mut state, grid.step_size(k))?;
            state.t = grid.time(k + 1);
            if watch(k + 1).is_break() {
                return Ok((Self { every, stored }, state, Some(k + 1)));
            }
        }
        if grid.steps == 0 {
            stored.push((state.clone(), stepper.clone()));
        }
        Ok((Self { every, stored }, state, None))
    }

    /// Number of stored checkpoints.
    pub fn len(&self) -> usize {
        self.stored.len()
    }

    /// Whether no checkpoint is stored.
    pub fn is_empty(&self) -> bool {
        self.stored.is_empty()
    }

    /// Recomputes segment `c` (steps `c·m … min((c+1)·m, K)`) from its checkpoint, with the
    /// step Jacobians, into `segment` (its buffers reused).
    pub fn recompute(&self, c: usize, grid: &TimeGrid, segment: &mut Segment) -> Result<(), Error> {
        let Some((start, stepper)) = self.stored.get(c) else {
            return Ok(());
        };
        let mut stepper = stepper.clone();
        let first = c * self.every;
        let last = (first + self.every).min(grid.steps);
        let cols = 2 * stepper.dof() + stepper.parameters();
        let width = 2 * stepper.dof() * cols;
        segment.first = first;
        // The states' buffers are kept from segment to segment (`clone_from` reuses them).
        let len = last - first;
        segment.states.resize_with(len + 1, || State {
            t: 0.0,
            q: Vec::new(),
            p: Vec::new(),
        });
        segment.jacobians.resize_with(len, Vec::new);
        segment.states[0].clone_from(start);
        for i in 0..len {
            let (done, next) = segment.states.split_at_mut(i + 1);
            let (state, jac) = (&mut next[0], &mut segment.jacobians[i]);
            state.clone_from(&done[i]);
            jac.resize(width, 0.0);
            stepper.step_with_sensitivity(state, grid.step_size(first + i), jac)?;
            state.t = grid.time(first + i + 1);
        }
        Ok(())
    }
}
