//! A method chosen at run time as one rule type: [`BaseMethod`] and [`Method`] implement
//! [`Rule`] themselves.
//!
//! [`Method::dispatch`] gives a generic computation the concrete rule, so the integrator is
//! compiled once per rule type (six discrete Lagrangian types: α, symmetrised, Galerkin, and a
//! composition of each). A program that takes its method from a file compiles every one of them
//! for every system it can run, and every computation beside the run (a certificate, a tangent
//! run, an order study) again. Used as a rule, a [`Method`] discretises a Lagrangian into
//! [`ChosenLd`], an enum over the concrete discrete Lagrangians that forwards each evaluation to
//! the one chosen: the integrator is compiled once per system, while each rule's quadrature is
//! still compiled (and inlined) as before.
//!
//! The arithmetic is that of the concrete rule, so a run with a [`Method`] gives the same
//! numbers, bit for bit, as the run with the rule [`Method::dispatch`] passes; the cost is one
//! predictable branch per evaluation of the action, and what the optimiser no longer sees across
//! it (BENCHMARKS.md counts the instructions per step). The forwarding methods are always inlined:
//! the small Newton kernels run in x86-64-v3 code only for what is inlined into them, and a
//! rule evaluated out of line would run in baseline code. Explicit and separable steps are reached
//! through the same trait objects ([`DiscreteAction::explicit`], [`DiscreteAction::separable`]).
//! The compile-time sizes of the concrete rules ([`DiscreteAction::FIXED_STAGES`]) are not
//! known for a chosen rule; they only prune code, the sizes taken at run time are the same.

use super::composition::{ComposedForce, ComposedLd, Composition};
use super::galerkin::{GalerkinForce, GalerkinLd};
use super::method::{BaseMethod, Method};
use super::{
    AlphaForce, AlphaLd, GeneralizedMidpoint, Midpoint, Rule, SymmetrizedForce, SymmetrizedLd,
    SymmetrizedMidpoint, Trapezoid,
};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::newton::{NewtonFailure, NewtonOptions, NewtonReport};
use crate::scalar::Scalar;
use crate::separable::{ExplicitStep, Frame, SeparableJacobian, SeparableStep, SeparableWorkspace};

/// The discrete Lagrangian of a [`BaseMethod`]: midpoint and α-rules share [`AlphaLd`],
/// trapezoid and the symmetrised rules [`SymmetrizedLd`].
#[derive(Debug, Clone)]
pub enum BaseLd<L> {
    /// Midpoint, `alpha-<a>`.
    Alpha(AlphaLd<L>),
    /// Trapezoid, `symmetrized-<a>`.
    Symmetrized(SymmetrizedLd<L>),
    /// `gauss-<s>`, `lobatto-<s>`, `galerkin-…`.
    Galerkin(GalerkinLd<L>),
}

/// The discrete forces of a [`BaseMethod`].
#[derive(Debug, Clone)]
pub enum BaseForce<F> {
    /// Midpoint, `alpha-<a>`.
    Alpha(AlphaForce<F>),
    /// Trapezoid, `symmetrized-<a>`.
    Symmetrized(SymmetrizedForce<F>),
    /// Galerkin rules.
    Galerkin(GalerkinForce<F>),
}

/// The discrete Lagrangian of a [`Method`]: a base rule or a composition of one.
#[derive(Debug, Clone)]
pub enum ChosenLd<L> {
    /// A one-step rule.
    Single(BaseLd<L>),
    /// A composition of a one-step rule.
    Composed(ComposedLd<BaseLd<L>>),
}

/// The discrete forces of a [`Method`].
#[derive(Debug, Clone)]
pub enum ChosenForce<F> {
    /// A one-step rule.
    Single(BaseForce<F>),
    /// A composition of a one-step rule.
    Composed(ComposedForce<BaseForce<F>>),
}

/// Calls `$body` with the concrete value `$x` of whichever variant `$value` holds.
macro_rules! each {
    ($value:expr, $x:ident => $body:expr, $($variant:path),+) => {
        match $value {
            $($variant($x) => $body,)+
        }
    };
}

