//! What a step Jacobian needs of the integrator: the start `q_k` of the step, kept in a buffer,
//! and, where the step took the separable or explicit path of a two-point rule, the Jacobian
//! from the structure of the separable Lagrangian ([`crate::separable::jacobian`]); every other
//! step is differentiated by the general implicit function theorem
//! ([`crate::analysis::certificate::variational`]).

use super::Integrator;
use super::path::Path;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::holonomic::MomentumProjection;
use crate::integrator::StepReport;
use crate::mechanics::{Constraint, State};

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// One step that keeps its start `q_k` ([`Integrator::step_start`]) without allocating.
    pub(crate) fn step_keeping_start(
        &mut self,
        state: &mut State,
        h: f64,
    ) -> Result<StepReport, Error> {
        self.buffers.start.clone_from(&state.q);
        self.step(state, h)
    }

    /// `q_k` of the last step taken by [`Integrator::step_keeping_start`].
    pub(crate) fn step_start(&self) -> &[f64] {
        &self.buffers.start
    }

    /// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` (row-major `2n × 2n`) of the last step taken by
    /// [`Integrator::step_keeping_start`] from time `t0`, by the structure of a separable
    /// Lagrangian, when that step took the separable or explicit path of a two-point rule;
    /// `None` otherwise, `Some(Err(pivot))` when the step's `A` is singular.
    pub(crate) fn separable_jacobian(
        &mut self,
        t0: f64,
        h: f64,
        jac: &mut [f64],
    ) -> Option<Result<(), f64>> {
        let sh = self.shape;
        let free = !sh.forced && sh.d == 0 && sh.s == 1;
        if !free || !matches!(self.path, Path::Separable | Path::Explicit) {
            return None;
        }
        let step = self.action.separable_jacobian()?;
        let b = &mut self.buffers;
        let delta = b.z.get(..sh.n)?;
        step.step_jacobian((t0, h), (&b.start, delta), jac, &mut b.jacobian)
    }
}
