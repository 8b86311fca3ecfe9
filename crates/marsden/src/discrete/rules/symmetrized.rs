//! The symmetrised generalised midpoint family `L_d^{sym,α} = ½(L_d^α + L_d^{1−α})`.
//!
//! [MW01] §2.2.1 (eq. 2.2.4): symmetric, hence second order for every α; α = 0 is the trapezoid
//! rule `(h/2)[L(q₀, v) + L(q₁, v)]`, which for mechanical Lagrangians is velocity Störmer–Verlet
//! (reference cases R2, R5). Discrete forces: the average of the α and 1−α quadratures (for
//! α = 0, `(h/2) f` at each end).

use super::{Rule, at_node, with_displacement};
use crate::discrete::{DiscreteForce, DiscreteLagrangian};
use crate::mechanics::kernel::RunGrid;
use crate::mechanics::structure::InverseMass;
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;
use crate::separable::explicit::{Verlet, run_by_steps, velocity_verlet, velocity_verlet_run};
use crate::separable::jacobian::step_jacobian;
use crate::separable::{
    ExplicitRun, ExplicitStep, ExplicitWorkspace, JacobianWorkspace, SeparableJacobian,
};

/// The trapezoid rule (symmetrised α = 0): velocity Störmer–Verlet for mechanical systems.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Trapezoid;

/// The symmetrised generalised midpoint rule with parameter α ∈ [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SymmetrizedMidpoint {
    /// Nodes at α and 1 − α.
    pub alpha: f64,
}

impl SymmetrizedMidpoint {
    /// The rule with parameter `alpha`, checked to lie in `[0, 1]`.
    pub fn new(alpha: f64) -> Result<Self, crate::error::Error> {
        super::check_alpha(alpha).map(|alpha| Self { alpha })
    }
}

/// `L_d^{sym,α}` of a Lagrangian (built by [`Trapezoid`] and [`SymmetrizedMidpoint`]).
#[derive(Debug, Clone)]
pub struct SymmetrizedLd<L> {
    /// The continuous Lagrangian.
    pub lagrangian: L,
    /// Nodes at α and 1 − α.
    pub alpha: f64,
    /// `M⁻¹` when α = 0 and `L` is separable: the step is then explicit Störmer–Verlet.
    inverse_mass: Option<InverseMass>,
}

impl<L: Lagrangian> SymmetrizedLd<L> {
    /// `L_d^{sym,α}` of `lagrangian`; notes whether the explicit Verlet form applies.
    pub fn new(lagrangian: L, alpha: f64) -> Self {
        let inverse_mass = if alpha == 0.0 {
            InverseMass::of(&lagrangian.structure())
        } else {
            None
        };
        Self {
            lagrangian,
            alpha,
            inverse_mass,
        }
    }
}

impl<L: Lagrangian> ExplicitStep for SymmetrizedLd<L> {
    fn explicit_step(
        &self,
        t: f64,
        h: f64,
        q: &[f64],
        p: &mut [f64],
        delta: &mut [f64],
        ws: &mut ExplicitWorkspace,
    ) -> usize {
        match &self.inverse_mass {
            Some(inverse_mass) => {
                let verlet = Verlet {
                    lagrangian: &self.lagrangian,
                    inverse_mass,
                };
                velocity_verlet(verlet, t, h, q, p, delta, ws)
            }
            None => 0,
        }
    }

    fn explicit_run(
        &self,
        grid: RunGrid,
        q: &mut [f64],
        p: &mut [f64],
        ws: &mut ExplicitWorkspace,
    ) -> ExplicitRun {
        let Some(inverse_mass) = &self.inverse_mass else {
            return ExplicitRun::default();
        };
        let verlet = Verlet {
            lagrangian: &self.lagrangian,
            inverse_mass,
        };
        velocity_verlet_run(verlet, grid, &mut *q, &mut *p, ws)
            .unwrap_or_else(|| run_by_steps(self, grid, q, p, ws))
    }
}

