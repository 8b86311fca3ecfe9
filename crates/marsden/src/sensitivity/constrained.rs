//! The exact Jacobian of a constrained step (SHAKE + RATTLE) by the implicit function theorem.
//!
//! One step of [`Integrator`] with holonomic constraints `φ` and the [`Rattle`] projection
//! ([`crate::holonomic`], `crate::integrator::equations`) solves, for the control points
//! `Q₁ … Q_s` (`Q₀ = q_k`), the multiplier `λ` and the stage multipliers `Λ₁ … Λ_c`,
//!
//! ```text
//!     p_k + ∂Φ/∂Q₀ + F₀ = 0,     ∂Φ/∂Q_j + F_j = 0  (0 < j < s),
//!     φ(Q_s) = 0,                φ(X_i) = 0  (i = 1 … c),
//!     Φ = L_d(Q₀, …, Q_s) − h ⟨λ, φ(Q₀)⟩ − h Σ_i ⟨Λ_i, φ(X_i)⟩,
//! ```
//!
//! sets `q_{k+1} = Q_s`, `p̃_{k+1} = ∂Φ/∂Q_s + F_s`, and projects `p̃_{k+1}` onto `T*N`
//! (`super::projection`). Writing these equations as `R(y; q_k, p_k) = 0` with
//! `y = (Q₁, …, Q_s, λ, Λ)`, the implicit function theorem at the converged step gives
//! ([MW01] §1.5, §3.5; [LMO08] §3)
//!
//! ```text
//!     dy/d(q_k, p_k) = −(∂R/∂y)⁻¹ ∂R/∂(q_k, p_k),      dq_{k+1} = dQ_s,
//!     dp̃_{k+1} = ∂(∂Φ/∂Q_s + F_s)/∂q_k dq_k + ∂(∂Φ/∂Q_s + F_s)/∂y · dy,
//! ```
//!
//! where `∂R/∂y` is the Newton matrix of the step (curvature of the constraints included,
//! through the multipliers in `Φ`). All blocks come from one hyper-dual evaluation of
//! `(Φ, F, φ(Q_s), φ(X_i))` over the variables `x = (Q₀, Q₁ … Q_s, λ, Λ)`, all seeded: the
//! Hessian of `Φ` gives the momentum rows (with `−h Dφ(q_k)ᵀ` in the `λ` columns and
//! `−h ∂φ(X_i)/∂Q_j` in the `Λ_i` columns), the first derivatives of `F` and `φ` the rest.
//! The offsets `Δ_j = Q_j − q_k` the integrator stores are shifted inside the evaluation so
//! that the derivative of slot `j` is `∂/∂Q_j` at fixed other points, as in
//! `crate::integrator::equations`. Without constraints (`d = 0`) this is the unconstrained
//! step Jacobian of [`crate::analysis::certificate::variational`].
//!
//! ## Tangent vectors of `T*N`
//!
//! The step equations are defined for any `(q_k, p_k)` near `T*N` (they impose `φ = 0` at the
//! new point only), so the matrix written here is the derivative of that extension of the map,
//! a full `2n × 2n` matrix. Only its action on tangent vectors of `T*N` at `(q_k, p_k)` —
//! `Dφ(q_k) δq = 0` and `δ(Dφ(q) FH(q, p)) = 0` — is the derivative of the run's map on the
//! constraint manifold; applied to such vectors it returns tangent vectors of `T*N` at
//! `(q_{k+1}, p_{k+1})`, and restricted to them it preserves the canonical form ([LR04] §7.3).
//! Components normal to `T*N` (e.g. from finite differences of unprojected initial data) have
//! no meaning for the constrained dynamics.
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references
//! [LR04]: crate#references

use std::cell::RefCell;

use super::projection::{ProjectionWorkspace, projection_jacobian};
use super::step::SensitiveStep;
use crate::analysis::certificate::DifferentiableStep;
use crate::analysis::certificate::variational::{at_step, check_stage_offsets};
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::{Error, StepError, StepFailure};
use crate::holonomic::{MomentumProjection, Rattle};
use crate::integrator::{Integrator, StepReport};
use crate::mechanics::{Constraint, Lagrangian, State};
use crate::numerics::ad::{self, HessianParts, MultiFunction};
use crate::numerics::dense::Lu;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// Inline capacity for the offsets of a step (`s·n`).
const OFFSETS: usize = 16;

