//! Discrete mechanics: discrete Lagrangians, their derivatives and discrete Legendre transforms.
//!
//! Concept of the notes (MW01): *discrete variational mechanics*. A discrete Lagrangian `L_d(q₀, q₁, h) ≈ ∫₀ʰ L dt`
//! replaces the action of one step; the discrete action `Σ L_d(q_k, q_{k+1})` is made
//! stationary, which gives the discrete Euler–Lagrange (DEL) equations
//!
//! ```text
//!     D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0,
//! ```
//!
//! and the discrete Legendre transforms ([MW01] §1.3, [conventions](crate#conventions))
//!
//! ```text
//!     F⁻L_d(q₀, q₁) = (q₀, −D₁L_d(q₀, q₁)),     F⁺L_d(q₀, q₁) = (q₁, D₂L_d(q₀, q₁)).
//! ```
//!
//! Two traits: [`DiscreteLagrangian`] is the two-point `L_d(q₀, q₁)` a user may supply directly;
//! [`DiscreteAction`] is what the integrator steps: `L_d` written over the control points
//! `Q₀ = q_k, Q₁, …, Q_s = q_{k+1}` of one step, so that Galerkin rules can expose internal stages
//! as unknowns of the same Newton solve. Every `DiscreteLagrangian` is a `DiscreteAction` with no
//! internal stages.
//!
//! [MW01]: crate#references

use crate::scalar::Scalar;

use crate::numerics::newton::{NewtonFailure, NewtonOptions, NewtonReport};
use crate::numerics::scratch::{Buffer, NODE};
use crate::separable::ExplicitStep;
use crate::separable::{Frame, SeparableJacobian, SeparableStep, SeparableWorkspace};

/// A two-point discrete Lagrangian `L_d(t₀, h, q₀, q₁)`.
///
/// ```
/// use marsden::{DiscreteLagrangian, Scalar};
///
/// /// Midpoint discrete Lagrangian of the unit harmonic oscillator, written by hand.
/// struct OscillatorLd;
/// impl DiscreteLagrangian for OscillatorLd {
///     fn dof(&self) -> usize { 1 }
///     fn discrete_lagrangian<S: Scalar>(&self, _t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
///         let v = (q1[0] - q0[0]) / h;
///         let q = (q0[0] + q1[0]) * 0.5;
///         (v * v - q * q) * (0.5 * h)
///     }
/// }
/// ```
pub trait DiscreteLagrangian {
    /// The number of degrees of freedom, when the type fixes it (the catalog systems): the
    /// integrator then compiles its statically sized step kernels for that size only. A wrong
    /// value costs speed, never correctness (the general path takes the steps). Default: `None`.
    const FIXED_DOF: Option<usize> = None;

    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;

    /// `L_d(q₀, q₁)` for the step from `t₀` to `t₀ + h`.
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S;

    /// `L_d(q₀, q₀ + Δ)`, given the displacement `Δ = q₁ − q₀` exactly.
    ///
    /// The integrator steps displacements: `q₁ − q₀` recomputed from rounded positions carries an
    /// error `ε|q|`, which a difference quotient `(q₁ − q₀)/h` turns into a momentum error
    /// `ε|q|/h` per step, visible as a random walk of conserved momenta. The default forms
    /// `q₁ = q₀ + Δ`; override it (as the built-in rules do) to use `Δ` directly.
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        let mut q1 = Buffer::<S, NODE>::empty();
        let q1 = q1.from_fn(q0.len(), S::from(0.0), |i| q0[i] + delta[i]);
        self.discrete_lagrangian(t0, h, q0, q1)
    }

    /// An explicit form of the step, if this discrete Lagrangian has one (the trapezoid rule on a
    /// separable Lagrangian: velocity Störmer–Verlet, [`crate::separable::explicit`]). Default: none.
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        None
    }

    /// A structured Newton step, if this discrete Lagrangian may have one (the α rules on a
    /// separable Lagrangian: Jacobian `M/h + hα(1−α)∇²V`, [`crate::separable::alpha`]; whether the
    /// Lagrangian really is separable is asked once, [`SeparableStep::mass`]). Default: none.
    fn separable(&self) -> Option<&dyn SeparableStep> {
        None
    }

    /// The step Jacobian from the structure of a separable Lagrangian, if this two-point rule
    /// has one (the α and symmetrised α rules: `M` and `∇²V` at the nodes,
    /// [`crate::separable::jacobian`]). Default: none.
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        None
    }
}

/// A discrete Lagrangian over the control points of one step (what the integrator steps).
///
/// The control points `Q₀ = q_k, Q₁, …, Q_s = q_{k+1}` (`s = internal_stages() + 1`) are given as
/// `q0 = Q₀` and the offsets `Δ_j = Q_j − Q₀` back to back (length `s·n`). The step solves
/// `∂L_d/∂Q_j = 0` for the internal points together with the discrete Legendre transform for
/// `q_{k+1}`; derivatives are always taken with respect to the control points `Q_j`.
pub trait DiscreteAction {
    /// The number of degrees of freedom, when the type fixes it (the catalog systems): the
    /// integrator then compiles its statically sized step kernels for that size only. A wrong
    /// value costs speed, never correctness (the general path takes the steps). Default: `None`.
    const FIXED_DOF: Option<usize> = None;

