//! Discrete mechanics: discrete Lagrangians, their derivatives and discrete Legendre transforms.
//!
//! Seed: *discrete variational mechanics*. A discrete Lagrangian `L_d(q₀, q₁, h) ≈ ∫₀ʰ L dt`
//! replaces the action of one step; the discrete action `Σ L_d(q_k, q_{k+1})` is made
//! stationary, which gives the discrete Euler–Lagrange (DEL) equations
//!
//! ```text
//!     D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0,
//! ```
//!
//! and the discrete Legendre transforms ([MW01] §1.3, conventions in DESIGN.md §3)
//!
//! ```text
//!     F⁻L_d(q₀, q₁) = (q₀, −D₁L_d(q₀, q₁)),     F⁺L_d(q₀, q₁) = (q₁, D₂L_d(q₀, q₁)).
//! ```
//!
//! Two traits: [`DiscreteLagrangian`] is the two-point `L_d(q₀, q₁)` a user may supply directly;
//! [`DiscreteAction`] is what the integrator steps: `L_d` written over the control points
//! `Q₀ = q_k, Q₁, …, Q_s = q_{k+1}` of one step, so that Galerkin rules can expose internal stages
//! as unknowns of the same Newton solve. Every `DiscreteLagrangian` is a `DiscreteAction` with no
//! internal stages.
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).

use crate::Scalar;
use crate::ad::{self, MultiFunction};
use crate::explicit::ExplicitStep;
use crate::scratch::{NODE, with_buffer};
use crate::separable::SeparableStep;

/// A two-point discrete Lagrangian `L_d(t₀, h, q₀, q₁)`.
///
/// ```
/// use marsden::{DiscreteLagrangian, Scalar};
///
/// /// Midpoint discrete Lagrangian of the unit harmonic oscillator, written by hand.
/// struct OscillatorLd;
/// impl DiscreteLagrangian for OscillatorLd {
///     fn dof(&self) -> usize { 1 }
///     fn discrete_lagrangian<S: Scalar>(&self, _t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
///         let v = (q1[0] - q0[0]) / h;
///         let q = (q0[0] + q1[0]) * 0.5;
///         (v * v - q * q) * (0.5 * h)
///     }
/// }
/// ```
pub trait DiscreteLagrangian {
    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;

    /// `L_d(q₀, q₁)` for the step from `t₀` to `t₀ + h`.
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S;

    /// `L_d(q₀, q₀ + Δ)`, given the displacement `Δ = q₁ − q₀` exactly.
    ///
    /// The integrator steps displacements: `q₁ − q₀` recomputed from rounded positions carries an
    /// error `ε|q|`, which a difference quotient `(q₁ − q₀)/h` turns into a momentum error
    /// `ε|q|/h` per step, visible as a random walk of conserved momenta. The default forms
    /// `q₁ = q₀ + Δ`; override it (as the built-in rules do) to use `Δ` directly.
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        let q1 = |i: usize| q0[i] + delta[i];
        with_buffer::<S, NODE, S>(q0.len(), S::from(0.0), q1, |q1| {
            self.discrete_lagrangian(t0, h, q0, q1)
        })
    }

    /// An explicit form of the step, if this discrete Lagrangian has one (the trapezoid rule on a
    /// separable Lagrangian: velocity Störmer–Verlet, [`crate::explicit`]). Default: none.
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        None
    }

    /// A structured Newton step, if this discrete Lagrangian may have one (the α rules on a
    /// separable Lagrangian: Jacobian `M/h + hα(1−α)∇²V`, [`crate::separable`]; whether the
    /// Lagrangian really is separable is asked once, [`SeparableStep::mass`]). Default: none.
    fn separable(&self) -> Option<&dyn SeparableStep> {
        None
    }
}

/// A discrete Lagrangian over the control points of one step (what the integrator steps).
///
/// The control points `Q₀ = q_k, Q₁, …, Q_s = q_{k+1}` (`s = internal_stages() + 1`) are given as
/// `q0 = Q₀` and the offsets `Δ_j = Q_j − Q₀` back to back (length `s·n`). The step solves
/// `∂L_d/∂Q_j = 0` for the internal points together with the discrete Legendre transform for
/// `q_{k+1}`; derivatives are always taken with respect to the control points `Q_j`.
pub trait DiscreteAction {
    /// Degrees of freedom `n`.
    fn dof(&self) -> usize;
    /// Number of internal control points per step (0 for two-point discrete Lagrangians).
    fn internal_stages(&self) -> usize {
        0
    }
    /// The discrete action of one step as a function of `Q₀` and the offsets `Q_j − Q₀`.
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S;

    /// An explicit form of the step, if any (see [`DiscreteLagrangian::explicit`]).
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        None
    }

    /// A structured Newton step, if any (see [`DiscreteLagrangian::separable`]).
    fn separable(&self) -> Option<&dyn SeparableStep> {
        None
    }
}

impl<D: DiscreteLagrangian + ?Sized> DiscreteLagrangian for &D {
    fn dof(&self) -> usize {
        (**self).dof()
    }
    #[inline(always)]
    fn discrete_lagrangian<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        (**self).discrete_lagrangian(t0, h, q0, q1)
    }
    #[inline(always)]
    fn discrete_lagrangian_offset<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], delta: &[S]) -> S {
        (**self).discrete_lagrangian_offset(t0, h, q0, delta)
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        (**self).explicit()
    }
    fn separable(&self) -> Option<&dyn SeparableStep> {
        (**self).separable()
    }
}

