//! The symplecticity certificate of a constrained step, on `T*N`.
//!
//! With holonomic constraints `φ(q) = 0` the run's map (SHAKE + RATTLE) lives on the
//! constraint manifold's cotangent bundle, embedded in `T*Q` as
//!
//! ```text
//!     T*N = { (q, p) : φ(q) = 0,  Dφ(q) v(q, p) = 0 },     p = ∂L/∂v(t, q, v(q, p)),
//! ```
//!
//! and it is symplectic there: it preserves the canonical 2-form `ω` restricted to `T*N`
//! ([MW01] §3.5, [LR04] §7.3), not on all of `T*Q` — the core's step Jacobian
//! ([`SensitiveStep`]) is the derivative of an extension of the map off
//! `T*N` whose normal components mean nothing. So the certificate takes a basis `u₁ … u_k`
//! (`k = 2n − 2d`) of the tangent space of `T*N` at the step's start, pushes it through the
//! step Jacobian `DF`, and reports
//!
//! ```text
//!     max_{i<j} |ω(DF u_i, DF u_j) − ω(u_i, u_j)|,   relative to  max_i |DF u_i|²,
//! ```
//!
//! with `ω(a, b) = ⟨a_q, b_p⟩ − ⟨a_p, b_q⟩` (`|ω(a, b)| ≤ |a||b|`, so the relative defect of a
//! map that mixes nothing up is at most of order one).
//!
//! **The tangent space.** In the velocity chart `(q, v) ↦ (q, ∂L/∂v)` of `T*N`, a tangent
//! vector `(δq, δv)` satisfies the derivatives of both constraints,
//!
//! ```text
//!     Dφ(q) δq = 0,      (vᵀ ∇²φ_c(q) δq)_c + Dφ(q) δv = 0,
//! ```
//!
//! and maps to `(δq, δp) = (δq, ∂²L/∂v∂q δq + ∂²L/∂v² δv)`. The basis is an orthonormal basis
//! of the null space of that `2d × 2n` system (Gram–Schmidt), second derivatives by
//! hyper-dual AD.
//!
//! [MW01]: crate#references
//! [LR04]: crate#references

use super::SensitiveStep;
use super::projection::{AtTime, Component};
use crate::error::Error;
use crate::mechanics::{Constraint, Lagrangian, State};
use crate::numerics::ad::{self, HessianParts};

/// An orthonormal basis (in the velocity chart, see the module documentation) of the tangent
/// space of `T*N` at `(t, q, p)` with `p = ∂L/∂v(t, q, v)`, as vectors `(δq, δp)` of length
/// `2n`: `2n − 2d` of them when the constraints are independent.
pub fn cotangent_basis<L: Lagrangian, C: Constraint>(
    lagrangian: &L,
    constraint: &C,
    t: f64,
    q: &[f64],
    v: &[f64],
) -> Vec<Vec<f64>> {
    let (n, d) = (q.len(), constraint.count());
    let m = 2 * n;
    let mut parts = HessianParts::default();
    // Rows of the linearized constraints in (δq, δv): [∇φ_c, 0] and [vᵀ∇²φ_c, ∇φ_c].
    let mut rows = Vec::with_capacity(2 * d);
    let mut hidden = Vec::with_capacity(d);
    for c in 0..d {
        let f = Component { constraint, c, n };
        ad::partial_hessian(&f, q, 0..n, 0..n, &mut parts);
        let grad = parts.grad_rows.clone();
        let mut row = vec![0.0; m];
        row[..n].copy_from_slice(&grad);
        rows.push(row);
        let mut row = vec![0.0; m];
        for (j, entry) in row[..n].iter_mut().enumerate() {
            *entry = (0..n).map(|i| v[i] * parts.hess[i * n + j]).sum();
        }
        row[n..].copy_from_slice(&grad);
        hidden.push(row);
    }
    rows.extend(hidden);
    let x: Vec<f64> = q.iter().chain(v).copied().collect();
    let l = AtTime { lagrangian, t };
    ad::partial_hessian(&l, &x, n..m, 0..m, &mut parts);
    null_space(&rows, m)
        .into_iter()
        .map(|u| {
            let mut w = u[..n].to_vec();
            // δp_i = Σ_j ∂²L/∂v_i∂q_j δq_j + ∂²L/∂v_i∂v_j δv_j.
            w.extend((0..n).map(|i| (0..m).map(|j| parts.hess[i * m + j] * u[j]).sum::<f64>()));
            w
        })
        .collect()
}

