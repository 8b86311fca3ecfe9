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

    /// Structure the integrators may exploit (default: none). Declaring
    /// [`Structure::Separable`] asserts `L = ½ vᵀ M v − V(t, q)` with a constant `M`; it is
    /// checked by AD at the initial state of a [`crate::Problem`]
    /// ([`crate::mechanics::check_structure`]).
    fn structure(&self) -> Structure {
        Structure::General
    }
}

/// What is known about the form of a Lagrangian.
#[derive(Debug, Clone, PartialEq)]
pub enum Structure {
    /// No assumption.
    General,
    /// `L = ½ vᵀ M v − V(t, q)` with a constant, symmetric positive definite mass matrix `M`:
    /// the trapezoid rule is then explicit (velocity Störmer–Verlet, [`crate::explicit`]).
    Separable {
        /// The constant mass matrix.
        mass: MassMatrix,
    },
}

/// A constant mass matrix.
#[derive(Debug, Clone, PartialEq)]
pub enum MassMatrix {
    /// `diag(m₁, …, m_n)`.
    Diagonal(Vec<f64>),
    /// A dense symmetric matrix, row-major n × n.
    Dense(Vec<f64>),
}

impl MassMatrix {
    /// The matrix as a dense row-major array.
    pub fn to_dense(&self) -> Vec<f64> {
        match self {
            Self::Dense(m) => m.clone(),
            Self::Diagonal(d) => {
                let n = d.len();
                let mut m = vec![0.0; n * n];
                d.iter().enumerate().for_each(|(i, di)| m[i * n + i] = *di);
                m
            }
        }
    }
}

impl<L: Lagrangian + ?Sized> Lagrangian for &L {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        (**self).lagrangian(t, q, v)
    }
    fn structure(&self) -> Structure {
        (**self).structure()
    }
}
