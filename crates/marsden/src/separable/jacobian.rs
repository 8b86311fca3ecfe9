//! The exact step Jacobian `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` of a two-point rule on a separable
//! Lagrangian, from `M` and `∇²V` alone.
//!
//! For `L = ½ vᵀMv − V(t, q)` a two-point rule sampling `L` at nodes `c_i ∈ [0, 1]` with weights
//! `w_i` (the α rule: one node α, weight 1; the symmetrised α rule and the trapezoid rule: nodes
//! α and 1 − α, weights ½; [MW01] §2.2.1) has, with `Δ = q_{k+1} − q_k`, `q_c = q_k + cΔ` and
//! `g_c = ∇V(t₀ + ch, q_c)`,
//!
//! ```text
//!     L_d     = h ½ (Δ/h)ᵀ M (Δ/h) − h Σ_i w_i V(t₀ + c_i h, q_{c_i}),
//!     R(Δ)    = p_k + ∂L_d/∂q_k  = p_k − MΔ/h − h Σ_i w_i (1 − c_i) g_{c_i} = 0,
//!     p_{k+1} = ∂L_d/∂q_{k+1}   = MΔ/h − h Σ_i w_i c_i g_{c_i}
//! ```
//!
//! (the residual and momentum of [`super::alpha`] for one node). With `H_i = ∇²V` at node `i`,
//! the implicit function theorem on `R = 0` ([MW01] §1.5) gives
//!
//! ```text
//!     A = M/h + h Σ w_i c_i (1 − c_i) H_i,     B = h Σ w_i (1 − c_i) H_i,
//!     C = h Σ w_i c_i H_i,                     K = M/h − h Σ w_i c_i² H_i,
//!     Y = dΔ/d(q_k, p_k) = A⁻¹ [−B | I],
//!     ∂q_{k+1}/∂(q_k, p_k) = [I | 0] + Y,      ∂p_{k+1}/∂(q_k, p_k) = K Y − [C | 0]:
//! ```
//!
//! one Hessian of `V` per node (banded for local potentials, [`crate::numerics::banded`]) and one
//! `n × n` factorisation, where the general Jacobian
//! ([`crate::analysis::certificate::variational`]) takes a full hyper-dual Hessian of the
//! discrete action. Tests compare the two to round-off. Up to four degrees of freedom the same
//! arithmetic runs on stack arrays (`jacobian_small`, the same bits).
//!
//! [MW01]: crate#references

use super::jacobian_small::{StepData, step_jacobian_small};
use super::step::{Mass, node};
use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::numerics::banded::{BandLu, Banded};

/// A two-point rule that can write its step Jacobian from the structure of a separable
/// Lagrangian (object-safe: plain `f64` data).
pub trait SeparableJacobian {
    /// Writes `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` (row-major `2n × 2n`) of the step of length `h`
    /// from `(t₀, q_k)` with converged offset `Δ = q_{k+1} − q_k` into `jac`.
    ///
    /// `None` if the Lagrangian is not separable (the general Jacobian applies);
    /// `Some(Err(pivot))` if `A` is singular.
    fn step_jacobian(
        &self,
        grid: (f64, f64),
        start: (&[f64], &[f64]),
        jac: &mut [f64],
        ws: &mut JacobianWorkspace,
    ) -> Option<Result<(), f64>>;
}

/// The buffers of `step_jacobian` and the mass matrix, asked once.
#[derive(Debug, Clone, Default)]
pub struct JacobianWorkspace {
    /// `None`: not asked yet; `Some(None)`: not separable.
    pub(super) mass: Option<Option<Mass>>,
    /// `∇²V` at one node.
    pub(super) hess: Banded,
    a: Banded,
    b: Banded,
    c: Banded,
    k: Banded,
    lu: BandLu,
    /// `q_c`.
    node: Vec<f64>,
    /// `Y` (column-major `n × 2n`).
    y: Vec<f64>,
}

impl JacobianWorkspace {
    fn mass_of<L: Lagrangian>(&mut self, l: &L) -> Option<&Mass> {
        self.mass
            .get_or_insert_with(|| match l.structure() {
                Structure::Separable {
                    mass: MassMatrix::Diagonal(d),
                } => Some(Mass::Diagonal(d)),
                Structure::Separable {
                    mass: MassMatrix::Dense(m),
                } => Some(Mass::Dense(m)),
                Structure::General => None,
            })
            .as_ref()
    }
}