/// An orthonormal basis of `{x ∈ ℝᵐ : ⟨r, x⟩ = 0 for every r in rows}` (modified Gram–Schmidt:
/// the rows first, then the unit vectors, keeping what is left of each).
fn null_space(rows: &[Vec<f64>], m: usize) -> Vec<Vec<f64>> {
    let mut kept: Vec<Vec<f64>> = Vec::new();
    for r in rows {
        if let Some(u) = orthonormalized(r.clone(), &kept) {
            kept.push(u);
        }
    }
    let rank = kept.len();
    for i in 0..m {
        let mut e = vec![0.0; m];
        e[i] = 1.0;
        if let Some(u) = orthonormalized(e, &kept) {
            kept.push(u);
        }
    }
    kept.split_off(rank)
}

/// `x` minus its projections on the orthonormal `kept`, normalized; `None` if less than
/// `10⁻⁸` of its length is left (it lies in their span).
fn orthonormalized(mut x: Vec<f64>, kept: &[Vec<f64>]) -> Option<Vec<f64>> {
    let size = norm(&x);
    for k in kept {
        let c = dot(k, &x);
        x.iter_mut().zip(k).for_each(|(xi, ki)| *xi -= c * ki);
    }
    let left = norm(&x);
    (left > 1e-8 * size.max(f64::MIN_POSITIVE)).then(|| x.iter().map(|xi| xi / left).collect())
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// `ω(a, b) = ⟨a_q, b_p⟩ − ⟨a_p, b_q⟩` for vectors `(δq, δp)` of length `2n`.
pub fn omega(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() / 2;
    dot(&a[..n], &b[n..]) - dot(&a[n..], &b[..n])
}

/// The `(absolute, relative)` defect of `jac` (row-major `2n × 2n`) on the vectors of
/// `basis`: `max_{i<j} |ω(DF u_i, DF u_j) − ω(u_i, u_j)|` and that over `max_i |DF u_i|²`.
pub fn restricted_defect(jac: &[f64], basis: &[Vec<f64>]) -> (f64, f64) {
    let images: Vec<Vec<f64>> = basis
        .iter()
        .map(|u| {
            let m = u.len();
            (0..m).map(|r| dot(&jac[r * m..(r + 1) * m], u)).collect()
        })
        .collect();
    let mut worst: f64 = 0.0;
    for i in 0..basis.len() {
        for j in i + 1..basis.len() {
            let change = omega(&images[i], &images[j]) - omega(&basis[i], &basis[j]);
            // NaN sticks: a Jacobian that is not finite certifies nothing.
            if change.abs() > worst || change.is_nan() {
                worst = change.abs();
            }
        }
    }
    let scale = images
        .iter()
        .map(|w| dot(w, w))
        .fold(0.0, crate::numerics::dense::max_or_nan);
    (worst, worst / scale.max(f64::MIN_POSITIVE))
}

/// The `(absolute, relative)` defect on `T*N` of one constrained step of size `h` of `stepper`
/// (for `lagrangian` under `constraint`) from `state`, whose velocity is `v`.
///
/// # Errors
/// The step (or its Jacobian) fails.
pub fn step_defect_on_cotangent_bundle<S: SensitiveStep, L: Lagrangian, C: Constraint>(
    stepper: &mut S,
    lagrangian: &L,
    constraint: &C,
    state: &State,
    v: &[f64],
    h: f64,
) -> Result<(f64, f64), Error> {
    let n = stepper.dof();
    let basis = cotangent_basis(lagrangian, constraint, state.t, &state.q, v);
    let mut jac = vec![0.0; 4 * n * n];
    let mut s = state.clone();
    stepper.step_with_sensitivity(&mut s, h, &mut jac)?;
    Ok(restricted_defect(&jac, &basis))
}
