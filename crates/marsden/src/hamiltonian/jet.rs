//! Derivatives of a Hamiltonian by AD: `∇H`, `∇²H`, Hamilton's vector field and its Jacobian.
//!
//! Concept of the notes (MW01): *Hamiltonian mechanics*. With `z = (q, p)` and `J = [[0, I], [−I, 0]]`, Hamilton's
//! equations are `ż = X_H(z) = J∇H(z)`, i.e. `q̇ = ∂H/∂p`, `ṗ = −∂H/∂q`, and the Jacobian of the
//! vector field is `DX_H = J∇²H`. One hyper-dual evaluation of `H` gives value, gradient and
//! Hessian together ([`crate::numerics::ad::partial_hessian`]).

use super::Hamiltonian;
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::scalar::Scalar;

/// `H(t, ·)` as a function of `z = (q, p)` for the AD drivers.
pub(crate) struct OnPhaseSpace<'a, H> {
    pub ham: &'a H,
    pub t: f64,
}

impl<H: Hamiltonian> MultiFunction for OnPhaseSpace<'_, H> {
    fn inputs(&self) -> usize {
        2 * self.ham.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, z: &[S], out: &mut [S]) {
        let (q, p) = z.split_at(self.ham.dof());
        out[0] = self.ham.hamiltonian(S::from(self.t), q, p);
    }
}

/// Hamilton's vector field `X_H = (∂H/∂p, −∂H/∂q)` at `(t, q, p)`, written into `(dq, dp)`;
/// returns `H(t, q, p)`.
pub fn vector_field<H: Hamiltonian>(
    ham: &H,
    t: f64,
    q: &[f64],
    p: &[f64],
    dq: &mut [f64],
    dp: &mut [f64],
) -> f64 {
    let n = ham.dof();
    let z: Vec<f64> = q.iter().chain(p).copied().collect();
    let mut grad = vec![0.0; 2 * n];
    let mut value = [0.0];
    ad::jacobian(
        &OnPhaseSpace { ham, t },
        &z,
        0..2 * n,
        &mut value,
        &mut grad,
    );
    for i in 0..n {
        dq[i] = grad[n + i];
        dp[i] = -grad[i];
    }
    value[0]
}

/// Value, gradient and Hessian of `H` at one phase-space point.
#[derive(Debug, Clone, Default)]
pub struct PhaseJet {
    /// Degrees of freedom.
    pub n: usize,
    /// `H(t, q, p)`.
    pub value: f64,
    /// `∇H = (∂H/∂q, ∂H/∂p)` (length 2n).
    pub grad: Vec<f64>,
    /// `∇²H`, row-major 2n × 2n in the variables `(q, p)`.
    pub hess: Vec<f64>,
    parts: HessianParts,
}

impl PhaseJet {
    /// Evaluates the jet at `(t, z)` with `z = (q, p)`, reusing this jet's buffers.
    pub fn eval<H: Hamiltonian>(&mut self, ham: &H, t: f64, z: &[f64]) {
        let n = ham.dof();
        let m = 2 * n;
        ad::partial_hessian(&OnPhaseSpace { ham, t }, z, 0..m, 0..m, &mut self.parts);
        self.n = n;
        self.value = self.parts.values[0];
        self.grad.clear();
        self.grad.extend_from_slice(&self.parts.grad_rows);
        self.hess.clear();
        self.hess.extend_from_slice(&self.parts.hess);
    }

    /// A new jet at `(t, q, p)`.
    pub fn at<H: Hamiltonian>(ham: &H, t: f64, q: &[f64], p: &[f64]) -> Self {
        let z: Vec<f64> = q.iter().chain(p).copied().collect();
        let mut jet = Self::default();
        jet.eval(ham, t, &z);
        jet
    }

    /// `X_H = J∇H` (length 2n: `(∂H/∂p, −∂H/∂q)`).
    pub fn vector_field(&self, out: &mut [f64]) {
        let n = self.n;
        for i in 0..n {
            out[i] = self.grad[n + i];
            out[n + i] = -self.grad[i];
        }
    }

    /// `DX_H = J∇²H`, row-major 2n × 2n.
    pub fn vector_field_jacobian(&self, out: &mut [f64]) {
        let (n, m) = (self.n, 2 * self.n);
        for i in 0..n {
            for k in 0..m {
                out[i * m + k] = self.hess[(n + i) * m + k];
                out[(n + i) * m + k] = -self.hess[i * m + k];
            }
        }
    }
}
