//! A run of rigid bodies over many steps, sampled every `every` steps.
//!
//! The core's [`crate::run::Trajectory`] pairs positions and momenta of equal length; a rigid
//! body has 9 numbers of attitude and 3 of momentum, so the samples of a rigid run are kept here:
//! one [`RigidState`] per sample. A failed step ends the run with the samples taken so far and the
//! typed error ([`RigidRunFailure`]).

use super::lgvi::Lgvi;
use super::potential::{ExternalLoads, RigidPotential};
use super::state::RigidState;
use crate::error::Error;

/// The samples of a rigid-body run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RigidTrajectory {
    /// The sampled states, the initial one first.
    pub states: Vec<RigidState>,
}

impl RigidTrajectory {
    /// The sample times.
    pub fn times(&self) -> Vec<f64> {
        self.states.iter().map(|s| s.t).collect()
    }

    /// The last sample.
    pub fn last(&self) -> Option<&RigidState> {
        self.states.last()
    }

    /// A quantity along the samples (an invariant of [`super::invariants`], say).
    pub fn map<T>(&self, f: impl FnMut(&RigidState) -> T) -> Vec<T> {
        self.states.iter().map(f).collect()
    }
}

/// A run that stopped at a failed step: the samples taken before it, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidRunFailure {
    /// The samples up to the last completed step (that state included).
    pub trajectory: RigidTrajectory,
    /// The step failure.
    pub error: Error,
}

impl std::fmt::Display for RigidRunFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ({} samples kept)",
            self.error,
            self.trajectory.states.len()
        )
    }
}

impl std::error::Error for RigidRunFailure {}

/// Takes `steps` steps of `stepper`, sampling its state at the start and every `every` steps (and
/// after the last step).
///
/// # Errors
/// [`RigidRunFailure`] at the first failed step, with the samples so far and the state before
/// that step.
pub fn run<U: RigidPotential, E: ExternalLoads>(
    stepper: &mut Lgvi<U, E>,
    steps: usize,
    every: usize,
) -> Result<RigidTrajectory, Box<RigidRunFailure>> {
    let every = every.max(1);
    let mut trajectory = RigidTrajectory {
        states: Vec::with_capacity(steps / every + 2),
    };
    trajectory.states.push(stepper.state().clone());
    for k in 1..=steps {
        if let Err(error) = stepper.step() {
            if k > 1 && (k - 1) % every != 0 {
                trajectory.states.push(stepper.state().clone());
            }
            return Err(Box::new(RigidRunFailure { trajectory, error }));
        }
        if k % every == 0 || k == steps {
            trajectory.states.push(stepper.state().clone());
        }
    }
    Ok(trajectory)
}
