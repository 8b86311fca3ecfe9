//! The exact Jacobian of a variational step by the implicit function theorem.
//!
//! The step `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of [`crate::integrator::Integrator`] solves, for the offsets
//! `z = (Δ₁, …, Δ_s)` of the control points `Q_j = q_k + Δ_j` (DESIGN.md §3, [`crate::integrator::equations`]),
//!
//! ```text
//!     R₀(z; q_k, p_k) = p_k + ∂L_d/∂Q₀ + F₀ = 0,      R_j(z; q_k) = ∂L_d/∂Q_j + F_j = 0  (0 < j < s),
//! ```
//!
//! and sets `q_{k+1} = q_k + Δ_s`, `p_{k+1} = P(z; q_k) = ∂L_d/∂Q_s + F_s`. At the converged `z`,
//! differentiating `R = 0` gives ([MW01] §1.5; implicit function theorem)
//!
//! ```text
//!     dz/d(q_k, p_k) = −(∂R/∂z)⁻¹ ∂R/∂(q_k, p_k),
//!     dq_{k+1} = [I | 0] + dΔ_s,      dp_{k+1} = [∂P/∂q_k | 0] + ∂P/∂z · dz.
//! ```
//!
//! Everything is a second derivative of `L_d` (and a first derivative of the discrete forces)
//! with respect to *all* control points, including the `Q₀–Q₀` block the Newton step never
//! needs. In the variables `x = (q_k, Δ₁, …, Δ_s)` of [`crate::discrete::DiscreteAction::action`] one
//! hyper-dual evaluation with every variable seeded gives the full Hessian `∇²_x L_d` and the
//! force Jacobian; with `∂/∂Q_j = ∂/∂Δ_j` (j ≥ 1) and `∂/∂Q₀ = ∂/∂q − Σ_j ∂/∂Δ_j`, and since
//! `∂/∂q_k` at fixed offsets is `∂/∂x₀` itself, all blocks follow by sums of Hessian rows.
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).

use super::DifferentiableStep;
use crate::discrete::legendre::ActionAndForces;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::{StepError, StepFailure};
use crate::integrator::{Integrator, StepReport};
use crate::mechanics::{State, Unconstrained};
use crate::numerics::ad::{self, HessianParts};
use crate::numerics::dense::Lu;

/// Derivative blocks of the step equations, read from one full Hessian evaluation.
struct Blocks<'a> {
    parts: &'a HessianParts,
    n: usize,
    s: usize,
    forced: bool,
}

impl Blocks<'_> {
    fn width(&self) -> usize {
        (self.s + 1) * self.n
    }

    /// `∂(∂L_d/∂Q_i + F_i)_a / ∂x_c` for control point `i ∈ 0..=s`, component `a`.
    fn d_equation(&self, i: usize, a: usize, c: usize) -> f64 {
        let (n, w) = (self.n, self.width());
        let hess = |row: usize| self.parts.hess[row * w + c];
        let l = if i == 0 {
            hess(a) - (1..=self.s).map(|j| hess(j * n + a)).sum::<f64>()
        } else {
            hess(i * n + a)
        };
        let f = if self.forced {
            self.parts.jac_cols[(1 + i * n + a) * w + c]
        } else {
            0.0
        };
        l + f
    }
}

/// Writes `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` (row-major 2n × 2n) of the step from `(t₀, q₀)` with
/// converged control-point offsets `offsets = (Δ₁ … Δ_s)` into `jac`.
///
/// Errors with [`Error::SingularJacobian`] if `∂R/∂z` is singular (the step is not locally
/// unique, so its Jacobian is undefined).
pub fn step_jacobian<A: DiscreteAction, F: DiscreteForce>(
    action: &A,
    force: &F,
    (t0, h): (f64, f64),
    q0: &[f64],
    offsets: &[f64],
    jac: &mut [f64],
) -> Result<(), Error> {
    let n = action.dof();
    let s = action.internal_stages() + 1;
    let (sn, m) = (s * n, 2 * n);
    Error::check_len("offsets", offsets, sn)?;
    let x: Vec<f64> = q0.iter().chain(offsets).copied().collect();
    let f = ActionAndForces::new(action, force, (t0, h));
    let mut parts = HessianParts::default();
    ad::partial_hessian(&f, &x, 0..x.len(), 0..x.len(), &mut parts);
    let b = Blocks {
        parts: &parts,
        n,
        s,
        forced: force.is_active(),
    };
    // Equations R_r, r = i·n + a for control points i < s; unknowns z = x[n..].
    let a_mat: Vec<f64> = (0..sn * sn)
        .map(|k| b.d_equation(k / sn / n, (k / sn) % n, n + k % sn))
        .collect();
    let mut lu = Lu::new();
    lu.factor(&a_mat, sn).map_err(|e| {
        Error::Step(StepFailure {
            step: 0,
            t: t0,
            cause: StepError::SingularJacobian {
                iteration: 0,
                pivot: e.pivot,
            },
        })
    })?;
    // dz = −A⁻¹ [∂R/∂q | ∂R/∂p], column by column (sn × 2n, stored column-major in `dz`).
    let (mut dz, mut col, mut scratch) = (vec![0.0; sn * m], vec![0.0; sn], Vec::with_capacity(sn));
    for c in 0..m {
        for (r, x) in col.iter_mut().enumerate() {
            let (i, a) = (r / n, r % n);
            *x = -if c < n {
                b.d_equation(i, a, c)
            } else {
                f64::from(u8::from(i == 0 && a == c - n))
            };
        }
        lu.solve(&mut col, &mut scratch);
        dz[c * sn..(c + 1) * sn].copy_from_slice(&col);
    }
    for a in 0..n {
        for c in 0..m {
            let delta_s = dz[c * sn + (s - 1) * n + a];
            jac[a * m + c] = f64::from(u8::from(a == c)) + delta_s;
            let direct = if c < n { b.d_equation(s, a, c) } else { 0.0 };
            let through: f64 = (0..sn)
                .map(|r| b.d_equation(s, a, n + r) * dz[c * sn + r])
                .sum();
            jac[(n + a) * m + c] = direct + through;
        }
    }
    Ok(())
}

impl<A: DiscreteAction, F: DiscreteForce> DifferentiableStep for Integrator<A, F, Unconstrained> {
    fn dof(&self) -> usize {
        self.shape().n
    }

    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        Integrator::step(self, state, h)
    }

    fn step_with_jacobian(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let n = self.shape().n;
        Error::check_len("jacobian", jac, 4 * n * n)?;
        let (t0, q0) = (state.t, state.q.clone());
        let report = Integrator::step(self, state, h)?;
        let step = self.statistics().steps.saturating_sub(1);
        step_jacobian(
            self.action(),
            self.force(),
            (t0, h),
            &q0,
            self.stage_offsets(),
            jac,
        )
        .map_err(|e| match e {
            Error::Step(StepFailure {
                t,
                cause: StepError::SingularJacobian { pivot, .. },
                ..
            }) => Error::Step(StepFailure {
                step,
                t,
                cause: StepError::SingularJacobian {
                    iteration: report.iterations,
                    pivot,
                },
            }),
            other => other,
        })?;
        Ok(report)
    }
}