impl<T: DiscreteLagrangian> DiscreteAction for T {
    fn dof(&self) -> usize {
        DiscreteLagrangian::dof(self)
    }
    #[inline(always)]
    fn action<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S]) -> S {
        self.discrete_lagrangian_offset(t0, h, q0, offsets)
    }
    fn explicit(&self) -> Option<&dyn ExplicitStep> {
        DiscreteLagrangian::explicit(self)
    }
    fn separable(&self) -> Option<&dyn SeparableStep> {
        DiscreteLagrangian::separable(self)
    }
}

/// `(L_d, F₀ … F_s)` as functions of `x = (q₀, Δ₁ … Δ_s)`, the offset form of
/// [`DiscreteAction::action`] and [`crate::DiscreteForce::discrete_force`] (no re-seeding of
/// offsets): output 0 is the action, outputs `1 + j·n + a` the force on control point `j`,
/// component `a` (only when the force is active). For the AD drivers of the step's exact
/// Jacobian ([`crate::certificate`]) and of the momentum increment ([`crate::compensated`]).
pub(crate) struct ActionAndForces<'a, A, F> {
    action: &'a A,
    force: &'a F,
    t0: f64,
    h: f64,
    n: usize,
    s: usize,
}

impl<'a, A: DiscreteAction, F: crate::DiscreteForce> ActionAndForces<'a, A, F> {
    /// The step of `action` and `force` from `t0` with step size `h`.
    pub fn new(action: &'a A, force: &'a F, (t0, h): (f64, f64)) -> Self {
        let (n, s) = (action.dof(), action.internal_stages() + 1);
        Self {
            action,
            force,
            t0,
            h,
            n,
            s,
        }
    }
}

impl<A: DiscreteAction, F: crate::DiscreteForce> MultiFunction for ActionAndForces<'_, A, F> {
    fn inputs(&self) -> usize {
        (self.s + 1) * self.n
    }
    fn outputs(&self) -> usize {
        1 + if self.force.is_active() {
            self.inputs()
        } else {
            0
        }
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, offsets) = x.split_at(self.n);
        out[0] = self.action.action(self.t0, self.h, q0, offsets);
        if self.force.is_active() {
            self.force
                .discrete_force(self.t0, self.h, q0, offsets, &mut out[1..]);
        }
    }
}

/// `L_d` as a function of `(q₀, q₁)` for the AD drivers.
struct TwoPoint<'a, D> {
    ld: &'a D,
    t0: f64,
    h: f64,
}

impl<D: DiscreteLagrangian> MultiFunction for TwoPoint<'_, D> {
    fn inputs(&self) -> usize {
        2 * self.ld.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, q1) = x.split_at(self.ld.dof());
        out[0] = self.ld.discrete_lagrangian(self.t0, self.h, q0, q1);
    }
}

fn gradient<D: DiscreteLagrangian>(
    ld: &D,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    slot: usize,
    out: &mut [f64],
) -> f64 {
    let n = ld.dof();
    let x: Vec<f64> = q0.iter().chain(q1).copied().collect();
    let mut value = [0.0];
    ad::jacobian(
        &TwoPoint { ld, t0, h },
        &x,
        slot * n..(slot + 1) * n,
        &mut value,
        out,
    );
    value[0]
}

/// `D₁L_d(q₀, q₁)`, written into `out`; returns `L_d(q₀, q₁)`.
pub fn d1<D: DiscreteLagrangian>(
    ld: &D,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    out: &mut [f64],
) -> f64 {
    gradient(ld, t0, h, q0, q1, 0, out)
}

/// `D₂L_d(q₀, q₁)`, written into `out`; returns `L_d(q₀, q₁)`.
pub fn d2<D: DiscreteLagrangian>(
    ld: &D,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    out: &mut [f64],
) -> f64 {
    gradient(ld, t0, h, q0, q1, 1, out)
}

/// Discrete Legendre transform `F⁻L_d`: `p₀ = −D₁L_d(q₀, q₁)`.
pub fn legendre_minus<D: DiscreteLagrangian>(
    ld: &D,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    p0: &mut [f64],
) {
    d1(ld, t0, h, q0, q1, p0);
    p0.iter_mut().for_each(|p| *p = -*p);
}

/// Discrete Legendre transform `F⁺L_d`: `p₁ = D₂L_d(q₀, q₁)`.
pub fn legendre_plus<D: DiscreteLagrangian>(
    ld: &D,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    p1: &mut [f64],
) {
    d2(ld, t0, h, q0, q1, p1);
}

/// DEL residual `D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1})` for the steps starting at `t_prev`
/// and `t_prev + h`; zero on discrete trajectories.
pub fn del_residual<D: DiscreteLagrangian>(
    ld: &D,
    t_prev: f64,
    h: f64,
    [q_prev, q, q_next]: [&[f64]; 3],
    out: &mut [f64],
) {
    let mut second = vec![0.0; ld.dof()];
    d2(ld, t_prev, h, q_prev, q, out);
    d1(ld, t_prev + h, h, q, q_next, &mut second);
    out.iter_mut().zip(&second).for_each(|(a, b)| *a += b);
}
