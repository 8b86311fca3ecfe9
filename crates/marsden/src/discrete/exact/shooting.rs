//! The Euler–Lagrange boundary value problem `q(t₀) = q₀, q(t₀ + h) = q₁` by shooting.
//!
//! Newton's method on the initial velocity: `r(v₀) = q(t₀ + h; q₀, v₀) − q₁ = 0`, with the
//! Jacobian `B = ∂q(t₀+h)/∂v₀` by central differences of the flow (step `ε^{1/3}` times the
//! velocity scale, relative accuracy ~1e-10, so Newton converges to round-off in one or two
//! more iterations than with the exact Jacobian). The flow is [`EulerLagrangeFlow`]. For `h`
//! below the first conjugate time the solution is unique near `(q₁ − q₀)/h` ([MW01] §1.6).
//!
//! [MW01]: crate#references

use super::flow::{EulerLagrangeFlow, FlowEnd};
use crate::error::Error;
use crate::error::SetupError;
use crate::mechanics::{Force, Lagrangian};
use crate::numerics::dense::{Lu, max_norm};

/// Most Newton iterations of the shooting method.
const MAX_ITERATIONS: usize = 30;

/// The solution of the boundary value problem over one step.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryValue {
    /// Initial velocity `v₀`.
    pub v0: Vec<f64>,
    /// Final velocity `v₁`.
    pub v1: Vec<f64>,
    /// The action `∫ L dt` along the solution: `L_d^E(q₀, q₁, h)`.
    pub action: f64,
    /// Newton iterations used.
    pub iterations: usize,
    /// `∂q(t₀+h)/∂v₀` at the solution (row-major n × n, central differences).
    pub b: Vec<f64>,
    /// `∂v(t₀+h)/∂v₀` at the solution (row-major n × n, central differences).
    pub d: Vec<f64>,
}

/// Velocity scale of the problem, for difference steps: the chord, the velocity, and
/// `max(|q|, 1)/|h|` (so a problem at rest still gets a usable difference step).
fn velocity_scale(q0: &[f64], q1: &[f64], h: f64, v: &[f64]) -> f64 {
    let chord = q0
        .iter()
        .zip(q1)
        .map(|(a, b)| (b - a).abs())
        .fold(0.0, crate::numerics::dense::max_or_nan)
        / h.abs();
    let positions = max_norm(q0).max(max_norm(q1)).max(1.0) / h.abs();
    chord.max(max_norm(v)).max(positions)
}

/// Central-difference derivatives `∂(q, v)(t₀+h)/∂x_a` for `x = v₀` (`of_velocity`) or `x = q₀`,
/// as two row-major n × n blocks `(∂q/∂x, ∂v/∂x)`; the difference step is `ε^{1/3}` times
/// `max(|x_a|, scale)`.
pub(crate) fn flow_derivatives<L: Lagrangian, F: Force>(
    flow: &EulerLagrangeFlow<L, F>,
    t0: f64,
    h: f64,
    q0: &[f64],
    v0: &[f64],
    of_velocity: bool,
    scale: f64,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let n = q0.len();
    let (mut dq, mut dv) = (vec![0.0; n * n], vec![0.0; n * n]);
    let (mut q, mut v) = (q0.to_vec(), v0.to_vec());
    let mut shot = |a: usize, value: f64| {
        let x = if of_velocity { &mut v } else { &mut q };
        let base = x[a];
        x[a] = value;
        let end = flow.advance(t0, h, &q, &v);
        let x = if of_velocity { &mut v } else { &mut q };
        x[a] = base;
        end
    };
    for a in 0..n {
        let base = if of_velocity { v0[a] } else { q0[a] };
        let delta = 6e-6 * base.abs().max(scale);
        let (up, down) = (base + delta, base - delta);
        let (plus, minus) = (shot(a, up)?, shot(a, down)?);
        for i in 0..n {
            dq[i * n + a] = (plus.q[i] - minus.q[i]) / (up - down);
            dv[i * n + a] = (plus.v[i] - minus.v[i]) / (up - down);
        }
    }
    Ok((dq, dv))
}