/// Sizes of a constrained step.
#[derive(Debug, Clone, Copy)]
struct Layout {
    n: usize,
    s: usize,
    d: usize,
    stages: usize,
    forced: bool,
    /// Parameters `P` (frozen coordinates of the model after the `n` free ones).
    params: usize,
}

impl Layout {
    /// Variables `x = (Q₀ … Q_s, λ, Λ, θ)`.
    fn width(&self) -> usize {
        self.n + self.unknowns() + self.params
    }
    /// Unknowns `y = (Q₁ … Q_s, λ, Λ)`: the variables after `Q₀`, before `θ`.
    fn unknowns(&self) -> usize {
        self.s * self.n + self.d * (1 + self.stages)
    }
    /// Coordinates of the model: `n` free, then `P` parameters.
    fn coordinates(&self) -> usize {
        self.n + self.params
    }
    fn forces(&self) -> usize {
        if self.forced {
            (self.s + 1) * self.n
        } else {
            0
        }
    }
}

/// `(Φ, F, φ(Q_s), φ(X₁) … φ(X_c))` of one step as a function of `x = (q_k, Δ, λ, Λ)`.
struct AugmentedStep<'a, A, F, C> {
    action: &'a A,
    force: &'a F,
    constraint: &'a C,
    t0: f64,
    h: f64,
    layout: Layout,
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> MultiFunction
    for AugmentedStep<'_, A, F, C>
{
    fn inputs(&self) -> usize {
        self.layout.width()
    }
    fn outputs(&self) -> usize {
        let l = self.layout;
        1 + l.forces() + l.d * (1 + l.stages)
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let l = self.layout;
        let (n, sn, big) = (l.n, l.s * l.n, l.coordinates());
        let (q0, rest) = x.split_at(n);
        let (offsets, rest) = rest.split_at(sn);
        let (multipliers, theta) = rest.split_at(l.d * (1 + l.stages));
        let zero = S::from(0.0);
        // The model's point `(q₀, θ)` and offsets `(Δ_j − (q₀ − re q₀), 0)`: same real part,
        // derivatives taken with `Q_j = q₀ + Δ_j` held fixed; `θ` never moves.
        let point = |i: usize| if i < n { q0[i] } else { theta[i - n] };
        let shifted = |i: usize| {
            let (j, a) = (i / big, i % big);
            if a < n {
                offsets[j * n + a] + (S::from(q0[a].re()) - q0[a])
            } else {
                zero
            }
        };
        let mut q0 = Buffer::<S, NODE>::empty();
        let q0 = q0.from_fn(big, zero, point);
        let mut offsets = Buffer::<S, OFFSETS>::empty();
        let offsets = offsets.from_fn(l.s * big, zero, shifted);
        self.evaluate(q0, offsets, multipliers, out);
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint> AugmentedStep<'_, A, F, C> {
    /// `(Φ, F, φ(Q_s), φ(X_i))` at the model's point `q0` and `offsets` (`n + P` per point).
    fn evaluate<S: Scalar>(&self, q0: &[S], offsets: &[S], multipliers: &[S], out: &mut [S]) {
        let l = self.layout;
        let (n, d, big) = (l.n, l.d, l.coordinates());
        let zero = S::from(0.0);
        out[0] = self.action.action(self.t0, self.h, q0, offsets);
        let nf = l.forces();
        if nf > 0 {
            // The forces on the free coordinates (those on θ are zero and not equations).
            let mut all = Buffer::<S, OFFSETS>::empty();
            let all = all.filled((l.s + 1) * big, zero);
            self.force.discrete_force(self.t0, self.h, q0, offsets, all);
            for j in 0..=l.s {
                out[1 + j * n..1 + (j + 1) * n].copy_from_slice(&all[j * big..j * big + n]);
            }
        }
        if d == 0 {
            return;
        }
        let first = 1 + nf;
        // −h ⟨λ, φ(Q₀)⟩, computed in the slot of φ(Q_s) before it is filled.
        self.constraint.constraint(q0, &mut out[first..first + d]);
        for c in 0..d {
            out[0] -= out[first + c] * multipliers[c] * S::from(self.h);
        }
        let last = &offsets[(l.s - 1) * big..];
        let mut q_end = Buffer::<S, NODE>::empty();
        let q_end = q_end.from_fn(big, zero, |i| q0[i] + last[i]);
        self.constraint
            .constraint(q_end, &mut out[first..first + d]);
        for i in 0..l.stages {
            let block = first + (1 + i) * d;
            let mut point = Buffer::<S, NODE>::empty();
            let point = point.filled(big, zero);
            self.action.stage_point(i, q0, offsets, point);
            self.constraint
                .constraint(point, &mut out[block..block + d]);
            for c in 0..d {
                out[0] -= out[block + c] * multipliers[(1 + i) * d + c] * S::from(self.h);
            }
        }
    }
}

/// The derivative blocks of one full hyper-dual evaluation of [`AugmentedStep`].
struct Blocks<'a> {
    parts: &'a HessianParts,
    layout: Layout,
}

