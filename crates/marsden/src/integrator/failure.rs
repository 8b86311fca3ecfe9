//! What a failed step reports: the Newton failure mapped to a typed error carrying the step,
//! the time and the numbers a user needs (an unsatisfiable constraint is named as such).

use super::Integrator;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::{StepError, StepFailure};
use crate::holonomic::MomentumProjection;
use crate::mechanics::{Constraint, State};
use crate::numerics::dense::max_norm;
use crate::numerics::newton::{NewtonFailure, NewtonReport};

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Fails if the converged `Δ_s = q_{k+1} − q_k` or `p_{k+1}` is not finite.
    #[inline(always)]
    pub(super) fn check_finite(&self, z: &[f64], step: usize, t: f64) -> Result<(), Error> {
        let sn = self.shape.s * self.shape.n;
        let q_next = &z[sn - self.shape.n..sn];
        // Two plain loops: a chained iterator stayed a call of its own.
        let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
        if finite(q_next) && finite(&self.buffers.p_next) {
            Ok(())
        } else {
            Err(Error::Step(StepFailure {
                step,
                t,
                cause: StepError::NonFinite {
                    what: "the new state",
                },
            }))
        }
    }

    pub(super) fn newton_error(
        &self,
        failure: NewtonFailure,
        step: usize,
        state: &State,
        z: &[f64],
    ) -> Error {
        let t = state.t;
        if let Some(error) = self.constraint_error(&failure, step, state, z) {
            return error;
        }
        match failure {
            NewtonFailure::NotConverged(r) => Error::Step(StepFailure {
                step,
                t,
                cause: StepError::NewtonDidNotConverge {
                    iterations: r.iterations,
                    residual: r.residual,
                    tolerance: self.options.residual_tolerance,
                },
            }),
            NewtonFailure::Singular { iteration, pivot } => Error::Step(StepFailure {
                step,
                t,
                cause: StepError::SingularJacobian { iteration, pivot },
            }),
            NewtonFailure::NonFinite(_) => Error::Step(StepFailure {
                step,
                t,
                cause: StepError::NonFinite {
                    what: "the Newton residual",
                },
            }),
        }
    }

    /// A failed constrained step whose constraint equations `φ(q_{k+1}) = 0` were left unsolved
    /// is reported as [`Error::ConstraintNotSatisfied`] (e.g. an unsatisfiable constraint).
    pub(super) fn constraint_error(
        &self,
        failure: &NewtonFailure,
        step: usize,
        state: &State,
        z: &[f64],
    ) -> Option<Error> {
        let sh = self.shape;
        if sh.d == 0 {
            return None;
        }
        // φ at the last Newton iterate q_k + Δ_s (both solvers leave it in `z`).
        let delta = z.get(sh.s * sh.n - sh.n..sh.s * sh.n)?;
        let q_end: Vec<f64> = state.q.iter().zip(delta).map(|(q, d)| q + d).collect();
        let mut phi = vec![0.0; sh.d];
        self.constraint.constraint(&q_end, &mut phi);
        let (index, value) = phi.iter().enumerate().fold((0, 0.0_f64), |best, (i, &v)| {
            if v.abs() > best.1.abs() { (i, v) } else { best }
        });
        let tol = self.options.residual_tolerance * max_norm(&state.p).max(1.0);
        let iterations = match *failure {
            NewtonFailure::NotConverged(r) | NewtonFailure::NonFinite(r) => r.iterations,
            NewtonFailure::Singular { iteration, .. } => iteration,
        };
        (value.is_finite() && value.abs() > tol).then_some(Error::Step(StepFailure {
            step,
            t: state.t,
            cause: StepError::ConstraintNotSatisfied {
                index,
                residual: value,
                iterations,
            },
        }))
    }
}

/// System evaluations of one Newton solve, converged or not (a singular Jacobian at iteration
/// `i` follows `i + 1` evaluations).
pub(super) fn evaluations_of(result: &Result<NewtonReport, NewtonFailure>) -> usize {
    match result {
        Ok(r) | Err(NewtonFailure::NotConverged(r)) | Err(NewtonFailure::NonFinite(r)) => {
            r.evaluations
        }
        Err(NewtonFailure::Singular { iteration, .. }) => iteration + 1,
    }
}
