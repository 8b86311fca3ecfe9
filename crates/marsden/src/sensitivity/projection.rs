//! The derivative of the RATTLE momentum projection onto `T*N`.
//!
//! The projection ([`crate::holonomic::Rattle`]) replaces `p̃` at `q = q_{k+1}` by
//! `p = p̃ − Dφ(q)ᵀν`, with `(v, ν)` the solution of ([HLW06] §VII.1, [LMO08] §3)
//!
//! ```text
//!     K₁ = ∂L/∂v(t, q, v) + Dφ(q)ᵀν − p̃ = 0,        K₂ = Dφ(q) v = 0.
//! ```
//!
//! The implicit function theorem at the converged `(v, ν)` gives, with `W = ∂²L/∂v²`,
//! `H_c = ∇²φ_c(q)` and `G = Dφ(q)`,
//!
//! ```text
//!     [[W, Gᵀ], [G, 0]] [dv; dν] = [dp̃ − (∂²L/∂v∂q + Σ_c ν_c H_c) dq;  −(vᵀH_c dq)_c],
//!     dp = dp̃ − Σ_c ν_c H_c dq − Gᵀ dν,
//! ```
//!
//! the same equations whether the projection took its closed form (constant mass matrix) or
//! Newton's method. Parameters `θ` of `L` and `φ`, read as frozen coordinates after `q`, enter
//! exactly as `dq` does (their own columns; [`super::parametric_constrained`]). Second derivatives come from one hyper-dual evaluation of `L` over `(q, v)`
//! and one of each constraint component over `q`.
//!
//! [HLW06]: crate#references
//! [LMO08]: crate#references

use crate::error::{Error, StepError, StepFailure};
use crate::mechanics::{Constraint, Lagrangian};
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::dense::Lu;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// `(q, v) ↦ L(t, q, v)`.
pub(super) struct AtTime<'a, L> {
    pub(super) lagrangian: &'a L,
    pub(super) t: f64,
}

impl<L: Lagrangian> MultiFunction for AtTime<'_, L> {
    fn inputs(&self) -> usize {
        2 * self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let (q, v) = x.split_at(x.len() / 2);
        out[0] = self.lagrangian.lagrangian(S::from(self.t), q, v);
    }
}

/// `q ↦ φ_c(q)` as the first output.
pub(super) struct Component<'a, C> {
    pub(super) constraint: &'a C,
    pub(super) c: usize,
    pub(super) n: usize,
}

impl<C: Constraint> MultiFunction for Component<'_, C> {
    fn inputs(&self) -> usize {
        self.n
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        let mut phi = Buffer::<S, NODE>::empty();
        let phi = phi.filled(self.constraint.count(), zero);
        self.constraint.constraint(x, phi);
        out[0] = phi[self.c];
    }
}

/// Buffers of [`projection_jacobian`].
#[derive(Debug, Default)]
pub(super) struct ProjectionWorkspace {
    x: Vec<f64>,
    parts: HessianParts,
    /// `G = Dφ(q)` (d × n) and `Σ_c ν_c H_c` (n × (n + P)), `vᵀH_c` (d × (n + P)).
    g: Vec<f64>,
    curvature: Vec<f64>,
    v_curvature: Vec<f64>,
    kkt: Vec<f64>,
    lu: Lu,
    col: Vec<f64>,
    scratch: Vec<f64>,
    /// `∂p/∂(q, p̃, θ)`, row-major n × (2n + P).
    jac: Vec<f64>,
}

