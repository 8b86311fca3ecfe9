//! The continuous system: a Lagrangian `L(t, q, v)` written once, generic over the scalar.
//!
//! Seed: *Lagrangian mechanics* — `L: TQ → ℝ`, the action `∫ L(q, q̇) dt`, Hamilton's principle
//! and its Euler–Lagrange equations `∂L/∂q − d/dt ∂L/∂q̇ = 0` ([MW01] §1.2). Everything the crate
//! needs (momenta, energy, accelerations, discrete Lagrangians and their derivatives) is obtained
//! from this one function by automatic differentiation; see [`crate::mechanics`].
//!
//! [MW01]: J. E. Marsden, M. West, *Discrete mechanics and variational integrators*, Acta Numerica 10 (2001).

use crate::Scalar;

/// A (possibly time-dependent) Lagrangian `L(t, q, v)` on `TQ = ℝⁿ × ℝⁿ`.
///
/// Write it once over [`Scalar`]; f64 evaluation gives values, dual numbers give derivatives.
///
/// ```
/// use marsden::{Lagrangian, Scalar};
///
/// /// Planar pendulum, L = ½ m l² θ̇² + m g l cos θ.
/// struct Pendulum { m: f64, l: f64, g: f64 }
///
/// impl Lagrangian for Pendulum {
///     fn dof(&self) -> usize { 1 }
///     fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
///         v[0] * v[0] * (0.5 * self.m * self.l * self.l) + q[0].cos() * (self.m * self.g * self.l)
///     }
/// }
///
/// let p = Pendulum { m: 1.0, l: 1.0, g: 1.0 };
/// assert_eq!(p.lagrangian(0.0, &[0.0], &[2.0]), 3.0);
/// ```
pub trait Lagrangian {
    /// Number of degrees of freedom `n` (length of `q` and `v`).
    fn dof(&self) -> usize;

    /// `L(t, q, v)`; `q` and `v` have length [`Lagrangian::dof`].
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S;
}

impl<L: Lagrangian + ?Sized> Lagrangian for &L {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        (**self).lagrangian(t, q, v)
    }
}
