//! The explicit path: steps of an action with an explicit form (velocity Störmer–Verlet, the
//! trapezoid rule on a separable Lagrangian, and its compositions; [`crate::separable::explicit`]),
//! one at a time or many in one loop with no per-step dispatch or copies.

use super::Integrator;
use super::path::Path;
use super::report::StepReport;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::{StepError, StepFailure};
use crate::holonomic::MomentumProjection;
use crate::mechanics::kernel::RunGrid;
use crate::mechanics::{Constraint, State};

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// [`Integrator::advance`] on the explicit path: the first `steps − 1` steps in one
    /// [`crate::separable::ExplicitStep::explicit_run`], the last by [`Integrator::step`], so
    /// that [`Integrator::stage_offsets`] holds the last step's exact offset, as after single
    /// steps (the run loop keeps no offsets).
    pub(super) fn advance_explicit(
        &mut self,
        state: &mut State,
        h: f64,
        steps: usize,
    ) -> Result<StepReport, Error> {
        let Some(last) = steps.checked_sub(1) else {
            return Ok(StepReport::default());
        };
        let t0 = state.t;
        if let (Some(explicit), true) = (self.action.explicit(), last > 0) {
            let grid = RunGrid { t0, h, steps: last };
            let run =
                explicit.explicit_run(grid, &mut state.q, &mut state.p, &mut self.buffers.explicit);
            let st = &mut self.statistics;
            st.potential_gradients += run.gradients;
            st.steps += run.steps;
            st.explicit_steps += run.steps;
            state.t = t0 + run.steps as f64 * h;
            if run.steps < last {
                st.failed_steps += 1;
                return Err(Error::Step(StepFailure {
                    step: st.steps,
                    t: state.t,
                    cause: StepError::NonFinite {
                        what: "the new state",
                    },
                }));
            }
        }
        let report = self.step(state, h)?;
        state.t = t0 + steps as f64 * h;
        Ok(report)
    }

    /// The explicit step ([`crate::separable::explicit`]) when the action has one and nothing else (forces,
    /// constraints) enters the step; `Ok(None)` when it does not apply.
    pub(super) fn step_explicit(
        &mut self,
        state: &mut State,
        h: f64,
        step: usize,
    ) -> Result<Option<StepReport>, Error> {
        let sh = self.shape;
        // An action with internal stages may be explicit too (a composition of Verlet steps).
        if self.path != Path::Explicit {
            return Ok(None);
        }
        let Some(explicit) = self.action.explicit() else {
            return Ok(None);
        };
        let b = &mut self.buffers;
        b.p_next.clone_from(&state.p);
        b.z.resize(sh.n, 0.0);
        let gradients = explicit.explicit_step(
            state.t,
            h,
            &state.q,
            &mut b.p_next,
            &mut b.z,
            &mut b.explicit,
        );
        self.statistics.potential_gradients += gradients;
        if !b.z.iter().chain(&b.p_next).all(|x| x.is_finite()) {
            self.statistics.failed_steps += 1;
            return Err(Error::Step(StepFailure {
                step,
                t: state.t,
                cause: StepError::NonFinite {
                    what: "the new state",
                },
            }));
        }
        state.q.iter_mut().zip(&b.z).for_each(|(q, d)| *q += d);
        state.p.copy_from_slice(&b.p_next);
        state.t += h;
        self.statistics.steps += 1;
        self.statistics.explicit_steps += 1;
        Ok(Some(StepReport::default()))
    }
}