impl Rule for BaseMethod {
    type Discrete<L: Lagrangian> = BaseLd<L>;
    type DiscreteForce<F: Force> = BaseForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> BaseLd<L> {
        match self {
            Self::Midpoint => BaseLd::Alpha(Midpoint.discretize(lagrangian)),
            Self::Alpha(alpha) => {
                BaseLd::Alpha(GeneralizedMidpoint { alpha: *alpha }.discretize(lagrangian))
            }
            Self::Trapezoid => BaseLd::Symmetrized(Trapezoid.discretize(lagrangian)),
            Self::Symmetrized(alpha) => {
                BaseLd::Symmetrized(SymmetrizedMidpoint { alpha: *alpha }.discretize(lagrangian))
            }
            Self::Galerkin(g) => BaseLd::Galerkin(g.discretize(lagrangian)),
        }
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> BaseForce<F> {
        match self {
            Self::Midpoint => BaseForce::Alpha(Midpoint.discretize_force(force, dof)),
            Self::Alpha(alpha) => {
                BaseForce::Alpha(GeneralizedMidpoint { alpha: *alpha }.discretize_force(force, dof))
            }
            Self::Trapezoid => BaseForce::Symmetrized(Trapezoid.discretize_force(force, dof)),
            Self::Symmetrized(alpha) => BaseForce::Symmetrized(
                SymmetrizedMidpoint { alpha: *alpha }.discretize_force(force, dof),
            ),
            Self::Galerkin(g) => BaseForce::Galerkin(g.discretize_force(force, dof)),
        }
    }
    fn name(&self) -> String {
        BaseMethod::name(self)
    }
    fn order(&self) -> u32 {
        Method::Single(self.clone()).order()
    }
}

impl Rule for Method {
    type Discrete<L: Lagrangian> = ChosenLd<L>;
    type DiscreteForce<F: Force> = ChosenForce<F>;
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> ChosenLd<L> {
        match self {
            Self::Single(base) => ChosenLd::Single(base.discretize(lagrangian)),
            Self::Composed(scheme, base) => {
                ChosenLd::Composed(Composition::new(base.clone(), *scheme).discretize(lagrangian))
            }
        }
    }
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> ChosenForce<F> {
        match self {
            Self::Single(base) => ChosenForce::Single(base.discretize_force(force, dof)),
            Self::Composed(scheme, base) => ChosenForce::Composed(
                Composition::new(base.clone(), *scheme).discretize_force(force, dof),
            ),
        }
    }
    fn name(&self) -> String {
        Method::name(self)
    }
    fn order(&self) -> u32 {
        Method::order(self)
    }
}

/// Forwards every method of [`DiscreteAction`] to the chosen variant.
macro_rules! forward_action {
    ($ty:ident, $($variant:path),+) => {
        impl<L: Lagrangian> DiscreteAction for $ty<L> {
            const FIXED_DOF: Option<usize> = L::FIXED_DOF;
            fn dof(&self) -> usize {
                each!(self, x => x.dof(), $($variant),+)
            }
            fn internal_stages(&self) -> usize {
                each!(self, x => x.internal_stages(), $($variant),+)
            }
            #[inline(always)]
            fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S {
                each!(self, x => x.action(t0, h, q0, offsets), $($variant),+)
            }
            fn explicit(&self) -> Option<&dyn ExplicitStep> {
                each!(self, x => x.explicit(), $($variant),+)
            }
            #[inline]
            fn separable(&self) -> Option<&dyn SeparableStep> {
                each!(self, x => x.separable(), $($variant),+)
            }
            #[inline]
            fn solve_separable_step(
                &self,
                frame: Frame<'_>,
                z: &mut [f64],
                p_next: &mut [f64],
                options: &NewtonOptions,
                ws: &mut SeparableWorkspace,
            ) -> Option<Result<NewtonReport, NewtonFailure>> {
                each!(self, x => x.solve_separable_step(frame, z, p_next, options, ws), $($variant),+)
            }
            fn separable_jacobian(&self) -> Option<&dyn SeparableJacobian> {
                each!(self, x => x.separable_jacobian(), $($variant),+)
            }
            fn constrained_stages(&self) -> Result<usize, String> {
                each!(self, x => x.constrained_stages(), $($variant),+)
            }
            #[inline(always)]
            fn stage_point<S: Scalar>(&self, i: usize, q0: &[S], offsets: &[S], out: &mut [S]) {
                each!(self, x => x.stage_point(i, q0, offsets, out), $($variant),+)
            }
            fn end_weight(&self) -> f64 {
                each!(self, x => x.end_weight(), $($variant),+)
            }
        }
    };
}

/// Forwards [`DiscreteForce`] to the chosen variant.
macro_rules! forward_force {
    ($ty:ident, $($variant:path),+) => {
        impl<F: Force> DiscreteForce for $ty<F> {
            #[inline(always)]
            fn discrete_force<S: Scalar>(
                &self,
                t0: f64,
                h: f64,
                q0: &[S],
                offsets: &[S],
                out: &mut [S],
            ) {
                each!(self, x => x.discrete_force(t0, h, q0, offsets, out), $($variant),+)
            }
            fn is_active(&self) -> bool {
                each!(self, x => x.is_active(), $($variant),+)
            }
        }
    };
}

forward_action!(BaseLd, BaseLd::Alpha, BaseLd::Symmetrized, BaseLd::Galerkin);
forward_action!(ChosenLd, ChosenLd::Single, ChosenLd::Composed);
forward_force!(
    BaseForce,
    BaseForce::Alpha,
    BaseForce::Symmetrized,
    BaseForce::Galerkin
);
forward_force!(ChosenForce, ChosenForce::Single, ChosenForce::Composed);
