//! The momentum projection after a solved step (RATTLE, [`crate::holonomic::Rattle`]):
//! `p_{k+1} = p̃_{k+1} − h Dφ(q_{k+1})ᵀ μ_k`, so that `(q_{k+1}, p_{k+1})` lies on the cotangent
//! bundle of the constraint manifold ([conventions](crate#conventions); [LMO08]). With the rule's
//! end weight `w` ([`crate::discrete::DiscreteAction::end_weight`]) `μ_k / w` estimates the
//! multiplier `λ(t_{k+1})` of the continuous equations (kept as [`Integrator::end_multipliers`]).
//!
//! [LMO08]: crate#references

use super::Integrator;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::{StepError, StepFailure};
use crate::holonomic::MomentumProjection;
use crate::mechanics::{Constraint, State, constraint_jacobian};

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Applies the momentum projection to `p_{k+1}` (in the buffers, so that a failure leaves
    /// `state` untouched) and keeps its multipliers as `μ_k = ν/h`.
    pub(super) fn project(
        &mut self,
        z: &[f64],
        state: &State,
        h: f64,
        step: usize,
    ) -> Result<(), Error> {
        if !self.projection.is_active() {
            return Ok(());
        }
        let (n, sn) = (self.shape.n, self.shape.s * self.shape.n);
        let weight = self.action.end_weight();
        let (b, d) = (&mut self.buffers, self.shape.d);
        b.q_next.clear();
        b.q_next
            .extend(state.q.iter().zip(&z[sn - n..sn]).map(|(q, d)| q + d));
        b.phi_next.resize(d, 0.0);
        b.dphi_next.resize(d * n, 0.0);
        if d > 0 {
            constraint_jacobian(
                &self.constraint,
                &b.q_next,
                &mut b.phi_next,
                &mut b.dphi_next,
            );
        }
        let t = state.t + h;
        let projected = self
            .projection
            .project(t, &b.q_next, &b.dphi_next, &mut b.p_next);
        match projected {
            Ok(_) => {
                b.mu.clear();
                b.mu.extend(self.projection.multipliers().iter().map(|nu| nu / h));
                b.lambda_end.clear();
                b.lambda_end.extend(b.mu.iter().map(|mu| mu / weight));
                // Dφ(q_{k+1}) serves the next step too (see `solve`).
                std::mem::swap(&mut b.dphi0, &mut b.dphi_next);
                b.dphi0_current = d > 0;
                Ok(())
            }
            Err(failure) => Err(Error::Step(StepFailure {
                step,
                t,
                cause: StepError::MomentumProjectionFailed {
                    iterations: failure.iterations,
                    residual: failure.residual,
                },
            })),
        }
    }
}
