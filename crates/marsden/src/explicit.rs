//! The explicit fast path: the trapezoid rule on a separable Lagrangian is velocity
//! Störmer–Verlet.
//!
//! For `L = ½ vᵀ M v − V(t, q)` with constant `M`, the trapezoid discrete Lagrangian
//! `L_d = (h/2)[L(t₀, q₀, v) + L(t₁, q₁, v)]`, `v = (q₁ − q₀)/h`, gives ([MW01] §2.2.1; HLW06
//! §VI.6; reference cases §0)
//!
//! ```text
//!     p_k     = −D₁L_d = M v − (h/2) ∂L/∂q(t₀, q_k)     ⇒   p½ = p_k + (h/2) ∂L/∂q(t₀, q_k),
//!                                                             q_{k+1} = q_k + h M⁻¹ p½,
//!     p_{k+1} =  D₂L_d = M v + (h/2) ∂L/∂q(t₁, q_{k+1}) ⇒   p_{k+1} = p½ + (h/2) ∂L/∂q(t₁, q_{k+1}),
//! ```
//!
//! since `∂L/∂q = −∇V` does not depend on `v`. No Newton iteration, and one gradient
//! ([`crate::Lagrangian::potential_gradient`], AD unless written by hand) per step: the gradient
//! at `(t₁, q_{k+1})` that ends step k is kept in the [`ExplicitWorkspace`] and starts step k+1
//! ("first same as last"), as long as the next step starts from the same positions (bit for bit)
//! and the same time (to a few ulps: the run rewrites `t_k = t₀ + k h`, which may differ from
//! the accumulated `t + h` in the last bit). The integrator takes this path automatically for
//! the trapezoid rule when the Lagrangian declares [`crate::Structure::Separable`] and there are
//! no forces or constraints; a test checks it against the general Newton path to round-off.
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).

use crate::linalg::Lu;
use crate::{Lagrangian, MassMatrix, Structure};

/// A step that needs no nonlinear solve (object-safe: plain `f64` state).
pub trait ExplicitStep {
    /// One step from `(q, p)` at `t`: writes the offset `Δ = q_{k+1} − q_k` into `delta` and
    /// replaces `p` by `p_{k+1}`; `ws` holds buffers and the cached gradient. Returns the number
    /// of potential gradients evaluated (1 in a run, 2 on a fresh start).
    fn explicit_step(
        &self,
        t: f64,
        h: f64,
        q: &[f64],
        p: &mut [f64],
        delta: &mut [f64],
        ws: &mut ExplicitWorkspace,
    ) -> usize;
}

/// Buffers of the explicit step and the gradient that ended the last step.
#[derive(Debug, Clone, Default)]
pub struct ExplicitWorkspace {
    /// `∇V` at `(cache_t, cache_q)`.
    grad: Vec<f64>,
    cache_q: Vec<f64>,
    cache_t: f64,
    cache_valid: bool,
    q_next: Vec<f64>,
    /// Storage for [`Lagrangian::potential_gradient`].
    scratch: Vec<f64>,
    /// Storage for the dense mass solve.
    solve: Vec<f64>,
}

impl ExplicitWorkspace {
    fn resize(&mut self, n: usize) {
        if self.grad.len() != n {
            self.grad.resize(n, 0.0);
            self.q_next.resize(n, 0.0);
            self.cache_q.resize(n, 0.0);
            self.cache_valid = false;
        }
    }

    /// Whether the cached gradient was taken at `(t, q)`.
    fn holds(&self, t: f64, h: f64, q: &[f64]) -> bool {
        let close = (t - self.cache_t).abs() <= 16.0 * f64::EPSILON * t.abs().max(h.abs());
        self.cache_valid && close && self.cache_q.as_slice() == q
    }
}

/// `M⁻¹` of a separable Lagrangian, ready to apply.
#[derive(Debug, Clone)]
pub enum InverseMass {
    /// Reciprocals of a diagonal mass matrix.
    Diagonal(Vec<f64>),
    /// LU factors of a dense mass matrix.
    Dense(Lu),
}

impl InverseMass {
    /// `M⁻¹` if `structure` is separable with an invertible mass matrix.
    pub fn of(structure: &Structure) -> Option<Self> {
        let Structure::Separable { mass } = structure else {
            return None;
        };
        match mass {
            MassMatrix::Diagonal(d) if d.iter().all(|m| *m != 0.0 && m.is_finite()) => {
                Some(Self::Diagonal(d.iter().map(|m| 1.0 / m).collect()))
            }
            MassMatrix::Diagonal(_) => None,
            MassMatrix::Dense(m) => {
                let n = (m.len() as f64).sqrt().round() as usize;
                let mut lu = Lu::new();
                lu.factor(m, n).ok().map(|_| Self::Dense(lu))
            }
        }
    }

    /// `x ← M⁻¹ x` (`scratch` for the dense solve).
    #[inline]
    pub fn apply(&self, x: &mut [f64], scratch: &mut Vec<f64>) {
        match self {
            Self::Diagonal(d) => x.iter_mut().zip(d).for_each(|(v, di)| *v *= di),
            Self::Dense(lu) => lu.solve(x, scratch),
        }
    }
}

/// `p ← p − (h/2) ∇V`.
#[inline]
fn half_kick(h: f64, grad: &[f64], p: &mut [f64]) {
    let c = 0.5 * h;
    p.iter_mut().zip(grad).for_each(|(pi, g)| *pi -= c * g);
}

/// One velocity Störmer–Verlet step of a separable `L` (the trapezoid variational step):
/// `Δ = h M⁻¹ p½` into `delta`, `p ← p_{k+1}`; returns the gradients evaluated.
pub(crate) fn velocity_verlet<L: Lagrangian>(
    l: &L,
    inverse_mass: &InverseMass,
    (t, h): (f64, f64),
    (q, p): (&[f64], &mut [f64]),
    delta: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> usize {
    ws.resize(q.len());
    let mut gradients = 1;
    if !ws.holds(t, h, q) {
        l.potential_gradient(t, q, &mut ws.grad, &mut ws.scratch);
        gradients += 1;
    }
    half_kick(h, &ws.grad, p);
    delta.copy_from_slice(p);
    inverse_mass.apply(delta, &mut ws.solve);
    delta.iter_mut().for_each(|d| *d *= h);
    ws.q_next
        .iter_mut()
        .zip(q.iter().zip(delta.iter()))
        .for_each(|(x, (qi, d))| *x = qi + d);
    l.potential_gradient(t + h, &ws.q_next, &mut ws.grad, &mut ws.scratch);
    half_kick(h, &ws.grad, p);
    std::mem::swap(&mut ws.cache_q, &mut ws.q_next);
    ws.cache_t = t + h;
    ws.cache_valid = true;
    gradients
}