/// The step Jacobian of the module documentation for the rule with `nodes` `(c_i, w_i)`; `None`
/// if `l` is not separable, `Some(Err(pivot))` if `A` is singular. Systems of up to four degrees
/// of freedom take the same arithmetic on stack arrays ([`super::jacobian_small`]).
pub(crate) fn step_jacobian<L: Lagrangian>(
    l: &L,
    nodes: &[(f64, f64)],
    grid: (f64, f64),
    start: (&[f64], &[f64]),
    jac: &mut [f64],
    ws: &mut JacobianWorkspace,
) -> Option<Result<(), f64>> {
    let data = step_data(l, nodes, grid, start, ws)?;
    if let Some(Some(mass)) = &ws.mass
        && let Some(small) = step_jacobian_small(&data, mass, &mut ws.hess, jac)
    {
        return Some(small);
    }
    Some(banded(&data, jac, ws))
}

/// The step's data with the half-bandwidth of `∇²V` (that of the potential for a diagonal
/// mass, else full); `None` if `l` is not separable.
pub(super) fn step_data<'a, L: Lagrangian>(
    l: &'a L,
    nodes: &'a [(f64, f64)],
    grid: (f64, f64),
    start: (&'a [f64], &'a [f64]),
    ws: &mut JacobianWorkspace,
) -> Option<StepData<'a, L>> {
    let diagonal = matches!(ws.mass_of(l)?, Mass::Diagonal(_));
    let bandwidth = match l.potential_bandwidth() {
        Some(b) if diagonal => b,
        _ => start.0.len().saturating_sub(1),
    };
    Some(StepData {
        l,
        nodes,
        grid,
        start,
        bandwidth,
    })
}

/// The step Jacobian in band storage, any `n`; `Err(pivot)` if `A` is singular.
pub(super) fn banded<L: Lagrangian>(
    data: &StepData<'_, L>,
    jac: &mut [f64],
    ws: &mut JacobianWorkspace,
) -> Result<(), f64> {
    let (l, nodes, bandwidth) = (data.l, data.nodes, data.bandwidth);
    let ((t0, h), (q0, delta)) = (data.grid, data.start);
    let n = q0.len();
    for m in [&mut ws.a, &mut ws.b, &mut ws.c, &mut ws.k] {
        m.reshape(n, bandwidth);
    }
    if let Some(Some(mass)) = &ws.mass {
        for i in 0..n {
            for j in ws.a.columns(i) {
                let m = mass.entry(n, i, j) / h;
                ws.a.set(i, j, m);
                ws.k.set(i, j, m);
            }
        }
    }
    ws.node.resize(n, 0.0);
    for &(c, w) in nodes {
        ws.hess.reshape(n, bandwidth);
        node(c, q0, delta, &mut ws.node);
        l.potential_hessian(t0 + c * h, &ws.node, &mut ws.hess);
        let hw = h * w;
        for i in 0..n {
            for j in ws.hess.columns(i) {
                let hij = ws.hess.get(i, j);
                ws.a.add(i, j, hw * c * (1.0 - c) * hij);
                ws.b.add(i, j, hw * (1.0 - c) * hij);
                ws.c.add(i, j, hw * c * hij);
                ws.k.add(i, j, -hw * c * c * hij);
            }
        }
    }
    ws.lu.factor(&ws.a).map_err(|e| e.pivot)?;
    write_jacobian(n, jac, ws);
    Ok(())
}

/// `Y = A⁻¹[−B | I]`, then `[[I | 0] + Y; K Y − [C | 0]]` into `jac` (row-major `2n × 2n`).
fn write_jacobian(n: usize, jac: &mut [f64], ws: &mut JacobianWorkspace) {
    let m = 2 * n;
    ws.y.clear();
    ws.y.resize(n * m, 0.0);
    for (j, col) in ws.y.chunks_exact_mut(n).enumerate() {
        if j < n {
            for (i, x) in col.iter_mut().enumerate() {
                *x = -ws.b.get(i, j);
            }
        } else {
            col[j - n] = 1.0;
        }
        ws.lu.solve(col);
    }
    for a in 0..n {
        let (top, bottom) = (a * m, (n + a) * m);
        for j in 0..m {
            let col = &ws.y[j * n..(j + 1) * n];
            jac[top + j] = f64::from(u8::from(a == j)) + col[a];
            let through: f64 = ws.k.columns(a).map(|k| ws.k.get(a, k) * col[k]).sum();
            let direct = if j < n { ws.c.get(a, j) } else { 0.0 };
            jac[bottom + j] = through - direct;
        }
    }
}