impl Blocks<'_> {
    /// `∂(∂Φ/∂Q_j + F_j)_a / ∂x_v`.
    fn d_point(&self, j: usize, a: usize, v: usize) -> f64 {
        let (l, w) = (self.layout, self.layout.width());
        let row = j * l.n + a;
        let force = if l.forced {
            self.parts.jac_cols[(1 + row) * w + v]
        } else {
            0.0
        };
        self.parts.hess[row * w + v] + force
    }

    /// `∂R_r/∂x_v` for equation `r` of `R(y; q_k, p_k)` (momentum rows, then constraint rows).
    fn d_equation(&self, r: usize, v: usize) -> f64 {
        let (l, w) = (self.layout, self.layout.width());
        let sn = l.s * l.n;
        if r < sn {
            self.d_point(r / l.n, r % l.n, v)
        } else {
            self.parts.jac_cols[(1 + l.forces() + r - sn) * w + v]
        }
    }
}

/// Buffers of [`shake_jacobian`], kept per thread so a run allocates only on its first step.
#[derive(Debug, Default)]
struct Workspace {
    /// The converged unknowns `z` and `x = (q_k, z)`.
    z: Vec<f64>,
    x: Vec<f64>,
    parts: HessianParts,
    a_mat: Vec<f64>,
    lu: Lu,
    /// `dy` column-major (unknowns × 2n), one right-hand side, the solver's scratch.
    dy: Vec<f64>,
    col: Vec<f64>,
    scratch: Vec<f64>,
    /// `∂(q_{k+1}, p̃_{k+1})/∂(q_k, p_k)` and the projection's `∂p_{k+1}/∂(q_{k+1}, p̃_{k+1})`.
    shake: Vec<f64>,
    /// The projection's point `(q_{k+1}, θ)`.
    point: Vec<f64>,
    projection: ProjectionWorkspace,
}

thread_local! {
    static WORKSPACE: RefCell<Workspace> = RefCell::new(Workspace::default());
}

