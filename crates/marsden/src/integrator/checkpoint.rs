//! Checkpoints of an integrator: everything it carries from one step to the next, as plain
//! data, so that a run stopped after `k` steps and restored into a freshly built integrator of
//! the same problem continues bit for bit as if it had never stopped.
//!
//! What a step reads besides the state `(q_k, p_k)` and the integrator's configuration:
//!
//! * the predictor's history (the last three solutions, their `h`, a velocity hint), which is
//!   Newton's starting guess ([`super::predictor`]);
//! * on the separable path, the factored Jacobian of an earlier step and the last contraction
//!   rate, which decide whether it is reused ([`crate::separable::alpha`]);
//! * on the explicit path, the gradient `∇V(q_k)` the last step ended with (its first
//!   half-kick);
//! * with compensated summation, the rounding errors carried in `q` and `p`
//!   ([`super::compensated`]);
//! * with constraints, `Dφ(q_k)` computed by the last projection, and the projection's starting
//!   guess ([`crate::holonomic::MomentumProjection::carried`]);
//! * the last solution and its multipliers (what [`Integrator::multipliers`] and its siblings
//!   report), and the work counters.
//!
//! With the crate's `serde` feature an [`IntegratorCheckpoint`] serialises with any serde
//! format that keeps `f64` bit for bit (a binary one: the separable path's contraction rate
//! starts as NaN, which JSON has no word for).

use super::Integrator;
use super::compensated::CompensationCarry;
use super::path::Path;
use super::predictor::Predictor;
use super::report::Statistics;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::{Error, InputError};
use crate::holonomic::{MomentumProjection, ProjectionCarry};
use crate::mechanics::Constraint;
use crate::separable::{ExplicitCarry, SeparableCarry};

/// Everything an [`Integrator`] carries from one step to the next ([`Integrator::checkpoint`],
/// [`Integrator::restore`]): the predictor's history, the solution and multipliers of the last
/// step, and what each step path reuses (a factored Jacobian, a gradient, a compensated-sum
/// remainder), so that a restored integrator continues bit for bit.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct IntegratorCheckpoint {
    /// `(n, s, d)` of the step.
    shape: [usize; 3],
    path: Path,
    compensated: bool,
    statistics: Statistics,
    predictor: Predictor,
    /// The last solution `z` (offsets, multipliers, stage multipliers).
    solution: Vec<f64>,
    multipliers: Multipliers,
    constraint: ConstraintCarry,
    compensation: CompensationCarry,
    explicit: ExplicitCarry,
    separable: SeparableCarry,
    projection: ProjectionCarry,
}

/// The multipliers of the last step beyond those in its solution.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct Multipliers {
    projection: Vec<f64>,
    end: Vec<f64>,
    stages: Vec<f64>,
}

/// `Dφ(q_{k+1})` as the last projection left it for the next step, with the `q` it belongs to.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
struct ConstraintCarry {
    q: Vec<f64>,
    phi: Vec<f64>,
    dphi: Vec<f64>,
    current: bool,
}

impl IntegratorCheckpoint {
    /// Steps the integrator had completed.
    pub fn steps(&self) -> usize {
        self.statistics.steps
    }

    /// The work counters at the checkpoint.
    pub fn statistics(&self) -> &Statistics {
        &self.statistics
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// A checkpoint of everything this integrator carries to its next step (the state
    /// `(q, p)` itself is the caller's).
    pub fn checkpoint(&self) -> IntegratorCheckpoint {
        let (sh, b) = (self.shape, &self.buffers);
        IntegratorCheckpoint {
            shape: [sh.n, sh.s, sh.d],
            path: self.path,
            compensated: self.is_compensated(),
            statistics: self.statistics,
            predictor: self.predictor.clone(),
            solution: b.z.clone(),
            multipliers: Multipliers {
                projection: b.mu.clone(),
                end: b.lambda_end.clone(),
                stages: b.stage_multipliers.clone(),
            },
            constraint: ConstraintCarry {
                q: b.q_next.clone(),
                phi: b.phi.clone(),
                dphi: b.dphi0.clone(),
                current: b.dphi0_current,
            },
            compensation: self.compensation.carried(),
            explicit: b.explicit.carried(),
            separable: b.separable.carried(),
            projection: self.projection.carried(),
        }
    }

    /// Restores a checkpoint taken from an integrator of the same problem (same rule, forces,
    /// constraints and options): the next step from the checkpoint's state gives the numbers
    /// the checkpointed integrator would have given, bit for bit.
    ///
    /// # Errors
    /// [`InputError::DimensionMismatch`] if the step's sizes `(n, s, d)` differ,
    /// [`InputError::InvalidOption`] if the checkpoint was taken on another path (fast paths
    /// or compensated summation switched differently); the integrator is then unchanged.
    pub fn restore(&mut self, checkpoint: &IntegratorCheckpoint) -> Result<(), Error> {
        let sh = self.shape;
        let expected = [sh.n, sh.s, sh.d];
        let names = ["checkpoint n", "checkpoint s", "checkpoint d"];
        for ((what, e), f) in names.into_iter().zip(expected).zip(checkpoint.shape) {
            if e != f {
                return Err(Error::Input(InputError::DimensionMismatch {
                    what,
                    expected: e,
                    found: f,
                }));
            }
        }
        if checkpoint.path != self.path || checkpoint.compensated != self.is_compensated() {
            return Err(Error::Input(InputError::InvalidOption {
                name: "checkpoint",
                value: f64::NAN,
                reason: "taken by an integrator on another step path (fast paths or \
                         compensated summation set differently)",
            }));
        }
        self.statistics = checkpoint.statistics;
        self.predictor.clone_from(&checkpoint.predictor);
        let b = &mut self.buffers;
        b.z.clone_from(&checkpoint.solution);
        b.mu.clone_from(&checkpoint.multipliers.projection);
        b.lambda_end.clone_from(&checkpoint.multipliers.end);
        b.stage_multipliers
            .clone_from(&checkpoint.multipliers.stages);
        b.q_next.clone_from(&checkpoint.constraint.q);
        b.phi.clone_from(&checkpoint.constraint.phi);
        b.dphi0.clone_from(&checkpoint.constraint.dphi);
        b.dphi0_current = checkpoint.constraint.current;
        b.explicit.restore_carried(&checkpoint.explicit);
        b.separable.restore_carried(&checkpoint.separable);
        self.compensation.restore_carried(&checkpoint.compensation);
        self.projection.restore_carried(&checkpoint.projection);
        Ok(())
    }
}
