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
//! since `∂L/∂q = −∇V` does not depend on `v`. No Newton iteration: one gradient of `L` in `q`
//! (by AD, at `v = 0`) per step. The integrator takes this path automatically for the trapezoid
//! rule when the Lagrangian declares [`crate::Structure::Separable`] and there are no forces or
//! constraints; a test checks it against the general Newton path to round-off.
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).

use crate::ad::{self, MultiFunction};
use crate::linalg::Lu;
use crate::{Lagrangian, MassMatrix, Scalar, Structure};

/// A step that needs no nonlinear solve (object-safe: plain `f64` state).
pub trait ExplicitStep {
    /// One step from `(q, p)` at `t`: writes the offset `Δ = q_{k+1} − q_k` into `delta` and
    /// replaces `p` by `p_{k+1}`; `work` is scratch.
    fn explicit_step(
        &self,
        t: f64,
        h: f64,
        q: &[f64],
        p: &mut [f64],
        delta: &mut [f64],
        work: &mut Vec<f64>,
    );
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
}

/// `q ↦ L(t, q, 0)` for the AD driver: its gradient is `∂L/∂q = −∇V` of a separable `L`.
struct AtRest<'a, L> {
    lagrangian: &'a L,
    t: f64,
}

impl<L: Lagrangian> MultiFunction for AtRest<'_, L> {
    fn inputs(&self) -> usize {
        self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        crate::scratch::with_buffer::<S, { crate::scratch::NODE }, ()>(
            q.len(),
            zero,
            |_| zero,
            |v| {
                out[0] = self.lagrangian.lagrangian(S::from(self.t), q, v);
            },
        );
    }
}

/// `p ← p + (h/2) ∂L/∂q(t, q)`.
pub(crate) fn half_kick<L: Lagrangian>(
    l: &L,
    t: f64,
    h: f64,
    q: &[f64],
    p: &mut [f64],
    grad: &mut [f64],
) {
    let mut value = [0.0];
    ad::jacobian(
        &AtRest { lagrangian: l, t },
        q,
        0..q.len(),
        &mut value,
        grad,
    );
    p.iter_mut()
        .zip(grad.iter())
        .for_each(|(pi, g)| *pi += 0.5 * h * g);
}

/// One velocity Störmer–Verlet step of a separable `L` (the trapezoid variational step):
/// `Δ = h M⁻¹ p½` into `delta`, `p ← p_{k+1}`.
pub(crate) fn velocity_verlet<L: Lagrangian>(
    l: &L,
    inverse_mass: &InverseMass,
    (t, h): (f64, f64),
    (q, p): (&[f64], &mut [f64]),
    delta: &mut [f64],
    work: &mut Vec<f64>,
) {
    let n = q.len();
    work.resize(2 * n, 0.0);
    let (grad, q_next) = work.split_at_mut(n);
    half_kick(l, t, h, q, p, grad);
    delta.copy_from_slice(p);
    match inverse_mass {
        InverseMass::Diagonal(d) => delta.iter_mut().zip(d).for_each(|(v, di)| *v *= di),
        InverseMass::Dense(lu) => lu.solve(delta, &mut grad.to_vec()),
    }
    delta.iter_mut().for_each(|d| *d *= h);
    q_next
        .iter_mut()
        .zip(q.iter().zip(delta.iter()))
        .for_each(|(x, (qi, d))| *x = qi + d);
    half_kick(l, t + h, h, q_next, p, grad);
}
