//! The continuous system: a Lagrangian `L(t, q, v)` written once, generic over the scalar.
//!
//! Concept of the notes (MW01): *Lagrangian mechanics* — `L: TQ → ℝ`, the action `∫ L(q, q̇) dt`, Hamilton's principle
//! and its Euler–Lagrange equations `∂L/∂q − d/dt ∂L/∂q̇ = 0` ([MW01] §1.2). Everything the crate
//! needs (momenta, energy, accelerations, discrete Lagrangians and their derivatives) is obtained
//! from this one function by automatic differentiation; see [`crate::mechanics::jet`].
//!
//! [MW01]: crate#references

use super::kernel::VerletKernel;
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::banded::Banded;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

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
/// the CPU has it (`crate::integrator::small::dispatch`), but only what is inlined into it; marking `lagrangian`
/// `#[inline(always)]`, as the built-in systems do, makes sure yours is (same results either way).
pub trait Lagrangian {
    /// The number of degrees of freedom, when the type fixes it (the catalog systems): the
    /// integrator then compiles its statically sized step kernels for that size only. A wrong
    /// value costs speed, never correctness (the general path takes the steps). Default: `None`.
    const FIXED_DOF: Option<usize> = None;

    /// Number of degrees of freedom `n` (length of `q` and `v`).
    fn dof(&self) -> usize;

    /// `L(t, q, v)`; `q` and `v` have length [`Lagrangian::dof`].
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S;

    /// Structure the integrators may exploit (default: none). Declaring
    /// [`Structure::Separable`] asserts `L = ½ vᵀ M v − V(t, q)` with a constant `M`; it is
    /// checked by AD at the initial state of a [`crate::run::Problem`]
    /// ([`crate::mechanics::check_structure`]).
    fn structure(&self) -> Structure {
        Structure::General
    }

    /// `∇V(t, q)` of a separable `L = ½ vᵀ M v − V(t, q)`, written into `grad` (length n);
    /// `scratch` is storage the implementation may use, kept by the caller between calls so
    /// that the step does not allocate. Used only when [`Lagrangian::structure`] is
    /// [`Structure::Separable`].
    ///
    /// Default: AD of `−L(t, q, 0)` ([`gradient_by_ad`]). Override it where AD
    /// is too slow (the N-body problem, [`crate::systems::NBody`]); tests compare the two with
    /// [`crate::mechanics::potential::gradient_defect`].
    #[inline]
    fn potential_gradient(&self, t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        let _ = scratch;
        gradient_by_ad(self, t, q, grad);
    }

    /// Half-bandwidth `b` of `∇²V` (`∂²V/∂qᵢ∂qⱼ = 0` for `|i − j| > b`), if the potential is a
    /// sum of local terms; `None` (the default): dense.
    fn potential_bandwidth(&self) -> Option<usize> {
        None
    }

    /// `∇²V(t, q)` of a separable Lagrangian, written into `hess` (shaped n × n with the
    /// half-bandwidth of [`Lagrangian::potential_bandwidth`]; entries start at zero).
    ///
    /// Default: the dense AD Hessian of `−L(t, q, 0)` ([`hessian_by_ad`]).
    /// Override it together with `potential_bandwidth` for large systems (a chain:
    /// [`crate::systems::Chain`]), so the Newton Jacobian `M/h + (h/4)∇²V` of the midpoint
    /// rule is assembled and factored in `O(n)`.
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        hessian_by_ad(self, t, q, hess);
    }

    /// `∇²V(t, q)` of a separable Lagrangian as its upper triangle row by row
    /// (`∂²V/∂qᵢ∂qⱼ` for `i ≤ j`, `n(n + 1)/2` values) in `packed`, when the Lagrangian has it
    /// in that form without going through the band storage of
    /// [`Lagrangian::potential_hessian`] (compiled code that writes exactly these values);
    /// returns whether it did. The small separable Newton steps (`n ≤ 4`) ask this first and
    /// take `potential_hessian` when it returns `false`; both must give the same values.
    /// Default: `false`, nothing written.
    #[inline(always)]
    fn potential_hessian_packed(&self, t: f64, q: &[f64], packed: &mut [f64]) -> bool {
        let _ = (t, q, packed);
        false
    }

    /// The Lagrangian's own explicit run ([`crate::mechanics::kernel`]), if it has one: for a
    /// separable `L` with a diagonal mass, the trapezoid rule's runs then take their steps in
    /// it instead of the generic loop. It must give the generic loop's numbers bit for bit.
    /// Default: `None`.
    fn verlet_kernel(&self) -> Option<&dyn VerletKernel> {
        None
    }

    /// A starting guess for the inverse Legendre transform `v = FL⁻¹(t, q, p)` (written into
    /// `v`), where the Lagrangian knows a better one than `v = 0`: a Lagrangian built from a
    /// Hamiltonian gives `v = ∂H/∂p`, the exact answer, since `∂²L/∂v²` may be singular at
    /// `v = 0` where it is not at the state itself (`H = p⁴/4`). Default: leaves `v` as it is.
    fn velocity_guess(&self, t: f64, q: &[f64], p: &[f64], v: &mut [f64]) {
        let _ = (t, q, p, v);
    }
}

