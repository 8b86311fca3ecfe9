//! The midpoint (and generalised α) rule on a separable Lagrangian: a Newton solve with the
//! Jacobian `M/h + hα(1−α)∇²V`, reused across iterations and steps while it converges.
//!
//! For `L = ½ vᵀ M v − V(t, q)` and `L_d^α = h L(t₀ + αh, q₀ + αΔ, Δ/h)`, `Δ = q_{k+1} − q_k`,
//! the discrete Legendre transforms are ([MW01] §2.2.1; [conventions](crate#conventions))
//!
//! ```text
//!     R(Δ)    = p_k + ∂L_d/∂Q₀ = p_k − M Δ/h − h(1−α) ∇V(t₀ + αh, q_k + αΔ) = 0,
//!     p_{k+1} = ∂L_d/∂Q₁       = M Δ/h − hα ∇V(t₀ + αh, q_k + αΔ),
//! ```
//!
//! so `−∂R/∂Δ = A = M/h + hα(1−α)∇²V` (α = ½: `M/h + (h/4)∇²V`), symmetric, and positive
//! definite for small `h`. Each Newton iteration needs one gradient of `V`
//! ([`crate::mechanics::Lagrangian::potential_gradient`]); the Jacobian needs `∇²V`
//! ([`crate::mechanics::Lagrangian::potential_hessian`], banded for local potentials, so a chain of `n`
//! oscillators costs `O(n)` per step, [`crate::numerics::banded`]).
//!
//! **Jacobian reuse** (simplified Newton, Hairer & Wanner, *Solving ODEs II*, §IV.8): for
//! systems of at least [`REUSE_MIN_DOF`] degrees of freedom `A` is factored once and kept — across iterations and across steps of the same `h` — as long as the
//! iteration contracts fast: when the ratio of successive updates `θ = ‖δ_k‖/‖δ_{k−1}‖` exceeds
//! 0.1 with a Jacobian from an earlier step, a fresh one is assembled at the current iterate; an
//! update that grows (`θ ≥ 1`) is discarded first. Smaller systems take exact Newton steps
//! (a fresh `A` per update). The stopping tests are those of
//! [`crate::numerics::newton`], so the solution is the general path's to round-off (test
//! `separable_fast_path`); the counters `jacobian_factorizations` and `potential_gradients` of
//! [`crate::integrator::Statistics`] show the reuse.
//!
//! [MW01]: crate#references

use super::alpha_small::solve_alpha_small;
use super::step::{Frame, Mass, SeparableWorkspace, node};
use crate::mechanics::Lagrangian;
use crate::numerics::dense::max_norm;
use crate::numerics::newton::{Convergence, NewtonFailure, NewtonOptions, NewtonReport};

/// Contraction rate above which a reused Jacobian is replaced by a fresh one.
const THETA_REFRESH: f64 = 0.1;

/// Systems with at least this many degrees of freedom keep their Jacobian across iterations
/// and steps; smaller ones assemble a fresh one for every update (exact Newton), since for them
/// `∇²V` costs about as much as `∇V` and quadratic convergence saves evaluations.
pub const REUSE_MIN_DOF: usize = 32;

/// Estimated error of a reused-Jacobian iterate, relative to the update tolerance, below which
/// the residual test may stop the iteration (the general path's quadratic step leaves an error
/// far below one ulp; this keeps the linear one there too).
const ERROR_MARGIN: f64 = 1.0 / 16.0;

/// The α rule on a separable `L`: what one iterate gives.
struct Iterate {
    /// `‖R‖∞`.
    residual: f64,
    /// `max(|p_k|, |∂L_d/∂Q₀|)`: the size of the residual's terms.
    scale: f64,
}

/// Newton's method on the separable α-rule step (see the module docs).
///
/// Stops as the general path does ([`crate::numerics::newton`]), with one addition that keeps the answer
/// at round-off although a reused Jacobian converges only linearly: after an update the
/// residual test counts only once the estimated error of the iterate, `θ/(1−θ)·‖δ‖` (Hairer &
/// Wanner §IV.8; `θ` measured in this step, else the last step's), is below the update
/// tolerance — a quadratically convergent step meets this as soon as the general path would.
pub(crate) fn solve_alpha<L: Lagrangian>(
    l: &L,
    alpha: f64,
    frame: Frame<'_>,
    z: &mut [f64],
    p_next: &mut [f64],
    options: &NewtonOptions,
    ws: &mut SeparableWorkspace,
) -> Result<NewtonReport, NewtonFailure> {
    if let Some(result) = solve_alpha_small(l, alpha, frame, &mut *z, &mut *p_next, options, ws) {
        return result;
    }
    let n = frame.q0.len();
    ws.resize(n);
    let q_scale = frame
        .q0
        .iter()
        .fold(f64::MIN_POSITIVE, |m, q| m.max(q.abs()));
    let mut report = NewtonReport::default();
    let reuse = n >= REUSE_MIN_DOF;
    let mut state = Contraction {
        previous: f64::NAN,
        fresh: false,
        refresh: !reuse || ws.lu_h != Some(frame.h),
    };
    let mut convergence = Convergence::new(options);
    let mut error_small = true;
    loop {
        let it = evaluate(l, alpha, frame, z, p_next, ws);
        report.evaluations += 1;
        report.residual = it.residual;
        if convergence.check_gated(&report, it.scale, error_small)? {
            return Ok(report);
        }
        let (size, theta) = state.update(l, alpha, frame, z, ws, &mut report)?;
        report.iterations += 1;
        z.iter_mut().zip(&ws.update).for_each(|(d, u)| *d += u);
        let znorm = z.iter().fold(q_scale, |m, d| m.max(d.abs()));
        convergence.record_update(size, znorm);
        if theta.is_finite() {
            ws.theta = theta;
        }
        let rate = if theta.is_finite() { theta } else { ws.theta };
        let target = ERROR_MARGIN * convergence.step_tolerance() * znorm;
        error_small = !reuse || (rate < 1.0 && rate / (1.0 - rate) * size <= target);
        state.refresh |= !reuse;
    }
}

