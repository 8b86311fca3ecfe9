//! The Hamiltonian side: `H(t, q, p)` written once over the scalar, Hamilton's vector field by
//! AD, symplectic integrators for `H` given directly, and the Legendre correspondence with
//! Lagrangians.
//!
//! Concept of the notes (MW01): *Hamiltonian mechanics* (`X_H = (∂H/∂p, −∂H/∂q)`, `ι_{X_H}Ω = dH`, symplectic flow),
//! *Legendre transforms* (`FL`, `FH = (FL)⁻¹` for hyperregular systems, `E = H ∘ FL`,
//! `J_L = FL*J_H`). The pieces:
//!
//! * [`Hamiltonian`], [`Separable`] (`H = T(p) + V(t, q)`; every `Separable` is a `Hamiltonian`);
//! * [`PhaseJet`] and [`vector_field`]: value, gradient, Hessian and `X_H` by AD;
//! * methods ([`HamiltonianMethod`]) stepped by a [`HamiltonianIntegrator`]:
//!   [`ImplicitMidpoint`] (symplectic, any `H`), [`Splitting`] (Störmer–Verlet and symplectic
//!   Euler as partitioned RK methods for separable `H`), [`ExplicitMidpoint`] (explicit RK2, *not*
//!   symplectic: the comparison map of the certificate);
//! * [`LegendreHamiltonian`] (`H` from `L` by `FH`) and [`HamiltonianLagrangian`] (`L` from `H`
//!   by `FL`), both generic over the scalar so they work with every method here;
//! * Hamiltonians of the catalog systems (`catalog`).

mod catalog;
mod implicit_midpoint;
mod integrator;
mod jet;
mod legendre;
mod rk2;
mod splitting;

pub use implicit_midpoint::ImplicitMidpoint;
pub use integrator::{HamiltonianIntegrator, HamiltonianMethod};
pub use jet::{PhaseJet, vector_field};
pub use legendre::{HamiltonianLagrangian, LegendreHamiltonian};
pub use rk2::ExplicitMidpoint;
pub use splitting::Splitting;

use crate::scalar::Scalar;

/// A (possibly time-dependent) Hamiltonian `H(t, q, p)` on `T*Q = ℝⁿ × ℝⁿ`.
///
/// ```
/// use marsden::{Scalar, hamiltonian::{Hamiltonian, vector_field}};
///
/// /// Pendulum, H = p²/2 − cos q.
/// struct Pendulum;
/// impl Hamiltonian for Pendulum {
///     fn dof(&self) -> usize { 1 }
///     fn hamiltonian<S: Scalar>(&self, _t: S, q: &[S], p: &[S]) -> S {
///         p[0] * p[0] * 0.5 - q[0].cos()
///     }
/// }
/// let (mut dq, mut dp) = ([0.0], [0.0]);
/// vector_field(&Pendulum, 0.0, &[0.5], &[2.0], &mut dq, &mut dp);
/// assert_eq!(dq[0], 2.0);                  // q̇ = ∂H/∂p
/// assert_eq!(dp[0], -(0.5_f64).sin());     // ṗ = −∂H/∂q
/// ```
pub trait Hamiltonian {
    /// Number of degrees of freedom `n` (length of `q` and `p`).
    fn dof(&self) -> usize;

    /// `H(t, q, p)`.
    fn hamiltonian<S: Scalar>(&self, t: S, q: &[S], p: &[S]) -> S;
}

/// A separable Hamiltonian `H = T(p) + V(t, q)` (kinetic plus potential energy), the structure
/// partitioned methods such as Störmer–Verlet exploit ([HLW06] §I.1.4, §II.2).
///
/// Every `Separable` is a [`Hamiltonian`] (blanket implementation).
///
/// [HLW06]: crate#references
pub trait Separable {
    /// Number of degrees of freedom `n`.
    fn dof(&self) -> usize;
    /// Kinetic energy `T(p)`.
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S;
    /// Potential energy `V(t, q)`.
    fn potential<S: Scalar>(&self, t: S, q: &[S]) -> S;
}

impl<T: Separable> Hamiltonian for T {
    fn dof(&self) -> usize {
        Separable::dof(self)
    }
    #[inline]
    fn hamiltonian<S: Scalar>(&self, t: S, q: &[S], p: &[S]) -> S {
        self.kinetic(p) + self.potential(t, q)
    }
}