/// Writes `∂(q_{k+1}, p̃_{k+1})/∂(q_k, p_k, θ)` (row-major 2n × (2n + P)) of the SHAKE step
/// from `(t₀, q_k, θ)` with converged unknowns `z = (Δ₁ … Δ_s, λ, Λ₁ … Λ_c)` into `ws.shake`.
///
/// `θ` enters the step equations as a variable held fixed, so its columns are
/// `dy/dθ = −(∂R/∂y)⁻¹ ∂R/∂θ` beside those of `(q_k, p_k)`.
fn shake_jacobian<A: DiscreteAction, F: DiscreteForce, C: Constraint>(
    step: &AugmentedStep<'_, A, F, C>,
    q0: &[f64],
    theta: &[f64],
    z: &[f64],
    ws: &mut Workspace,
) -> Result<(), Error> {
    let l = step.layout;
    let (n, sn, w, u) = (l.n, l.s * l.n, l.width(), l.unknowns());
    let (m, cols) = (2 * n, 2 * n + l.params);
    Error::check_len("step unknowns", z, u)?;
    Error::check_len("parameters", theta, l.params)?;
    ws.x.clear();
    ws.x.extend(q0.iter().chain(z).chain(theta));
    ad::partial_hessian(step, &ws.x, 0..w, 0..w, &mut ws.parts);
    let b = Blocks {
        parts: &ws.parts,
        layout: l,
    };
    ws.a_mat.clear();
    ws.a_mat
        .extend((0..u * u).map(|k| b.d_equation(k / u, n + k % u)));
    ws.lu.factor(&ws.a_mat, u).map_err(|e| {
        Error::Step(StepFailure {
            step: 0,
            t: step.t0,
            cause: StepError::SingularJacobian {
                iteration: 0,
                pivot: e.pivot,
            },
        })
    })?;
    // The x-column of input column c: q_k (c < n), none for p_k, θ (c ≥ 2n, after y).
    let x_col = |c: usize| match c {
        c if c < n => Some(c),
        c if c >= m => Some(n + u + c - m),
        _ => None,
    };
    // dy = −(∂R/∂y)⁻¹ [∂R/∂q_k | ∂R/∂p_k | ∂R/∂θ]; p_k enters the first n rows with the identity.
    ws.dy.resize(u * cols, 0.0);
    ws.col.resize(u, 0.0);
    for c in 0..cols {
        for (r, entry) in ws.col.iter_mut().enumerate() {
            *entry = -match x_col(c) {
                Some(xc) => b.d_equation(r, xc),
                None => f64::from(u8::from(r == c - n)),
            };
        }
        ws.lu.solve(&mut ws.col, &mut ws.scratch);
        ws.dy[c * u..(c + 1) * u].copy_from_slice(&ws.col);
    }
    ws.shake.resize(m * cols, 0.0);
    for a in 0..n {
        for c in 0..cols {
            // Q_s is unknown (s − 1)·n + a.
            ws.shake[a * cols + c] = ws.dy[c * u + sn - n + a];
            let direct = x_col(c).map_or(0.0, |xc| b.d_point(l.s, a, xc));
            let through: f64 = (0..u)
                .map(|r| b.d_point(l.s, a, n + r) * ws.dy[c * u + r])
                .sum();
            ws.shake[(n + a) * cols + c] = direct + through;
        }
    }
    Ok(())
}

/// The model a constrained step is differentiated with: the run's own discrete action,
/// forces, constraints and projection Lagrangian (`θ` empty), or those of a parametric model
/// on `ℝⁿ⁺ᴾ` with its parameter values `θ` ([`super::parametric::Frozen`]).
pub(super) struct Model<'a, A, F, C, L> {
    pub action: &'a A,
    pub force: &'a F,
    pub constraint: &'a C,
    pub lagrangian: &'a L,
    pub theta: &'a [f64],
}

/// The step a constrained run has just taken: from `(t₀, q₀)` with step `h` to `state`, in
/// `iterations` Newton iterations.
pub(super) struct TakenStep<'a> {
    /// The start time `t₀`.
    pub t0: f64,
    /// The step `h`.
    pub h: f64,
    /// The start positions `q₀`.
    pub q0: &'a [f64],
    /// The state the step ended in.
    pub state: &'a State,
    /// The Newton iterations of the step (for the error's report).
    pub iterations: usize,
}

