//! What a stepper must offer to be differentiated along a run: one step that also writes the
//! step's Jacobian with respect to the state and to the parameters it carries.
//!
//! The variational [`Integrator`] (unconstrained, with or without forces, every rule) gives
//! `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` by the implicit function theorem on its converged step
//! ([`crate::analysis::certificate::variational`]); every
//! [`crate::hamiltonian::HamiltonianIntegrator`] gives its own. Neither carries parameters
//! (`P = 0`); [`super::parametric::ParametricIntegrator`] carries `P` of them.

use crate::analysis::certificate::DifferentiableStep;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::{Error, InputError};
use crate::hamiltonian::{Hamiltonian, HamiltonianIntegrator, HamiltonianMethod};
use crate::integrator::{Integrator, StepReport};
use crate::holonomic::MomentumProjection;
use crate::mechanics::{Constraint, State};

/// A one-step map `(q_k, p_k; θ) ↦ (q_{k+1}, p_{k+1})` that reports its exact Jacobian.
pub trait SensitiveStep {
    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;

    /// Number of parameters `P` (the columns of the Jacobian beyond the state's `2n`).
    fn parameters(&self) -> usize;

    /// One plain step of size `h` from `state` (advanced in place, `state.t` included).
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error>;

    /// One step, also writing `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` into `jac` (row-major,
    /// `2n × (2n + P)`).
    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error>;
}

/// The error of an integrator whose last step left no stage offsets to differentiate (the
/// explicit path of a composition keeps only the final offset).
pub(super) fn no_stage_offsets() -> Error {
    Error::Input(InputError::InvalidOption {
        name: "fast_paths",
        value: 1.0,
        reason: "the explicit path of a composition keeps no stage offsets, so its step cannot \
                 be differentiated; build the integrator with with_fast_paths(false)",
    })
}

/// Every integrator type (a tangent run uses the very integrator type of the run); a step with
/// active holonomic constraints is refused by [`DifferentiableStep::step_with_jacobian`].
impl<A, F, C, P> SensitiveStep for Integrator<A, F, C, P>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    fn dof(&self) -> usize {
        self.shape().n
    }

    fn parameters(&self) -> usize {
        0
    }

    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        Integrator::step(self, state, h)
    }

    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let shape = self.shape();
        if self.is_explicit() && shape.s > 1 {
            return Err(no_stage_offsets());
        }
        DifferentiableStep::step_with_jacobian(self, state, h, jac)
    }
}

impl<H: Hamiltonian, M: HamiltonianMethod<H>> SensitiveStep for HamiltonianIntegrator<H, M> {
    fn dof(&self) -> usize {
        self.hamiltonian().dof()
    }

    fn parameters(&self) -> usize {
        0
    }

    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        HamiltonianIntegrator::step(self, state, h)
    }

    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        HamiltonianIntegrator::step_with_jacobian(self, state, h, jac)
    }
}
