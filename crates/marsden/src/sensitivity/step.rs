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
use crate::error::Error;
use crate::hamiltonian::{Hamiltonian, HamiltonianIntegrator, HamiltonianMethod};
use crate::integrator::{Integrator, StepReport};
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
}

/// The integrator without constraints or projection (the type of `Integrator::new`); the one
/// [`crate::run::Problem::integrator`] builds (SHAKE + RATTLE, constraints or none) is
/// differentiated in [`super::constrained`].
impl<A: DiscreteAction, F: DiscreteForce> SensitiveStep for Integrator<A, F, Unconstrained> {}

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
