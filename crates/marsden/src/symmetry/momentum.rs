//! Momentum maps: continuous (`J_L`, `J_H`) and discrete (`J^±_{L_d}`).
//!
//! Concept of the notes (MW01): *the Lagrangian momentum map*, *Hamiltonian momentum maps*, *discrete Lagrangian
//! Noether's theorem*. In the dual basis of `𝔤*` (component `a` is the pairing with `e_a`):
//!
//! ```text
//!     J_L(q, v)·e_a        = ⟨∂L/∂v(q, v), (e_a)_Q(q)⟩,
//!     J_H(q, p)·e_a        = ⟨p, (e_a)_Q(q)⟩,
//!     J⁺_{L_d}(q₀, q₁)·e_a = ⟨D₂L_d(q₀, q₁), (e_a)_Q(q₁)⟩,
//!     J⁻_{L_d}(q₀, q₁)·e_a = ⟨−D₁L_d(q₀, q₁), (e_a)_Q(q₀)⟩.
//! ```
//!
//! `J_L = FL*J_H` and `J^±_{L_d} = (F^±L_d)*J_H` ([MW01] §1.3.3, §1.5.2): the discrete maps are
//! `J_H` at the discrete momenta. If `L_d` is invariant, `J⁺ = J⁻` on every pair and both are
//! conserved along discrete trajectories (discrete Noether, [MW01] Thm 1.3.3).
//!
//! The discrete maps take the step's displacement `Δ = q₁ − q₀` (as the integrator does,
//! [`crate::discrete::DiscreteLagrangian::discrete_lagrangian_offset`]) so that `D₂L_d` carries no
//! `ε|q|/h` round-off; [`discrete_momentum`] takes `(q₀, q₁)` and forms `Δ` itself.
//!
//! [MW01]: crate#references

use super::GroupAction;
use crate::discrete::DiscreteLagrangian;
use crate::mechanics;
use crate::mechanics::Lagrangian;
use crate::numerics::ad::{self, MultiFunction};
use crate::scalar::Scalar;

/// `J_H(q, p)·e_a = ⟨p, (e_a)_Q(q)⟩` for every basis element, written into `out` (length m).
pub fn momentum_map<G: GroupAction>(action: &G, q: &[f64], p: &[f64], out: &mut [f64]) {
    let mut xi = vec![0.0; q.len()];
    for (a, j) in out.iter_mut().enumerate().take(action.algebra_dim()) {
        action.generator(a, q, &mut xi);
        *j = pairing(p, &xi);
    }
}

/// `J_L(q, v) = J_H(FL(q, v))`: `⟨∂L/∂v, ξ_Q(q)⟩` for every basis element (length m).
pub fn lagrangian_momentum_map<L: Lagrangian, G: GroupAction>(
    l: &L,
    action: &G,
    t: f64,
    q: &[f64],
    v: &[f64],
    out: &mut [f64],
) {
    let mut p = vec![0.0; l.dof()];
    mechanics::momentum(l, t, q, v, &mut p);
    momentum_map(action, q, &p, out);
}

/// Which discrete momentum map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// `J⁺_{L_d}(q₀, q₁) = ⟨D₂L_d, ξ_Q(q₁)⟩` (momentum at the end of the step).
    Plus,
    /// `J⁻_{L_d}(q₀, q₁) = ⟨−D₁L_d, ξ_Q(q₀)⟩` (momentum at the start of the step).
    Minus,
}

/// `L_d(q₀, q₀ + Δ)` as a function of `(q₀, Δ)` for the AD drivers.
struct OffsetLd<'a, D> {
    ld: &'a D,
    t0: f64,
    h: f64,
}

impl<D: DiscreteLagrangian> MultiFunction for OffsetLd<'_, D> {
    fn inputs(&self) -> usize {
        2 * self.ld.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q0, delta) = x.split_at(self.ld.dof());
        out[0] = self
            .ld
            .discrete_lagrangian_offset(self.t0, self.h, q0, delta);
    }
}

/// The discrete Legendre transform of one side from `(q₀, Δ)`: `p₁ = D₂L_d` (`Plus`) or
/// `p₀ = −D₁L_d` (`Minus`) of the step over `span`, written into `p`.
///
/// In the variables `(q₀, Δ)`: `D₂L_d = ∂/∂Δ` and `D₁L_d = ∂/∂q₀ − ∂/∂Δ`.
pub fn discrete_legendre_offset<D: DiscreteLagrangian>(
    ld: &D,
    span: StepSpan,
    q0: &[f64],
    delta: &[f64],
    side: Side,
    p: &mut [f64],
) {
    let n = ld.dof();
    let x: Vec<f64> = q0.iter().chain(delta).copied().collect();
    let mut grad = vec![0.0; 2 * n];
    let mut value = [0.0];
    let StepSpan { t0, h } = span;
    ad::jacobian(&OffsetLd { ld, t0, h }, &x, 0..2 * n, &mut value, &mut grad);
    for i in 0..n {
        p[i] = match side {
            Side::Plus => grad[n + i],
            Side::Minus => -(grad[i] - grad[n + i]),
        };
    }
}

/// The time span of one step: from `t0` to `t0 + h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepSpan {
    /// The step's start time `t₀`.
    pub t0: f64,
    /// The step size `h`.
    pub h: f64,
}

/// `J^±_{L_d}` of the step `(q₀, q₀ + Δ)` over `span` (from `t₀` to `t₀ + h`), written into
/// `out` (length m).
pub fn discrete_momentum_offset<D: DiscreteLagrangian, G: GroupAction>(
    ld: &D,
    action: &G,
    span: StepSpan,
    q0: &[f64],
    delta: &[f64],
    side: Side,
    out: &mut [f64],
) {
    let n = ld.dof();
    let mut p = vec![0.0; n];
    discrete_legendre_offset(ld, span, q0, delta, side, &mut p);
    match side {
        Side::Minus => momentum_map(action, q0, &p, out),
        Side::Plus => {
            let q1: Vec<f64> = q0.iter().zip(delta).map(|(a, d)| a + d).collect();
            momentum_map(action, &q1, &p, out);
        }
    }
}

/// `J^±_{L_d}(q₀, q₁)` of the step over `span` (from `t₀` to `t₀ + h`), written into `out`
/// (length m).
pub fn discrete_momentum<D: DiscreteLagrangian, G: GroupAction>(
    ld: &D,
    action: &G,
    span: StepSpan,
    q0: &[f64],
    q1: &[f64],
    side: Side,
    out: &mut [f64],
) {
    let delta: Vec<f64> = q1.iter().zip(q0).map(|(b, a)| b - a).collect();
    discrete_momentum_offset(ld, action, span, q0, &delta, side, out);
}

/// `⟨a, b⟩`.
#[inline]
pub(crate) fn pairing(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