impl<L: Lagrangian> DiscreteLagrangian for SymmetrizedLd<L> {
    const FIXED_DOF: Option<usize> = L::FIXED_DOF;
    fn dof(&self) -> usize {
        self.lagrangian.dof()
    }
    #[inline]
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        with_displacement(q0, q1, |d| self.discrete_lagrangian_offset(t0, h, q0, d))
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        self.inverse_mass
            .as_ref()
            .map(|_| self as &dyn ExplicitStep)
    }
    fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
        Some(self)
    }
    #[inline]
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        let mut sum = S::from(0.0);
        for c in [self.alpha, 1.0 - self.alpha] {
            let t = S::from(t0 + c * h);
            sum += at_node(c, h, q0, delta, |q, v| self.lagrangian.lagrangian(t, q, v));
        }
        sum * (0.5 * h)
    }
}

/// On a separable `L` the symmetrised α step's Jacobian needs `∇²V` at `q_α` and `q_{1−α}`
/// (weights ½; for the trapezoid rule the ends, [`crate::separable::jacobian`]).
impl<L: Lagrangian> SeparableJacobian for SymmetrizedLd<L> {
    fn step_jacobian(
        &self,
        grid: (f64, f64),
        start: (&[f64], &[f64]),
        jac: &mut [f64],
        ws: &mut JacobianWorkspace,
    ) -> Option<Result<(), f64>> {
        let nodes = [(self.alpha, 0.5), (1.0 - self.alpha, 0.5)];
        step_jacobian(&self.lagrangian, &nodes, grid, start, jac, ws)
    }
}

/// Discrete forces of the symmetrised α rule.
#[derive(Debug, Clone)]
pub struct SymmetrizedForce<F> {
    /// The continuous force.
    pub force: F,
    /// Nodes at α and 1 − α.
    pub alpha: f64,
    /// Degrees of freedom.
    pub dof: usize,
}

impl<F: Force> DiscreteForce for SymmetrizedForce<F> {
    #[inline]
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        let n = self.dof;
        let zero = S::from(0.0);
        out[..2 * n].iter_mut().for_each(|o| *o = zero);
        for c in [self.alpha, 1.0 - self.alpha] {
            let t = S::from(t0 + c * h);
            let (w0, w1) = (0.5 * h * (1.0 - c), 0.5 * h * c);
            at_node(c, h, q0, offsets, |q, v| {
                let mut f = Buffer::<S, NODE>::empty();
                let f = f.filled(n, zero);
                self.force.force(t, q, v, f);
                for i in 0..n {
                    out[i] += f[i] * w0;
                    out[n + i] += f[i] * w1;
                }
            });
        }
    }
    fn is_active(&self) -> bool {
        self.force.is_active()
    }
}

/// The named rule is the α = 0.0 member of its family.
impl Rule for Trapezoid {
    type Discrete<L: Lagrangian> = SymmetrizedLd<L>;
    type DiscreteForce<F: Force> = SymmetrizedForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> SymmetrizedLd<L> {
        SymmetrizedMidpoint { alpha: 0.0 }.discretize(lagrangian)
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> SymmetrizedForce<F> {
        SymmetrizedMidpoint { alpha: 0.0 }.discretize_force(force, dof)
    }
    fn name(&self) -> String {
        "trapezoid".into()
    }
    fn order(&self) -> u32 {
        2
    }
}

impl Rule for SymmetrizedMidpoint {
    type Discrete<L: Lagrangian> = SymmetrizedLd<L>;
    type DiscreteForce<F: Force> = SymmetrizedForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> SymmetrizedLd<L> {
        SymmetrizedLd::new(lagrangian, self.alpha)
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> SymmetrizedForce<F> {
        SymmetrizedForce {
            force,
            alpha: self.alpha,
            dof,
        }
    }
    fn name(&self) -> String {
        format!("symmetrized-{}", self.alpha)
    }
    fn order(&self) -> u32 {
        2
    }
}
