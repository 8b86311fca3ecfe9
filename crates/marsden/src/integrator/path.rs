//! The path a step takes, chosen once: explicit Störmer–Verlet, the separable α-rule Newton,
//! the statically sized kernels (unconstrained or SHAKE), or the general Newton system with AD
//! Jacobians. Every path solves the same equations ([`super::equations`]); the fast ones have an
//! off-switch ([`Integrator::with_fast_paths`]) and tests compare them with the general path.

use super::Integrator;
use super::equations::{StepFunction, StepShape, StepSystem};
use super::failure::evaluations_of;
use super::small::constrained::{MAX_CONSTRAINTS, SmallConstrainedStep};
use super::small::solve_sized;
use super::small::unconstrained::SmallStep;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::holonomic::MomentumProjection;
use crate::mechanics::{Constraint, State, constraint_jacobian};
use crate::numerics::newton::{self, NewtonFailure, NewtonReport};
use crate::separable::{Frame, SeparableWorkspace};

/// Which solver takes the steps of an integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) enum Path {
    /// The explicit form of the action (velocity Störmer–Verlet and its compositions,
    /// [`crate::separable::explicit`]): unforced, unconstrained, not compensated.
    Explicit,
    /// The separable α-rule Newton step ([`crate::separable::alpha`]): two-point, unforced,
    /// unconstrained, `L = ½ vᵀMv − V` with a constant `M`.
    Separable,
    /// The statically sized kernel ([`super::small::unconstrained`]): two-point, unconstrained,
    /// `n ≤ 4`.
    Small,
    /// The statically sized SHAKE kernel ([`super::small::constrained`]): two-point, `n ≤ 4`,
    /// `1 ≤ d ≤ 4`.
    SmallConstrained,
    /// The step's Newton system with AD Jacobians ([`super::equations`]).
    General,
}

impl Path {
    /// The fastest path that solves the step of `shape` exactly as the general one does.
    /// `explicit`: the action has an explicit form; `separable`: its Lagrangian is separable
    /// (asked once, through `workspace`).
    pub(super) fn choose(
        shape: StepShape,
        fast_paths: bool,
        compensated: bool,
        explicit: bool,
        separable: impl FnOnce() -> bool,
    ) -> Path {
        let free = !shape.forced && shape.d == 0;
        let two_point = shape.s == 1;
        if !fast_paths {
            Path::General
        } else if free && !compensated && explicit {
            Path::Explicit
        } else if free && two_point && separable() {
            Path::Separable
        } else if two_point && shape.n <= 4 && shape.d == 0 {
            Path::Small
        } else if two_point && shape.n <= 4 && shape.d <= MAX_CONSTRAINTS {
            Path::SmallConstrained
        } else {
            Path::General
        }
    }
}

/// Whether the separable step of `action` applies (its Lagrangian declares a constant mass).
pub(super) fn separable_applies<A: DiscreteAction>(
    action: &A,
    workspace: &mut SeparableWorkspace,
) -> bool {
    action
        .separable()
        .is_some_and(|step| workspace.applies(step))
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Newton's method on the step equations from the predicted unknowns `z`, by the path chosen
    /// at construction.
    pub(super) fn solve(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        match self.path {
            Path::Separable => self.solve_separable(z, state, h),
            Path::Small => self.solve_small(z, state, h),
            Path::SmallConstrained => {
                self.prepare_constraint_jacobian(state);
                self.solve_small_constrained(z, state, h)
            }
            Path::General | Path::Explicit => {
                self.prepare_constraint_jacobian(state);
                self.solve_general(z, state, h)
            }
        }
    }

    /// `Dφ(q_k)` into the buffers: reused from the previous step's projection when the state is
    /// the one it left.
    fn prepare_constraint_jacobian(&mut self, state: &State) {
        let sh = self.shape;
        let b = &mut self.buffers;
        b.p_next.resize(sh.n, 0.0);
        let reuse = b.dphi0_current && b.q_next == state.q;
        if sh.d > 0 && !reuse {
            b.phi.resize(sh.d, 0.0);
            b.dphi0.resize(sh.d * sh.n, 0.0);
            constraint_jacobian(&self.constraint, &state.q, &mut b.phi, &mut b.dphi0);
        }
        b.dphi0_current = false;
    }

    /// The general path: the step's Newton system ([`super::equations`]) with AD Jacobians.
    fn solve_general(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        let sh = self.shape;
        let b = &mut self.buffers;
        let mut system = StepSystem {
            func: StepFunction {
                action: &self.action,
                force: &self.force,
                constraint: &self.constraint,
                t0: state.t,
                h,
                shape: sh,
                stage_multipliers: std::mem::take(&mut b.stage_multipliers),
            },
            q0: &state.q,
            p0: &state.p,
            dphi0: &b.dphi0,
            points: &mut b.points,
            parts: &mut b.parts,
            p_next: &mut b.p_next,
            ad_evaluations: 0,
            stage_scratch: std::mem::take(&mut b.stage_scratch),
        };
        let result = newton::solve(&mut system, z, &self.options, &mut b.newton);
        self.statistics.action_evaluations += system.ad_evaluations;
        b.stage_multipliers = std::mem::take(&mut system.func.stage_multipliers);
        b.stage_scratch = std::mem::take(&mut system.stage_scratch);
        if let Ok(r) | Err(NewtonFailure::NotConverged(r)) | Err(NewtonFailure::NonFinite(r)) =
            &result
        {
            self.statistics.system_evaluations += r.evaluations;
        }
        result
    }

    /// The structured Newton step of a separable Lagrangian ([`crate::separable::alpha`]) for
    /// two-point, unforced, unconstrained steps; chosen once ([`Path::Separable`]).
    fn solve_separable(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        let sh = self.shape;
        let b = &mut self.buffers;
        b.p_next.resize(sh.n, 0.0);
        let frame = Frame {
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
        };
        let Some(result) = self.action.solve_separable_step(
            frame,
            z,
            &mut b.p_next,
            &self.options,
            &mut b.separable,
        ) else {
            return self.solve_general(z, state, h);
        };
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.potential_gradients += evaluations;
        result
    }

    /// The statically sized step ([`crate::integrator::small::unconstrained`]) for two-point, unconstrained steps with
    /// `n ≤ 4`.
    fn solve_small(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        let sh = self.shape;
        let small = SmallStep {
            action: &self.action,
            force: &self.force,
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
        };
        let o = &self.options;
        let p_next = &mut self.buffers.p_next;
        p_next.resize(sh.n, 0.0);
        let Some(result) = solve_sized(self.dispatch, &small, sh.n, z, o, p_next) else {
            return self.solve_general(z, state, h);
        };
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.action_evaluations += evaluations;
        result
    }

    /// The statically sized constrained (SHAKE) step ([`crate::integrator::small::constrained`]) for
    /// two-point steps with `n ≤ 4` and `1 ≤ d ≤ 4`, once `Dφ(q_k)` is in the buffers.
    fn solve_small_constrained(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        let sh = self.shape;
        let b = &mut self.buffers;
        let small = SmallConstrainedStep {
            action: &self.action,
            force: &self.force,
            constraint: &self.constraint,
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
            dphi0: &b.dphi0,
            d: sh.d,
        };
        let (o, p_next) = (&self.options, &mut b.p_next);
        let Some(result) = solve_sized(self.dispatch, &small, sh.n, z, o, p_next) else {
            return self.solve_general(z, state, h);
        };
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.action_evaluations += evaluations;
        result
    }
}
