//! External forces: Lagrangian forces `f_L(t, q, v)` and their discrete counterparts `f_d^±`.
//!
//! Concept of the notes (MW01): *forced Lagrangian systems* and *discrete variational mechanics with forces*. The
//! Lagrange–d'Alembert principle `δ∫L dt + ∫⟨f_L, δq⟩ dt = 0` is discretised as
//! `δΣL_d + Σ(⟨f_d⁻, δq_k⟩ + ⟨f_d⁺, δq_{k+1}⟩) = 0`, which gives the forced discrete Legendre
//! transforms ([conventions](crate#conventions))
//!
//! ```text
//!     p_k     = −D₁L_d(q_k, q_{k+1}) − f_d⁻(q_k, q_{k+1}),
//!     p_{k+1} =  D₂L_d(q_k, q_{k+1}) + f_d⁺(q_k, q_{k+1}).
//! ```
//!
//! A [`Force`] is written once over the scalar type; a rule turns it into a
//! [`DiscreteForce`](crate::discrete::DiscreteForce) with its own quadrature (see
//! [`crate::discrete::rules`]). Generalising to control points, a `DiscreteForce` returns the
//! generalised force on every control point of a step, so forces work with Galerkin rules too.
//!
//! Ready-made forces (damping, constant and periodic driving, controls, sums, Hamiltonian forces
//! `f_H(t, q, p)` and user-written discrete forces `f_d^±`) live in [`crate::forces`].

use crate::scalar::Scalar;

/// A Lagrangian force `f_L(t, q, v) ∈ T*Q` (a generalised force, one component per coordinate).
pub trait Force {
    /// Writes `f_L(t, q, v)` into `out` (length n).
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]);
    /// `false` for the no-op force, so the integrator can skip all force work.
    fn is_active(&self) -> bool {
        true
    }
    /// Checks that the force fits a system with `dof` coordinates (called once by
    /// [`crate::run::Problem::integrator`] before any step; the default accepts every `dof`).
    fn validate(&self, _dof: usize) -> Result<(), crate::error::Error> {
        Ok(())
    }
}

/// No external force (the default). Zero-sized; compiles away.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NoForce;

impl Force for NoForce {
    fn force<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], out: &mut [S]) {
        out.iter_mut().for_each(|f| *f = S::from(0.0));
    }
    fn is_active(&self) -> bool {
        false
    }
}

impl<F: Force + ?Sized> Force for &F {
    #[inline(always)]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        (**self).force(t, q, v, out)
    }
    fn is_active(&self) -> bool {
        (**self).is_active()
    }
    fn validate(&self, dof: usize) -> Result<(), crate::error::Error> {
        (**self).validate(dof)
    }
}