/// Solves the boundary value problem from the velocity guess `v_guess`.
///
/// The Jacobian is recomputed while the updates are large and kept (chord iterations) once
/// they are below `1e-6` of the velocity scale. Converged when the update is at round-off:
/// `|Δv₀| ≤ 4ε (|v| + |q|/h)`.
///
/// # Errors
/// [`crate::error::SetupError::ShootingDidNotConverge`] if Newton's method does not converge (or
/// its Jacobian is singular: `h` at a conjugate time), and the flow's errors.
pub fn solve<L: Lagrangian, F: Force>(
    flow: &EulerLagrangeFlow<L, F>,
    t0: f64,
    h: f64,
    q0: &[f64],
    q1: &[f64],
    v_guess: &[f64],
) -> Result<BoundaryValue, Error> {
    let n = q0.len();
    let mut v0 = v_guess.to_vec();
    let mut end = flow.advance(t0, h, q0, &v0)?;
    let mut residual = mismatch(&end, q1);
    let mut lu = Lu::new();
    let mut scratch = Vec::with_capacity(n);
    let mut jacobian: Option<(Vec<f64>, Vec<f64>)> = None;
    let mut last_update = f64::INFINITY;
    let failure = |iterations, residual| {
        Error::Setup(SetupError::ShootingDidNotConverge {
            h,
            iterations,
            residual,
        })
    };
    let floor =
        |v: &[f64]| 4.0 * f64::EPSILON * (max_norm(v) + max_norm(q0).max(max_norm(q1)) / h.abs());
    // The flow is accurate to a few `tolerance · max(1, |y|)`: a residual that no longer halves
    // below 64 times that is noise (and `finish` removes it to first order).
    let noise = 64.0 * flow.options().tolerance * max_norm(q1).max(1.0);
    for iteration in 0..MAX_ITERATIONS {
        let scale = velocity_scale(q0, q1, h, &v0);
        let (b, d) = match jacobian.take() {
            Some(bd) if last_update <= 1e-6 * scale => bd,
            _ => {
                let bd = flow_derivatives(flow, t0, h, q0, &v0, true, scale)?;
                lu.factor(&bd.0, n)
                    .map_err(|_| failure(iteration, max_norm(&residual)))?;
                bd
            }
        };
        let before = max_norm(&residual);
        if before == 0.0 {
            let shot = Shot {
                v0,
                end,
                iterations: iteration,
            };
            return Ok(finish(flow, t0 + h, q1, shot, b, d));
        }
        let mut update: Vec<f64> = residual.iter().map(|r| -r).collect();
        lu.solve(&mut update, &mut scratch);
        v0.iter_mut().zip(&update).for_each(|(v, du)| *v += du);
        end = flow.advance(t0, h, q0, &v0)?;
        residual = mismatch(&end, q1);
        last_update = max_norm(&update);
        let after = max_norm(&residual);
        if !last_update.is_finite() || !after.is_finite() {
            break;
        }
        // Converged: the update is at round-off, or the residual is at the flow's noise
        // level and no longer decreasing.
        let stalled = after <= noise && after > 0.5 * before;
        if last_update <= floor(&v0) || stalled {
            let shot = Shot {
                v0,
                end,
                iterations: iteration + 1,
            };
            return Ok(finish(flow, t0 + h, q1, shot, b, d));
        }
        jacobian = Some((b, d));
    }
    Err(failure(MAX_ITERATIONS, max_norm(&residual)))
}

fn mismatch(end: &FlowEnd, q1: &[f64]) -> Vec<f64> {
    end.q.iter().zip(q1).map(|(a, b)| a - b).collect()
}

/// The last shot of the Newton iteration.
struct Shot {
    /// The initial velocity `v₀` shot with.
    v0: Vec<f64>,
    /// Where the flow from `(q₀, v₀)` ended.
    end: FlowEnd,
    /// The Newton iterations taken.
    iterations: usize,
}

/// The solution from the last `shot` towards `q₁` at `t₁`, with the last residual
/// `r = q(h) − q₁` removed to first order: one more Newton update `δv₀ = −B⁻¹r` applied without
/// another flow, `v₁ += D δv₀` and, since `∂S/∂v₀ = p₁ᵀB` at fixed `q₀` (Hamilton's principal
/// function), `S −= ⟨p₁, r⟩` (`b` = `B = ∂q(h)/∂v₀`, `d` = `D = ∂v(h)/∂v₀`, row-major n × n).
fn finish<L: Lagrangian, F: Force>(
    flow: &EulerLagrangeFlow<L, F>,
    t1: f64,
    q1: &[f64],
    shot: Shot,
    b: Vec<f64>,
    d: Vec<f64>,
) -> BoundaryValue {
    let Shot {
        mut v0,
        end,
        iterations,
    } = shot;
    let n = v0.len();
    let r = mismatch(&end, q1);
    let mut dv0: Vec<f64> = r.iter().map(|x| -x).collect();
    let mut lu = Lu::new();
    let mut v1 = end.v;
    let mut action = end.action;
    if lu.factor(&b, n).is_ok() {
        lu.solve(&mut dv0, &mut Vec::with_capacity(n));
        let mut p1 = vec![0.0; n];
        crate::mechanics::momentum(flow.lagrangian(), t1, &end.q, &v1, &mut p1);
        for i in 0..n {
            v0[i] += dv0[i];
            v1[i] += (0..n).map(|j| d[i * n + j] * dv0[j]).sum::<f64>();
            action -= p1[i] * r[i];
        }
    }
    BoundaryValue {
        v0,
        v1,
        action,
        iterations,
        b,
        d,
    }
}
