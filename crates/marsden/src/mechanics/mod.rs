//! The continuous system: a Lagrangian `L(t, q, v)` written once over the scalar type, forces
//! `f_L`, holonomic constraints `φ(q) = 0`, states and initial data, and what automatic
//! differentiation derives from them (Legendre transform, energy, Euler–Lagrange equations, the
//! potential of a separable Lagrangian).
//!
//! | module | seed concept |
//! |---|---|
//! | [`lagrangian`] | `L: TQ → ℝ`, its declared [`Structure`] (`L = ½ vᵀMv − V` with constant `M`) |
//! | [`force`] | Lagrangian forces `f_L(t, q, v)` |
//! | [`constraint`] | holonomic constraints `φ: Q → ℝ^d` |
//! | [`state`] | points `(t, q, p)` of phase space and initial data `(q₀, v₀)` or `(q₀, p₀)` |
//! | [`jet`] | Legendre transform `FL`, energy, Euler–Lagrange residual, accelerations, `FH` |
//! | [`kernel`] | a separable `L`'s own explicit (velocity Störmer–Verlet) run, e.g. compiled code |
//! | [`potential`] | `∇V`, `∇²V` of a separable `L`, hand-written ones checked against AD |
//! | [`structure`] | shortcuts for separable Lagrangians: `p = Mv`, `v = M⁻¹p` |

pub mod constraint;
pub(crate) mod constraint_jacobian;
pub mod force;
pub mod jet;
pub mod kernel;
pub mod lagrangian;
pub mod potential;
pub mod state;
pub mod structure;

pub use constraint::{Constraint, Unconstrained};
pub(crate) use constraint_jacobian::constraint_jacobian;
pub use force::{Force, NoForce};
pub use jet::{
    LagrangianJet, acceleration, check_regular, check_structure, dl_dq, energy,
    energy_from_momentum, euler_lagrange_residual, momentum, velocity,
};
pub use lagrangian::{Lagrangian, MassMatrix, Structure};
pub use state::{Initial, State};