/// `∂p/∂(q, p̃, θ)` (row-major n × (2n + P)) of the projection at `q` with converged velocities
/// `v` and multipliers `ν` at time `t` (see the module documentation).
///
/// `lagrangian` and `constraint` may carry `P` frozen coordinates `θ` after the `n` free ones
/// (parameters, [`super::parametric::Frozen`]): `q` is then `(q, θ)` (length `n + P`), `v` the
/// `n` free velocities, and `θ` enters as `q` does, with `dθ` in the last `P` columns. Without
/// parameters (`P = 0`) the result is `∂p/∂(q, p̃)`.
///
/// Errors with [`StepError::SingularJacobian`] if the KKT matrix is singular.
pub(super) fn projection_jacobian<'w, L: Lagrangian, C: Constraint>(
    lagrangian: &L,
    constraint: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
    nu: &[f64],
    ws: &'w mut ProjectionWorkspace,
) -> Result<&'w [f64], Error> {
    let (n, big, d) = (v.len(), q.len(), constraint.count());
    let (m, k, cols) = (2 * n, n + d, n + big);
    Error::check_len("projection coordinates", q, lagrangian.dof())?;
    Error::check_len("projection multipliers", nu, d)?;
    ws.g.resize(d * n, 0.0);
    ws.curvature.clear();
    ws.curvature.resize(n * big, 0.0);
    ws.v_curvature.resize(d * big, 0.0);
    for (c, &nu_c) in nu.iter().enumerate() {
        let phi = Component {
            constraint,
            c,
            n: big,
        };
        ad::partial_hessian(&phi, q, 0..n, 0..big, &mut ws.parts);
        ws.g[c * n..(c + 1) * n].copy_from_slice(&ws.parts.grad_rows);
        for (entry, second) in ws.curvature.iter_mut().zip(&ws.parts.hess) {
            *entry += nu_c * second;
        }
        for b in 0..big {
            ws.v_curvature[c * big + b] = (0..n).map(|a| v[a] * ws.parts.hess[a * big + b]).sum();
        }
    }
    ws.x.clear();
    ws.x.extend(q.iter().chain(v));
    ws.x.resize(2 * big, 0.0);
    let l = AtTime { lagrangian, t };
    let w = 2 * big;
    ad::partial_hessian(&l, &ws.x, big..big + n, 0..w, &mut ws.parts);
    // hess row a (∂/∂v_a), column b < n + P: ∂²L/∂v_a∂(q, θ)_b; column n + P + b: W_ab.
    ws.kkt.clear();
    ws.kkt.resize(k * k, 0.0);
    for a in 0..n {
        for b in 0..n {
            ws.kkt[a * k + b] = ws.parts.hess[a * w + big + b];
        }
        for c in 0..d {
            ws.kkt[a * k + n + c] = ws.g[c * n + a];
            ws.kkt[(n + c) * k + a] = ws.g[c * n + a];
        }
    }
    ws.lu.factor(&ws.kkt, k).map_err(|e| {
        Error::Step(StepFailure {
            step: 0,
            t,
            cause: StepError::SingularJacobian {
                iteration: 0,
                pivot: e.pivot,
            },
        })
    })?;
    ws.jac.resize(n * cols, 0.0);
    ws.col.resize(k, 0.0);
    for b in 0..cols {
        // The coordinate of column b: q_b (b < n), none for p̃, θ (b ≥ 2n).
        let e = match b {
            b if b < n => Some(b),
            b if b >= m => Some(b - n),
            _ => None,
        };
        for a in 0..n {
            ws.col[a] = match e {
                Some(e) => -(ws.parts.hess[a * w + e] + ws.curvature[a * big + e]),
                None => f64::from(u8::from(a == b - n)),
            };
        }
        for c in 0..d {
            ws.col[n + c] = e.map_or(0.0, |e| -ws.v_curvature[c * big + e]);
        }
        ws.lu.solve(&mut ws.col, &mut ws.scratch);
        for a in 0..n {
            let direct = match e {
                Some(e) => -ws.curvature[a * big + e],
                None => f64::from(u8::from(a == b - n)),
            };
            let through: f64 = (0..d).map(|c| ws.g[c * n + a] * ws.col[n + c]).sum();
            ws.jac[a * cols + b] = direct - through;
        }
    }
    Ok(&ws.jac)
}