/// After `run` took the step `taken` (from `(t₀, q₀)` with step `h` to `state`), writes
/// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k, θ)` (row-major 2n × (2n + P)) of that step into `jac`:
/// SHAKE's Jacobian ([`shake_jacobian`]), then the projection's ([`projection_jacobian`]).
/// `run` must have active constraints.
pub(super) fn constrained_jacobian<A, F, C, L, RA, RF, RC, RL, RC2>(
    run: &Integrator<RA, RF, RC, Rattle<RL, RC2>>,
    model: &Model<'_, A, F, C, L>,
    taken: TakenStep<'_>,
    jac: &mut [f64],
) -> Result<(), Error>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    L: Lagrangian,
    RA: DiscreteAction,
    RF: DiscreteForce,
    RC: Constraint,
    RL: Lagrangian,
    RC2: Constraint,
{
    let TakenStep {
        t0,
        h,
        q0,
        state,
        iterations,
    } = taken;
    let shape = run.shape();
    let (n, np) = (shape.n, model.theta.len());
    let (m, cols) = (2 * n, 2 * n + np);
    Error::check_len("jacobian", jac, m * cols)?;
    let layout = Layout {
        n,
        s: shape.s,
        d: shape.d,
        stages: shape.stages,
        forced: shape.forced,
        params: np,
    };
    let step = AugmentedStep {
        action: model.action,
        force: model.force,
        constraint: model.constraint,
        t0,
        h,
        layout,
    };
    let index = run.statistics().steps.saturating_sub(1);
    let rename = at_step(index, t0, iterations);
    WORKSPACE.with_borrow_mut(|ws| {
        let mut z = std::mem::take(&mut ws.z);
        z.clear();
        z.extend(
            (run.stage_offsets().iter())
                .chain(run.multipliers())
                .chain(run.stage_multipliers()),
        );
        let solved = shake_jacobian(&step, q0, model.theta, &z, ws);
        ws.z = z;
        solved.map_err(&rename)?;
        let projection = run.projection();
        if !projection.is_active() {
            jac.copy_from_slice(&ws.shake);
            return Ok(());
        }
        let mut point = std::mem::take(&mut ws.point);
        point.clear();
        point.extend(state.q.iter().chain(model.theta));
        let pj = projection_jacobian(
            model.lagrangian,
            model.constraint,
            t0 + h,
            &point,
            projection.velocity(),
            projection.multipliers(),
            &mut ws.projection,
        );
        ws.point = point;
        let pj = pj.map_err(&rename)?;
        // Rows q: SHAKE's; rows p: ∂p/∂(q_{k+1}, p̃_{k+1}) · SHAKE's + ∂p/∂θ.
        jac[..n * cols].copy_from_slice(&ws.shake[..n * cols]);
        for a in 0..n {
            for c in 0..cols {
                let through: f64 = (0..m)
                    .map(|r| pj[a * cols + r] * ws.shake[r * cols + c])
                    .sum();
                jac[(n + a) * cols + c] = if c >= m {
                    through + pj[a * cols + c]
                } else {
                    through
                };
            }
        }
        Ok(())
    })
}

impl<A, F, C, L, C2> SensitiveStep for Integrator<A, F, C, Rattle<L, C2>>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    L: Lagrangian,
    C2: Constraint,
{
    fn carried(&self) -> Option<crate::integrator::IntegratorCheckpoint> {
        Some(self.checkpoint())
    }

    fn restore_carried(
        &mut self,
        carried: &crate::integrator::IntegratorCheckpoint,
    ) -> Result<(), Error> {
        self.restore(carried)
    }

    /// One SHAKE + RATTLE step and its Jacobian (see the module documentation: meaningful on
    /// tangent vectors of `T*N`).
    fn step_with_sensitivity(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        if self.shape().d == 0 {
            // No constraint is active, so the projection is not either: the step is the
            // unconstrained one, differentiated as such (fewer variables, less round-off).
            return self.step_with_jacobian(state, h, jac);
        }
        let n = self.shape().n;
        Error::check_len("jacobian", jac, 4 * n * n)?;
        check_stage_offsets(self)?;
        let t0 = state.t;
        let report = self.step_keeping_start(state, h)?;
        let model = Model {
            action: self.action(),
            force: self.force(),
            constraint: self.constraint(),
            lagrangian: self.projection().lagrangian(),
            theta: &[],
        };
        let taken = TakenStep {
            t0,
            h,
            q0: self.step_start(),
            state: &*state,
            iterations: report.iterations,
        };
        constrained_jacobian(self, &model, taken, jac)?;
        Ok(report)
    }
}
