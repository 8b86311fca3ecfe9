//! The exact Jacobian of a variational step by the implicit function theorem.
//!
//! The step `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of [`crate::integrator::Integrator`] solves, for the
//! offsets `z = (Δ₁, …, Δ_s)` of the control points `Q_j = q_k + Δ_j`
//! ([conventions](crate#conventions), `crate::integrator::equations`),
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
//! [MW01]: crate#references

use std::cell::RefCell;

use super::DifferentiableStep;
use crate::discrete::legendre::ActionAndForces;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::InputError;
use crate::error::{StepError, StepFailure};
use crate::holonomic::MomentumProjection;
use crate::integrator::{Integrator, StepReport};
use crate::mechanics::{Constraint, State};
use crate::numerics::ad::{self, HessianParts};
use crate::numerics::dense::Lu;
use crate::symmetry::StepSpan;

/// Derivative blocks of the step equations, read from one full Hessian evaluation.
///
/// The action has `dof = n + P` coordinates: `n` free ones, then `P` frozen ones (parameters,
/// whose offsets are zero; [`frozen_step_jacobian`]).
struct Blocks<'a> {
    parts: &'a HessianParts,
    /// Coordinates of the action (free and frozen).
    dof: usize,
    s: usize,
    forced: bool,
}

impl Blocks<'_> {
    fn width(&self) -> usize {
        (self.s + 1) * self.dof
    }

    /// `∂(∂L_d/∂Q_i + F_i)_a / ∂x_c` for control point `i ∈ 0..=s`, component `a`.
    fn d_equation(&self, i: usize, a: usize, c: usize) -> f64 {
        let (n, w) = (self.dof, self.width());
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
/// Errors with [`crate::error::StepError::SingularJacobian`] if `∂R/∂z` is singular (the step is
/// not locally unique, so its Jacobian is undefined).
pub fn step_jacobian<A: DiscreteAction, F: DiscreteForce>(
    action: &A,
    force: &F,
    t0: f64,
    h: f64,
    q0: &[f64],
    offsets: &[f64],
    jac: &mut [f64],
) -> Result<(), Error> {
    frozen_step_jacobian(action, force, StepSpan { t0, h }, q0, &[], offsets, jac)
}

/// The step Jacobian with frozen coordinates: `action` and `force` have `n + P` coordinates,
/// the first `n` stepped, the last `P` parameters `θ` held fixed (offsets zero). Writes
/// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` (row-major 2n × (2n + P)) into `jac`, from the free
/// offsets `offsets = (Δ₁ … Δ_s)` (length `s·n`).
///
/// The parameter columns are the `∂/∂x₀` columns of the frozen coordinates: with the offsets of
/// `θ` zero, `θ` enters the step equations exactly as `q_k` does, `∂R/∂θ = ∂R/∂x₀[θ]`, and the
/// implicit function theorem of the module documentation gives `dz/dθ = −(∂R/∂z)⁻¹ ∂R/∂θ`.
/// With `P = 0` this is [`step_jacobian`].
pub fn frozen_step_jacobian<A: DiscreteAction, F: DiscreteForce>(
    action: &A,
    force: &F,
    span: StepSpan,
    q0: &[f64],
    theta: &[f64],
    offsets: &[f64],
    jac: &mut [f64],
) -> Result<(), Error> {
    let StepSpan { t0, h } = span;
    let (n, np) = (q0.len(), theta.len());
    let dof = action.dof();
    let s = action.internal_stages() + 1;
    let (sn, m, cols) = (s * n, 2 * n, 2 * n + np);
    Error::check_len("q (free coordinates)", q0, dof.saturating_sub(np))?;
    Error::check_len("offsets", offsets, sn)?;
    Error::check_len("jacobian", jac, m * cols)?;
    WORKSPACE.with_borrow_mut(|w| {
        let Workspace {
            x,
            parts,
            a_mat,
            lu,
            dz,
            col,
            scratch,
        } = w;
        x.clear();
        x.extend(q0.iter().chain(theta));
        for j in 0..s {
            x.extend_from_slice(&offsets[j * n..(j + 1) * n]);
            x.extend(std::iter::repeat_n(0.0, np));
        }
        let f = ActionAndForces::new(action, force, t0, h);
        ad::partial_hessian(&f, x, 0..x.len(), 0..x.len(), parts);
        let b = Blocks {
            parts,
            dof,
            s,
            forced: force.is_active(),
        };
        // Free row r = i·n + a (control point i, component a) sits at i·dof + a in x.
        let at = |r: usize| (r / n) * dof + r % n;
        // Equations R_r, r = i·n + a for control points i < s; unknowns z = the free offsets.
        a_mat.clear();
        a_mat
            .extend((0..sn * sn).map(|k| b.d_equation(k / sn / n, (k / sn) % n, dof + at(k % sn))));
        lu.factor(a_mat, sn).map_err(|e| singular(t0, e.pivot))?;
        // The x-column of input column c: q_k (c < n), none for p_k, θ (c ≥ 2n).
        let x_col = |c: usize| match c {
            c if c < n => Some(c),
            c if c >= m => Some(n + c - m),
            _ => None,
        };
        // dz = −A⁻¹ [∂R/∂q | ∂R/∂p | ∂R/∂θ], column by column (sn × cols, column-major).
        dz.resize(sn * cols, 0.0);
        col.resize(sn, 0.0);
        for c in 0..cols {
            for (r, x) in col.iter_mut().enumerate() {
                let (i, a) = (r / n, r % n);
                *x = -match x_col(c) {
                    Some(xc) => b.d_equation(i, a, xc),
                    None => f64::from(u8::from(i == 0 && a == c - n)),
                };
            }
            lu.solve(col, scratch);
            dz[c * sn..(c + 1) * sn].copy_from_slice(col);
        }
        for a in 0..n {
            for c in 0..cols {
                let delta_s = dz[c * sn + (s - 1) * n + a];
                jac[a * cols + c] = f64::from(u8::from(a == c)) + delta_s;
                let direct = x_col(c).map_or(0.0, |xc| b.d_equation(s, a, xc));
                let through: f64 = (0..sn)
                    .map(|r| b.d_equation(s, a, dof + at(r)) * dz[c * sn + r])
                    .sum();
                jac[(n + a) * cols + c] = direct + through;
            }
        }
        Ok(())
    })
}

/// The error of a singular `∂R/∂z` (step index and iteration filled in by [`at_step`]).
fn singular(t: f64, pivot: f64) -> Error {
    Error::Step(StepFailure {
        step: 0,
        t,
        cause: StepError::SingularJacobian {
            iteration: 0,
            pivot,
        },
    })
}

/// The buffers of [`frozen_step_jacobian`], kept per thread so that a run of step Jacobians
/// (a tangent run, an adjoint's recomputed segment) allocates nothing after its first step.
#[derive(Debug, Default)]
struct Workspace {
    /// `x = (q_k, θ, Δ₁, 0, …, Δ_s, 0)`.
    x: Vec<f64>,
    /// The hyper-dual Hessian and force Jacobian.
    parts: HessianParts,
    /// `∂R/∂z` and its factorisation.
    a_mat: Vec<f64>,
    lu: Lu,
    /// `dz` (column-major), one right-hand side and the solver's scratch.
    dz: Vec<f64>,
    col: Vec<f64>,
    scratch: Vec<f64>,
}

thread_local! {
    static WORKSPACE: RefCell<Workspace> = RefCell::new(Workspace::default());
}

/// The error of an integrator whose constraints are active: the implicit function theorem
/// above differentiates the unconstrained step equations only.
pub(crate) fn constrained_step(constraints: usize) -> Error {
    Error::Input(InputError::InvalidOption {
        name: "constraints",
        value: constraints as f64,
        reason: "the step Jacobian is available for unconstrained steps only (no holonomic \
                 constraints)",
    })
}

/// Names the step index, time and Newton iteration count of the step in the
/// [`StepError::SingularJacobian`] of a step Jacobian (which knows neither); other errors pass.
pub(crate) fn at_step(step: usize, t: f64, iteration: usize) -> impl Fn(Error) -> Error {
    move |e| match e {
        Error::Step(StepFailure {
            cause: StepError::SingularJacobian { pivot, .. },
            ..
        }) => Error::Step(StepFailure {
            step,
            t,
            cause: StepError::SingularJacobian { iteration, pivot },
        }),
        other => other,
    }
}

/// Refuses an integrator whose steps keep no stage offsets to differentiate: the explicit path
/// of a composition keeps only the final offset.
pub(crate) fn check_stage_offsets<A, F, C, P>(
    integrator: &Integrator<A, F, C, P>,
) -> Result<(), Error>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    if integrator.is_explicit() && integrator.shape().s > 1 {
        return Err(Error::Input(InputError::InvalidOption {
            name: "fast_paths",
            value: 1.0,
            reason: "the explicit path of a composition keeps no stage offsets, so its step \
                     cannot be differentiated; build the integrator with with_fast_paths(false)",
        }));
    }
    Ok(())
}

/// Every integrator type, so that a certificate or a tangent run can use the very integrator
/// type of a run (one compiled integrator per rule and system); a step with active holonomic
/// constraints is refused (`constrained_step`), and so is the explicit path of a composition
/// (`check_stage_offsets`).
impl<A, F, C, P> DifferentiableStep for Integrator<A, F, C, P>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
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
        let shape = self.shape();
        if shape.d > 0 {
            return Err(constrained_step(shape.d));
        }
        let n = shape.n;
        Error::check_len("jacobian", jac, 4 * n * n)?;
        check_stage_offsets(self)?;
        let t0 = state.t;
        let report = self.step_keeping_start(state, h)?;
        let step = self.statistics().steps.saturating_sub(1);
        let result = match self.separable_jacobian(t0, h, jac) {
            Some(structured) => structured.map_err(|pivot| singular(t0, pivot)),
            None => step_jacobian(
                self.action(),
                self.force(),
                t0,
                h,
                self.step_start(),
                self.stage_offsets(),
                jac,
            ),
        };
        result.map_err(at_step(step, t0, report.iterations))?;
        Ok(report)
    }
}
