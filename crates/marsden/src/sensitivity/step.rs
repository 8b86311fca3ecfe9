//! What a stepper must offer to be differentiated along a run: one step that also writes the
//! step's Jacobian with respect to the state and to the parameters it carries.
//!
//! [`SensitiveStep`] extends [`DifferentiableStep`] (one step and `∂(q_{k+1}, p_{k+1})/∂(q_k,
//! p_k)`) with parameter columns. The variational [`Integrator`] (unconstrained, with or without
//! forces, every rule) and every [`crate::hamiltonian::HamiltonianIntegrator`] carry none
//! (`P = 0`) and use their [`DifferentiableStep`] Jacobian
//! ([`crate::analysis::certificate::variational`]); the constrained one (SHAKE + RATTLE,
//! [`crate::holonomic::Rattle`]) gives its Jacobian on tangent vectors of `T*N`
//! ([`super::constrained`]); [`super::parametric::ParametricIntegrator`] and
//! [`super::parametric_constrained::ConstrainedParametricIntegrator`] carry `P` parameters.

use crate::analysis::certificate::DifferentiableStep;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::{Error, InputError};
use crate::hamiltonian::{Hamiltonian, HamiltonianIntegrator, HamiltonianMethod};
use crate::integrator::{Integrator, IntegratorCheckpoint, StepReport};
use crate::mechanics::{State, Unconstrained};

/// A one-step map `(q_k, p_k; θ) ↦ (q_{k+1}, p_{k+1})` that reports its exact Jacobian with
/// respect to the state and to `P` parameters.
pub trait SensitiveStep: DifferentiableStep {
    /// Number of parameters `P` (the columns of the Jacobian beyond the state's `2n`);
    /// default none.
    fn parameters(&self) -> usize {
        0
    }

    /// One step, also writing `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` into `jac` (row-major,
    /// `2n × (2n + P)`); default: [`DifferentiableStep::step_with_jacobian`] (`P = 0`).
    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        self.step_with_jacobian(state, h, jac)
    }

    /// Everything the stepper carries from one step to the next (its predictor's history,
    /// warm starts, counters: [`IntegratorCheckpoint`]), so that a tangent run can be
    /// checkpointed and continued bit for bit ([`super::tangent::tangent_continued`]);
    /// `None` (the default) for a stepper that cannot be checkpointed.
    fn carried(&self) -> Option<IntegratorCheckpoint> {
        None
    }

    /// Restores what [`SensitiveStep::carried`] gave, into a stepper of the same problem
    /// freshly built.
    ///
    /// # Errors
    /// The integrator's refusal of a checkpoint of another shape or path; by default (a
    /// stepper that cannot be checkpointed) [`InputError::InvalidOption`].
    fn restore_carried(&mut self, carried: &IntegratorCheckpoint) -> Result<(), Error> {
        let _ = carried;
        Err(Error::Input(InputError::InvalidOption {
            name: "checkpoint",
            value: f64::NAN,
            reason: "this stepper carries no checkpoint to restore",
        }))
    }
}

/// [`SensitiveStep::carried`] and [`SensitiveStep::restore_carried`] of a stepper that is an
/// [`Integrator`] in the field `$run`.
macro_rules! carried_by {
    ($run:ident) => {
        fn carried(&self) -> Option<$crate::integrator::IntegratorCheckpoint> {
            Some(self.$run.checkpoint())
        }

        fn restore_carried(
            &mut self,
            carried: &$crate::integrator::IntegratorCheckpoint,
        ) -> Result<(), $crate::error::Error> {
            self.$run.restore(carried)
        }
    };
}
pub(super) use carried_by;

/// The integrator without constraints or projection (the type of `Integrator::new`); the one
/// [`crate::run::Problem::integrator`] builds (SHAKE + RATTLE, constraints or none) is
/// differentiated in [`super::constrained`].
impl<A: DiscreteAction, F: DiscreteForce> SensitiveStep for Integrator<A, F, Unconstrained> {
    fn carried(&self) -> Option<IntegratorCheckpoint> {
        Some(self.checkpoint())
    }

    fn restore_carried(&mut self, carried: &IntegratorCheckpoint) -> Result<(), Error> {
        self.restore(carried)
    }
}

impl<H: Hamiltonian, M: HamiltonianMethod<H>> SensitiveStep for HamiltonianIntegrator<H, M> {}

/// [`DifferentiableStep`] of a parametric integrator (`Type<R: Rule, M: ParametricModel>`) by
/// the integrator in its field `run`: the step and its `(q_k, p_k)` Jacobian, as the run's
/// integrator gives them.
macro_rules! differentiable_by_run {
    ($ty:ident) => {
        impl<R, M> $crate::analysis::certificate::DifferentiableStep for $ty<R, M>
        where
            R: $crate::discrete::rules::Rule,
            M: $crate::sensitivity::ParametricModel + Clone,
        {
            fn dof(&self) -> usize {
                self.run.shape().n
            }

            fn step(
                &mut self,
                state: &mut $crate::mechanics::State,
                h: f64,
            ) -> Result<$crate::integrator::StepReport, $crate::error::Error> {
                self.run.step(state, h)
            }

            fn step_with_jacobian(
                &mut self,
                state: &mut $crate::mechanics::State,
                h: f64,
                jac: &mut [f64],
            ) -> Result<$crate::integrator::StepReport, $crate::error::Error> {
                self.run.step_with_jacobian(state, h, jac)
            }
        }
    };
}
pub(super) use differentiable_by_run;
