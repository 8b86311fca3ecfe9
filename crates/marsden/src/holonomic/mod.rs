//! Holonomic constraints `φ(q) = 0`: the SHAKE step, the RATTLE momentum projection, checks and
//! projections of initial data, and ready-made distance constraints.
//!
//! Concept of the notes (MW01): *constrained Lagrangian systems*. Motion on `N = φ⁻¹(0) ⊂ Q` extremises the augmented
//! action `∫ L − ⟨λ, φ(q)⟩ dt`, i.e. `∂L/∂q − d/dt ∂L/∂v = Dφ(q)ᵀλ`, `φ(q) = 0`.
//!
//! ## The constrained scheme
//!
//! One step `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of [`crate::integrator::Integrator`] with constraints
//! and a [`Rattle`] projection is ([MW01] §3.5, [LMO08] §3, [HLW06] §VII.1;
//! [conventions](crate#conventions)):
//!
//! ```text
//!  SHAKE:   p_k + D₁L_d(q_k, q_{k+1}) + f_d⁻ − h Dφ(q_k)ᵀ λ_k = 0,     φ(q_{k+1}) = 0,
//!           p̃_{k+1} = D₂L_d(q_k, q_{k+1}) + f_d⁺,
//!  RATTLE:  p_{k+1} = p̃_{k+1} − h Dφ(q_{k+1})ᵀ μ_k,   Dφ(q_{k+1}) · FH(t_{k+1}, q_{k+1}, p_{k+1}) = 0.
//! ```
//!
//! The first line is solved by Newton's method for `(q_{k+1}, λ_k)` in one system
//! (`crate::integrator::equations`); the projection is linear in `μ_k` for a constant mass matrix and solved by
//! Newton's method on `(v, μ)` in general ([`Rattle`]). Eliminating the momenta gives the
//! constrained discrete Euler–Lagrange equations
//! `D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) + f_d⁺ + f_d⁻ = h Dφ(q_k)ᵀ(λ_k + μ_{k−1})`: the
//! positions are those of SHAKE (the projection only moves `μ_{k−1}` out of the next `λ_k`),
//! while the momenta now lie on the cotangent bundle `T*N` (the *hidden* velocity constraint
//! holds), which is what makes the reported energy and momenta meaningful. For
//! `L = ½vᵀMv − V(q)` and the trapezoid rule the scheme is the classical RATTLE (Andersen 1983;
//! [HLW06] §VII.1) with HLW's multipliers `2λ_k` and `2μ_k`; without forces the map on `T*N` is
//! symplectic ([LR04] §7.3). The constraint force over a step is
//! `h Dφ(q_k)ᵀλ_k + h Dφ(q_{k+1})ᵀμ_k`, so `λ_k + μ_{k−1} ≈ λ(t_k)` of the continuous equations.
//!
//! Both multiplier series are kept in the [`crate::run::Trajectory`]: `multipliers(i)` holds `λ` and
//! `projection_multipliers(i)` holds `μ` of the step that ended at sample `i`. The multipliers
//! of the continuous equations implied by a state are [`multipliers_at`] (index reduction).
//!
//! ## Higher order
//!
//! With the constraint at the step end only, the constraint force is discretised at order 2
//! whatever the rule. Rules with internal stages therefore impose `φ = 0` at their stage points
//! too, one multiplier each ([`crate::discrete::DiscreteAction::constrained_stages`],
//! `crate::integrator::equations`): the Lobatto rules become constrained Lobatto IIIA–IIIB
//! ([Jay96]; [HLW06] §VII.1), order `2s − 2`; compositions impose it at every substep, so each
//! substep is a SHAKE + RATTLE step on `T*N` and the composition keeps its order ([Rei96]). The
//! Gauss rules need SPARK stage constraints (Jay 2007), not implemented: they are refused.
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references
//! [HLW06]: crate#references
//! [LR04]: crate#references
//! [Jay96]: crate#references
//! [Rei96]: crate#references
//!
//! ## Initial data
//!
//! [`crate::run::Problem::with_constraint`] refuses initial data off the manifold or not tangent to it
//! ([`check_initial`]), and constraints whose Jacobian is rank-deficient there
//! ([`constraint_rank`]); it never moves the data silently. Projections are explicit:
//! [`project_position`] (Newton on the minimum-norm correction; [`project_position_in_metric`] in
//! the mass metric, which [`crate::mechanics::Initial::project_onto`] uses), [`project_momentum`] (the RATTLE
//! projection) and [`crate::mechanics::Initial::project_onto`] for both.

mod distance;
mod initial;
mod multipliers;
mod rattle;

pub use distance::DistanceConstraints;
pub use initial::{
    ConstraintRank, DEFAULT_TOLERANCE, PositionProjection, RANK_TOLERANCE, check_initial,
    constraint_rank, project_momentum, project_position, project_position_in_metric,
};
pub use multipliers::multipliers_at;
pub use rattle::{
    MomentumProjection, NoProjection, ProjectionCarry, ProjectionFailure, ProjectionReport,
    ProjectionStatistics, Rattle,
};
