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
///
/// Speed: for up to four degrees of freedom the step runs in code compiled for x86-64-v3 when
/// the CPU has it ([`crate::dispatch`]), but only what is inlined into it; marking `lagrangian`
/// `#[inline(always)]`, as the built-in systems do, makes sure yours is (same results either way).
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

    /// `∇V(t, q)` of a separable `L = ½ vᵀ M v − V(t, q)`, written into `grad` (length n);
    /// `scratch` is storage the implementation may use, kept by the caller between calls so
    /// that the step does not allocate. Used only when [`Lagrangian::structure`] is
    /// [`Structure::Separable`].
    ///
    /// Default: AD of `−L(t, q, 0)` ([`crate::potential::gradient_by_ad`]). Override it where AD
    /// is too slow (the N-body problem, [`crate::systems::NBody`]); tests compare the two with
    /// [`crate::potential::gradient_defect`].
    #[inline]
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        let _ = scratch;
        crate::potential::gradient_by_ad(self, t, q, grad);
    }

    /// Half-bandwidth `b` of `∇²V` (`∂²V/∂qᵢ∂qⱼ = 0` for `|i − j| > b`), if the potential is a
    /// sum of local terms; `None` (the default): dense.
    fn potential_bandwidth(&self) -> Option<usize> {
        None
    }

    /// `∇²V(t, q)` of a separable Lagrangian, written into `hess` (shaped n × n with the
    /// half-bandwidth of [`Lagrangian::potential_bandwidth`]; entries start at zero).
    ///
    /// Default: the dense AD Hessian of `−L(t, q, 0)` ([`crate::potential::hessian_by_ad`]).
    /// Override it together with `potential_bandwidth` for large systems (a chain:
    /// [`crate::systems::Chain`]), so the Newton Jacobian `M/h + (h/4)∇²V` of the midpoint
    /// rule is assembled and factored in `O(n)`.
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut crate::banded::Banded) {
        crate::potential::hessian_by_ad(self, t, q, hess);
    }
}

/// What is known about the form of a Lagrangian.
#[derive(Debug, Clone, PartialEq)]
pub enum Structure {
    /// No assumption.
    General,
    /// `L = ½ vᵀ M v − V(t, q)` with a constant, symmetric positive definite mass matrix `M`:
    /// the trapezoid rule is then explicit (velocity Störmer–Verlet, [`crate::explicit`]) and
    /// the midpoint rule a Newton solve with Jacobian `M/h + (h/4)∇²V` ([`crate::separable`]);
    /// both use the potential's derivatives ([`crate::potential`]).
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
    #[inline(always)]
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        (**self).potential_gradient(t, q, grad, scratch)
    }
    fn potential_bandwidth(&self) -> Option<usize> {
        (**self).potential_bandwidth()
    }
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut crate::banded::Banded) {
        (**self).potential_hessian(t, q, hess)
    }
}