/// Bookkeeping of the simplified Newton iteration within one step.
struct Contraction {
    /// `‖δ‖` of the last update with the current Jacobian (NaN: none yet).
    previous: f64,
    /// Whether the current Jacobian was assembled in this step.
    fresh: bool,
    /// Whether to assemble a fresh Jacobian before the next update.
    refresh: bool,
}

impl Contraction {
    /// Computes the update `δ = A⁻¹R` into `ws.update`, refreshing the Jacobian when it is
    /// missing, grows the iteration, or contracts slowly; returns `‖δ‖∞` and the contraction
    /// `θ = ‖δ‖/‖δ_prev‖` (NaN for the first update with this Jacobian).
    fn update<L: Lagrangian>(
        &mut self,
        l: &L,
        alpha: f64,
        frame: Frame<'_>,
        z: &[f64],
        ws: &mut SeparableWorkspace,
        report: &mut NewtonReport,
    ) -> Result<(f64, f64), NewtonFailure> {
        let mut size = f64::NAN;
        for _attempt in 0..2 {
            if self.refresh {
                factor_jacobian(l, alpha, frame, z, ws).map_err(|pivot| {
                    NewtonFailure::Singular {
                        iteration: report.iterations,
                        pivot,
                    }
                })?;
                report.factorizations += 1;
                (self.fresh, self.previous) = (true, f64::NAN);
            }
            ws.update.copy_from_slice(&ws.residual);
            ws.lu.solve(&mut ws.update);
            size = max_norm(&ws.update);
            // A stale Jacobian that makes the iteration grow: discard the update and refresh.
            self.refresh = !self.fresh && size >= self.previous;
            if !self.refresh {
                break;
            }
        }
        let theta = size / self.previous;
        // A stale Jacobian that contracts slowly is replaced before the next update.
        self.refresh = !self.fresh && theta > THETA_REFRESH;
        self.previous = size;
        Ok((size, theta))
    }
}

/// Residual `R(Δ)` into `ws.residual` and `p_{k+1}` into `p_next` at the offset `delta`.
fn evaluate<L: Lagrangian>(
    l: &L,
    alpha: f64,
    frame: Frame<'_>,
    delta: &[f64],
    p_next: &mut [f64],
    ws: &mut SeparableWorkspace,
) -> Iterate {
    let Frame { t0, h, q0, p0 } = frame;
    node(alpha, q0, delta, &mut ws.node);
    l.potential_gradient(t0 + alpha * h, &ws.node, &mut ws.grad, &mut ws.scratch);
    if let Some(Some(mass)) = &ws.mass {
        mass.apply_over_h(delta, h, &mut ws.momentum);
    }
    let (w0, w1) = (h * (1.0 - alpha), h * alpha);
    let (mut residual, mut terms) = (0.0_f64, 0.0_f64);
    for i in 0..q0.len() {
        let (mv, g) = (ws.momentum[i], ws.grad[i]);
        let d_q0 = -mv - w0 * g;
        let r = d_q0 + p0[i];
        ws.residual[i] = r;
        p_next[i] = mv - w1 * g;
        residual = if r.is_nan() {
            f64::NAN
        } else {
            residual.max(r.abs())
        };
        terms = terms.max(d_q0.abs()).max(p0[i].abs());
    }
    Iterate {
        residual,
        scale: terms,
    }
}

/// Assembles `A = M/h + hα(1−α)∇²V` at the node of `delta` and factors it.
fn factor_jacobian<L: Lagrangian>(
    l: &L,
    alpha: f64,
    frame: Frame<'_>,
    delta: &[f64],
    ws: &mut SeparableWorkspace,
) -> Result<(), f64> {
    let Frame { t0, h, q0, .. } = frame;
    let n = q0.len();
    let Some(Some(mass)) = &ws.mass else {
        return Err(f64::NAN);
    };
    let dense = matches!(mass, Mass::Dense(_));
    let b = match l.potential_bandwidth() {
        Some(b) if !dense => b,
        _ => n.saturating_sub(1),
    };
    ws.hess.reshape(n, b);
    node(alpha, q0, delta, &mut ws.node);
    l.potential_hessian(t0 + alpha * h, &ws.node, &mut ws.hess);
    let c = h * alpha * (1.0 - alpha);
    let inv_h = 1.0 / h;
    for i in 0..n {
        for j in ws.hess.columns(i) {
            let m = match mass {
                Mass::Diagonal(d) => {
                    if i == j {
                        d[i]
                    } else {
                        0.0
                    }
                }
                Mass::Dense(m) => m[i * n + j],
            };
            let v = m * inv_h + c * ws.hess.get(i, j);
            ws.hess.set(i, j, v);
        }
    }
    ws.lu_h = None;
    ws.lu.factor(&ws.hess).map_err(|e| e.pivot)?;
    ws.lu_h = Some(h);
    Ok(())
}