    /// Whether a step may be two-point (no internal control points) for some value of the
    /// type; `false` lets the integrator skip compiling the two-point kernels (compositions).
    /// Default: `true`.
    const MAY_BE_TWO_POINT: bool = true;

    /// The number of internal control points when the type fixes it (0 for every two-point
    /// [`DiscreteLagrangian`]); with [`DiscreteAction::FIXED_DOF`] it bounds the size of the
    /// step's AD evaluations, so that only the chunk widths it needs are compiled. Default:
    /// `None`.
    const FIXED_STAGES: Option<usize> = None;

    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;
    /// Number of internal control points per step (0 for two-point discrete Lagrangians).
    fn internal_stages(&self) -> usize {
        0
    }
    /// The discrete action of one step as a function of `Q₀` and the offsets `Q_j − Q₀`.
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S;

    /// An explicit form of the step, if any (see [`DiscreteLagrangian::explicit`]).
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        None
    }

    /// A structured Newton step, if any (see [`DiscreteLagrangian::separable`]).
    fn separable(&self) -> Option<&dyn SeparableStep> {
        None
    }

    /// The step of [`DiscreteAction::separable`], if any, called through this type: a rule
    /// chosen at run time ([`crate::discrete::rules::chosen`]) forwards it to its variant, so
    /// that the call is direct (a call through the `dyn` reference stays a virtual call where
    /// the build does not optimise across crates).
    #[inline]
    fn solve_separable_step(
        &self,
        frame: Frame<'_>,
        z: &mut [f64],
        p_next: &mut [f64],
        options: &NewtonOptions,
        ws: &mut SeparableWorkspace,
    ) -> Option<Result<NewtonReport, NewtonFailure>> {
        let step = self.separable()?;
        Some(step.solve_separable(frame, z, p_next, options, ws))
    }

    /// A structured step Jacobian, if any (see [`DiscreteLagrangian::separable_jacobian`]).
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        None
    }

    /// Stage constraints: the number of interior points of a step at which a holonomic
    /// constraint `φ = 0` is imposed besides the end point, each with its own multiplier, so
    /// that a constrained step keeps the rule's order (constrained Lobatto IIIA–IIIB, [Jay96];
    /// compositions of RATTLE steps, [Rei96]); `Err(reason)` when the rule has no constrained
    /// form of its order. Default: `Ok(0)` (two-point rules: SHAKE + RATTLE has their order 2).
    ///
    /// [Jay96]: crate#references
    /// [Rei96]: crate#references
    fn constrained_stages(&self) -> Result<usize, String> {
        Ok(0)
    }

    /// The position at constrained stage `i` (`0 ≤ i < constrained_stages()`) from `Q₀` and the
    /// offsets (a linear combination of the control points with weights summing to 1). Default:
    /// `Q₀` (never called when there are no stage constraints).
    fn stage_point<S: Scalar>(&self, i: usize, q0: &[S], offsets: &[S], out: &mut [S]) {
        let _ = (i, offsets);
        out.copy_from_slice(q0);
    }

    /// The weight `w` of the end point in the step's quadrature of the constraint force: the
    /// projection multipliers `μ_k` of a constrained step approximate `w λ(t_{k+1})` of the
    /// continuous equations (`½` for symmetric two-point rules; `b_s` for Lobatto; `γ_m` times
    /// the base's for compositions). Default: `½`.
    fn end_weight(&self) -> f64 {
        0.5
    }
}

impl<D: DiscreteLagrangian + ?Sized> DiscreteLagrangian for &D {
    const FIXED_DOF: Option<usize> = D::FIXED_DOF;
    fn dof(&self) -> usize {
        (**self).dof()
    }
    #[inline(always)]
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        (**self).discrete_lagrangian(t0, h, q0, q1)
    }
    #[inline(always)]
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        (**self).discrete_lagrangian_offset(t0, h, q0, delta)
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        (**self).explicit()
    }
    fn separable(&self) -> Option<&dyn SeparableStep> {
        (**self).separable()
    }
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        (**self).separable_jacobian()
    }
}

impl<T: DiscreteLagrangian> DiscreteAction for T {
    const FIXED_DOF: Option<usize> = T::FIXED_DOF;
    const FIXED_STAGES: Option<usize> = Some(0);
    fn dof(&self) -> usize {
        DiscreteLagrangian::dof(self)
    }
    #[inline(always)]
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S {
        self.discrete_lagrangian_offset(t0, h, q0, offsets)
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        DiscreteLagrangian::explicit(self)
    }
    fn separable(&self) -> Option<&dyn SeparableStep> {
        DiscreteLagrangian::separable(self)
    }
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        DiscreteLagrangian::separable_jacobian(self)
    }
}

/// The length `(s + 1)·n` of the control points `Q₀ … Q_s` of a step of `A`, when its type fixes
/// it.
pub(crate) const fn fixed_points<A: DiscreteAction + ?Sized>() -> Option<usize> {
    match (A::FIXED_DOF, A::FIXED_STAGES) {
        (Some(n), Some(stages)) => Some((stages + 2) * n),
        _ => None,
    }
}
