//! Ready-made external forces and the ways to combine and convert them.
//!
//! Concept of the notes (MW01): *forced Lagrangian systems*, *forced Hamiltonian systems*, *discrete variational
//! mechanics with forces*. A Lagrangian force `f_L(t, q, v)` ([`crate::mechanics::Force`]) enters the
//! Lagrange–d'Alembert principle `δ∫L dt + ∫⟨f_L, δq⟩ dt = 0`, i.e. the forced Euler–Lagrange
//! equations `∂L/∂q − d/dt ∂L/∂v + f_L = 0` ([MW01] §3.1). A rule discretises it by its own
//! quadrature into discrete forces `f_d^±` ([`crate::discrete::rules::Rule::discretize_force`]), which enter the
//! forced discrete Legendre transforms ([conventions](crate#conventions), [MW01] §3.2)
//!
//! ```text
//!     p_k     = −D₁L_d(q_k, q_{k+1}) − f_d⁻(q_k, q_{k+1}),
//!     p_{k+1} =  D₂L_d(q_k, q_{k+1}) + f_d⁺(q_k, q_{k+1}).
//! ```
//!
//! | force | formula | file |
//! |---|---|---|
//! | [`LinearDamping`] | `f = −C v` (Rayleigh, `C` scalar, diagonal or matrix) | `damping.rs` |
//! | [`ConstantForce`] | `f = F` | `driving.rs` |
//! | [`PeriodicForce`] | `f_i = A_i cos(ω_i t + φ_i)` | `driving.rs` |
//! | [`Control`] | `f = u(t)`, a time-dependent input (control) | `control.rs` |
//! | [`ForceSum`] | `f = f₁ + f₂` (also for discrete forces) | `sum.rs` |
//! | [`FromHamiltonian`] | `f_L = f_H ∘ FL`, from a [`HamiltonianForce`] `f_H(t, q, p)` | `hamiltonian.rs` |
//! | [`TwoPoint`] | user-written discrete forces `f_d^±(q₀, q₁)` ([`TwoPointForce`]) | `two_point.rs` |
//!
//! Continuous inputs (`L`, `f_L`) go to [`crate::run::Problem`], which discretises both with the same
//! rule; discrete inputs (a user's `L_d` or `f_d^±`) go straight to an [`crate::integrator::Integrator`]
//! (`Integrator::new(ld).with_force(TwoPoint(my_forces))`), run with [`crate::run::simulate()`].
//!
//! Energy balance: with forces the energy changes by the work done. For the midpoint rule with
//! midpoint forces and `L = ½ vᵀMv − V(q)` (constant `M`) one step satisfies exactly
//! `E_{k+1} − E_k = W_k + [V(q_{k+1}) − V(q_k) − ⟨∇V(q̄), q_{k+1} − q_k⟩]`, where
//! `W_k = ⟨f_d⁻ + f_d⁺, (q_{k+1} − q_k)/h⟩` is the discrete work; the bracket vanishes for
//! quadratic `V` (reference case R12). See [`crate::analysis::diagnostics::EnergyBalance`].
//!
//! [MW01]: crate#references

mod control;
mod damping;
mod driving;
mod hamiltonian;
mod sum;
mod two_point;

pub use control::Control;
pub use damping::LinearDamping;
pub use driving::{ConstantForce, PeriodicForce};
pub use hamiltonian::{FromHamiltonian, HamiltonianForce, hamiltonian_form};
pub use sum::{ForceExt, ForceSum};
pub use two_point::{TwoPoint, TwoPointForce};