/// What is known about the form of a Lagrangian.
#[derive(Debug, Clone, PartialEq)]
pub enum Structure {
    /// No assumption.
    General,
    /// `L = ½ vᵀ M v − V(t, q)` with a constant, symmetric positive definite mass matrix `M`:
    /// the trapezoid rule is then explicit (velocity Störmer–Verlet, [`crate::separable::explicit`]) and
    /// the midpoint rule a Newton solve with Jacobian `M/h + (h/4)∇²V` ([`crate::separable::alpha`]);
    /// both use the potential's derivatives ([`crate::mechanics::potential`]).
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
    const FIXED_DOF: Option<usize> = L::FIXED_DOF;
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
    fn potential_hessian(&self, t: f64, q: &[f64], hess: &mut Banded) {
        (**self).potential_hessian(t, q, hess)
    }
    #[inline(always)]
    fn potential_hessian_packed(&self, t: f64, q: &[f64], packed: &mut [f64]) -> bool {
        (**self).potential_hessian_packed(t, q, packed)
    }
    fn verlet_kernel(&self) -> Option<&dyn VerletKernel> {
        (**self).verlet_kernel()
    }
    fn velocity_guess(&self, t: f64, q: &[f64], p: &[f64], v: &mut [f64]) {
        (**self).velocity_guess(t, q, p, v)
    }
}

/// `k · n + plus` when the type fixes `n` (the size of an AD evaluation of `L`, for
/// [`MultiFunction::MAX_INPUTS`]).
pub(crate) const fn times_dof(dof: Option<usize>, k: usize, plus: usize) -> Option<usize> {
    match dof {
        Some(n) => Some(k * n + plus),
        None => None,
    }
}

// ---- The potential of a separable Lagrangian by AD: the defaults of the trait above ----

/// `q ↦ −L(t, q, 0)`: the potential `V(t, q)` of a separable Lagrangian.
pub(crate) struct PotentialOf<'a, L: ?Sized> {
    /// The Lagrangian.
    pub lagrangian: &'a L,
    /// Time.
    pub t: f64,
}

impl<L: Lagrangian + ?Sized> MultiFunction for PotentialOf<'_, L> {
    const MAX_INPUTS: Option<usize> = times_dof(L::FIXED_DOF, 1, 0);
    fn inputs(&self) -> usize {
        self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        let mut v = Buffer::<S, NODE>::empty();
        let v = v.filled(q.len(), zero);
        out[0] = -self.lagrangian.lagrangian(S::from(self.t), q, v);
    }
}

/// `∇V(t, q)` by AD of `−L(t, q, 0)` (the default of
/// [`crate::mechanics::Lagrangian::potential_gradient`]); `grad` has length n.
pub fn gradient_by_ad<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64], grad: &mut [f64]) {
    let mut value = [0.0];
    ad::jacobian(
        &PotentialOf { lagrangian: l, t },
        q,
        0..q.len(),
        &mut value,
        grad,
    );
}

/// `V(t, q) = −L(t, q, 0)` at `f64` (a constant offset of `V` is irrelevant to the dynamics).
pub fn potential<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64]) -> f64 {
    let mut value = [0.0];
    ad::eval_f64(&PotentialOf { lagrangian: l, t }, q, &mut value);
    value[0]
}

/// `∇²V(t, q)` by AD of `−L(t, q, 0)`, dense, written into the band of `hess` (the default of
/// [`crate::mechanics::Lagrangian::potential_hessian`]; entries outside the band are dropped, so give
/// `hess` the full bandwidth `n − 1` unless the potential is known to be banded).
pub fn hessian_by_ad<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64], hess: &mut Banded) {
    let n = q.len();
    let mut parts = HessianParts::default();
    ad::partial_hessian(&PotentialOf { lagrangian: l, t }, q, 0..n, 0..n, &mut parts);
    hess.fill_zero();
    for i in 0..n {
        for j in hess.columns(i) {
            hess.set(i, j, parts.hess[i * n + j]);
        }
    }
}
