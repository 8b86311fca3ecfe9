//! The generalised midpoint family `L_d^α = h L(t₀ + αh, (1−α)q₀ + αq₁, (q₁−q₀)/h)`.
//!
//! [MW01] §2.2.1 (eq. 2.2.3). Order 1 for α ≠ ½ and 2 for the midpoint rule α = ½ (reference
//! case R5). Discrete forces by the same one-point quadrature: with `q_α` varied as
//! `(1−α)δq₀ + αδq₁`, `f_d⁻ = h(1−α) f(q_α, v)` and `f_d⁺ = hα f(q_α, v)`.

use super::{Rule, at_node, with_displacement};
use crate::discrete::{DiscreteForce, DiscreteLagrangian};
use crate::mechanics::{Force, Lagrangian, MassMatrix, Structure};
use crate::numerics::newton::{NewtonFailure, NewtonOptions, NewtonReport};
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;
use crate::separable::alpha::solve_alpha;
use crate::separable::jacobian::step_jacobian;
use crate::separable::{
    Frame, JacobianWorkspace, SeparableJacobian, SeparableStep, SeparableWorkspace,
};

/// The midpoint rule (α = ½): second order, symmetric, the implicit midpoint method for
/// mechanical Lagrangians.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Midpoint;

/// The generalised midpoint rule with parameter α ∈ [0, 1] (α = 0: symplectic Euler).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralizedMidpoint {
    /// Where in the step `L` is sampled.
    pub alpha: f64,
}

impl GeneralizedMidpoint {
    /// The rule with parameter `alpha`, checked to lie in `[0, 1]`.
    pub fn new(alpha: f64) -> Result<Self, crate::error::Error> {
        super::check_alpha(alpha).map(|alpha| Self { alpha })
    }
}

/// `L_d^α` of a Lagrangian (built by [`Midpoint`] and [`GeneralizedMidpoint`]).
#[derive(Debug, Clone)]
pub struct AlphaLd<L> {
    /// The continuous Lagrangian.
    pub lagrangian: L,
    /// Quadrature node in `[0, 1]`.
    pub alpha: f64,
}

impl<L: Lagrangian> DiscreteLagrangian for AlphaLd<L> {
    const FIXED_DOF: Option<usize> = L::FIXED_DOF;
    fn dof(&self) -> usize {
        self.lagrangian.dof()
    }
    #[inline]
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        with_displacement(q0, q1, |d| self.discrete_lagrangian_offset(t0, h, q0, d))
    }
    #[inline(always)]
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        let t = S::from(t0 + self.alpha * h);
        at_node(
            self.alpha,
            h,
            q0,
            delta,
            #[inline(always)]
            |q, v| self.lagrangian.lagrangian(t, q, v),
        ) * h
    }
    #[inline]
    fn separable(&self) -> Option<&dyn SeparableStep> {
        Some(self)
    }
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        Some(self)
    }
}

/// On a separable `L` the α step's Jacobian needs `∇²V` at `q_α` alone (one node, weight 1;
/// [`crate::separable::jacobian`]).
impl<L: Lagrangian> SeparableJacobian for AlphaLd<L> {
    fn step_jacobian(
        &self,
        grid: (f64, f64),
        start: (&[f64], &[f64]),
        jac: &mut [f64],
        ws: &mut JacobianWorkspace,
    ) -> Option<Result<(), f64>> {
        step_jacobian(&self.lagrangian, &[(self.alpha, 1.0)], grid, start, jac, ws)
    }
}

/// On a separable `L` the α step is a Newton solve with Jacobian `M/h + hα(1−α)∇²V`
/// ([`crate::separable::alpha`]).
impl<L: Lagrangian> SeparableStep for AlphaLd<L> {
    fn mass(&self) -> Option<MassMatrix> {
        let Structure::Separable { mass } = self.lagrangian.structure() else {
            return None;
        };
        Some(mass)
    }
    fn solve_separable(
        &self,
        frame: Frame<'_>,
        z: &mut [f64],
        p_next: &mut [f64],
        options: &NewtonOptions,
        ws: &mut SeparableWorkspace,
    ) -> Result<NewtonReport, NewtonFailure> {
        solve_alpha(&self.lagrangian, self.alpha, frame, z, p_next, options, ws)
    }
}

/// Discrete forces of the α rule: `(h(1−α) f, hα f)` at `q_α`.
#[derive(Debug, Clone)]
pub struct AlphaForce<F> {
    /// The continuous force.
    pub force: F,
    /// Quadrature node in `[0, 1]`.
    pub alpha: f64,
    /// Degrees of freedom.
    pub dof: usize,
}

impl<F: Force> DiscreteForce for AlphaForce<F> {
    #[inline(always)]
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        let n = self.dof;
        let t = S::from(t0 + self.alpha * h);
        let (w0, w1) = (h * (1.0 - self.alpha), h * self.alpha);
        at_node(
            self.alpha,
            h,
            q0,
            offsets,
            #[inline(always)]
            |q, v| {
                let zero = S::from(0.0);
                let mut f = Buffer::<S, NODE>::empty();
                let f = f.filled(n, zero);
                self.force.force(t, q, v, f);
                for i in 0..n {
                    out[i] = f[i] * w0;
                    out[n + i] = f[i] * w1;
                }
            },
        )
    }
    fn is_active(&self) -> bool {
        self.force.is_active()
    }
}

/// The named rule is the α = 0.5 member of its family.
impl Rule for Midpoint {
    type Discrete<L: Lagrangian> = AlphaLd<L>;
    type DiscreteForce<F: Force> = AlphaForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> AlphaLd<L> {
        GeneralizedMidpoint { alpha: 0.5 }.discretize(lagrangian)
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> AlphaForce<F> {
        GeneralizedMidpoint { alpha: 0.5 }.discretize_force(force, dof)
    }
    fn name(&self) -> String {
        "midpoint".into()
    }
    fn order(&self) -> u32 {
        2
    }
}

impl Rule for GeneralizedMidpoint {
    type Discrete<L: Lagrangian> = AlphaLd<L>;
    type DiscreteForce<F: Force> = AlphaForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> AlphaLd<L> {
        AlphaLd {
            lagrangian,
            alpha: self.alpha,
        }
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> AlphaForce<F> {
        AlphaForce {
            force,
            alpha: self.alpha,
            dof,
        }
    }
    fn name(&self) -> String {
        format!("alpha-{}", self.alpha)
    }
    fn order(&self) -> u32 {
        if self.alpha == 0.5 { 2 } else { 1 }
    }
}
