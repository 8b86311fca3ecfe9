//! Derivatives of discrete Lagrangians by AD: `D₁L_d`, `D₂L_d`, the discrete Legendre
//! transforms and the DEL residual ([MW01] §1.3, [conventions](crate#conventions)):
//!
//! ```text
//!     F⁻L_d(q₀, q₁) = (q₀, −D₁L_d(q₀, q₁)),     F⁺L_d(q₀, q₁) = (q₁, D₂L_d(q₀, q₁)),
//!     D₂L_d(q_{k−1}, q_k) + D₁L_d(q_k, q_{k+1}) = 0.
//! ```
//!
//! [MW01]: crate#references

use super::force::DiscreteForce;
use super::lagrangian::{DiscreteAction, DiscreteLagrangian, fixed_points};
use crate::mechanics::lagrangian::times_dof;
use crate::numerics::ad::{self, MultiFunction};
use crate::scalar::Scalar;

/// `(L_d, F₀ … F_s)` as functions of `x = (q₀, Δ₁ … Δ_s)`, the offset form of
/// [`DiscreteAction::action`] and [`DiscreteForce::discrete_force`] (no re-seeding of
/// offsets): output 0 is the action, outputs `1 + j·n + a` the force on control point `j`,
/// component `a` (only when the force is active). For the AD drivers of the step's exact
/// Jacobian ([`crate::analysis::certificate`]) and of the momentum increment ([`crate::integrator::compensated`]).
pub(crate) struct ActionAndForces<'a, A, F> {
    action: &'a A,
    force: &'a F,
    t0: f64,
    h: f64,
    n: usize,
    s: usize,
}

impl<'a, A: DiscreteAction, F: DiscreteForce> ActionAndForces<'a, A, F> {
    /// The step of `action` and `force` from `t0` with step size `h`.
    pub fn new(action: &'a A, force: &'a F, t0: f64, h: f64) -> Self {
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

impl<A: DiscreteAction, F: DiscreteForce> MultiFunction for ActionAndForces<'_, A, F> {
    const MAX_INPUTS: Option<usize> = fixed_points::<A>();
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
    const MAX_INPUTS: Option<usize> = times_dof(D::FIXED_DOF, 2, 0);
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
