//! Derivatives through the simulation: tangent (forward) sensitivities of the discrete
//! Hamiltonian map along a run, and adjoint (reverse) gradients of a loss over its samples.
//!
//! The step `F̃_{L_d}: (q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of a variational integrator is the
//! solution of its step equations `R(z; q_k, p_k, θ) = 0` ([MW01] §1.5); its derivative is
//! taken by the implicit function theorem at the converged step,
//! `dz = −(∂R/∂z)⁻¹ ∂R/∂(q_k, p_k, θ)`, with every block a second derivative of the discrete
//! action from one hyper-dual evaluation
//! ([`crate::analysis::certificate::variational::frozen_step_jacobian`]) — never by
//! differentiating Newton's iterations, so the derivative is that of the exact discrete map
//! whatever the solver's path or iteration count (on the separable and explicit paths of the
//! α and trapezoid rules, the same derivative from `M` and `∇²V` alone,
//! [`crate::separable::jacobian`]). Rules (midpoint, trapezoid, α, Galerkin,
//! compositions) and discrete forces (Lagrange–d'Alembert) enter only through the action and
//! the forces, so all of them are covered.
//!
//! - [`step`]: what a stepper offers ([`SensitiveStep`], a [`crate::analysis::certificate::DifferentiableStep`]
//!   with parameter columns): one step with its Jacobian.
//! - [`tangent`](fn@tangent): `S_k = ∂(q_k, p_k)/∂(q₀, p₀, θ)` forward along a run ([`Tangent`]).
//! - [`adjoint`](fn@adjoint): `dΛ/d(q₀, p₀, θ)` of `Λ = Σ_k ℓ_k(q_k, p_k)`, backwards ([`Gradient`]; watched:
//!   [`adjoint_watched`]), over [`checkpoints`] so memory stays bounded.
//! - [`constrained`]: the step Jacobian of a constrained run (SHAKE + RATTLE, multipliers
//!   included; `projection` linearises the projection onto `T*N`).
//! - [`parametric`]: named parameters of the Lagrangian and the forces, held as coordinates
//!   that do not move ([`ParametricIntegrator`]); [`parametric_constrained`]: also of the
//!   constraints, with SHAKE + RATTLE ([`ConstrainedParametricIntegrator`]).
//! - [`cotangent`]: the symplecticity certificate of a constrained step, on `T*N` (a basis of
//!   its tangent space pushed through the step Jacobian).
//!
//! [MW01]: crate#references

pub mod adjoint;
pub mod checkpoints;
pub mod constrained;
pub mod cotangent;
pub mod options;
pub mod parametric;
pub mod parametric_constrained;
mod projection;
pub mod step;
pub mod tangent;

pub use adjoint::{Gradient, adjoint, adjoint_watched};
pub use options::{AdjointOptions, TangentOptions};
pub use parametric::{ParametricIntegrator, ParametricModel};
pub use parametric_constrained::ConstrainedParametricIntegrator;
pub use step::SensitiveStep;
pub use tangent::{
    Tangent, TangentCheckpoint, TangentSample, tangent, tangent_continued, tangent_streamed,
    tangent_watched,
};
