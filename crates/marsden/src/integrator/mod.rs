//! The integrator: a discrete action (rule applied to `L`), discrete forces, constraints,
//! Newton's method and its buffers. One call to [`Integrator::step`] is one application of the
//! (forced, constrained) discrete Hamiltonian map `F̃_{L_d}: (q_k, p_k) ↦ (q_{k+1}, p_{k+1})`
//! ([MW01] §1.5, seed: *discrete Hamiltonian map*). With constraints, an optional
//! [`MomentumProjection`] (RATTLE, [`crate::holonomic::Rattle`]) is applied to the momenta after
//! the SHAKE solve ([`crate::holonomic`] describes the constrained scheme).
//!
//! [MW01]: crate#references

mod build;
mod checkpoint;
pub(crate) mod compensated;
pub(crate) mod equations;
mod explicit;
mod failure;
mod jacobian;
pub mod maps;
mod path;
mod predictor;
mod projection;
mod report;
pub(crate) mod small;

pub use checkpoint::IntegratorCheckpoint;
pub use equations::StepShape;
pub use report::{Statistics, StepReport};

use self::compensated::Compensation;
use self::path::Path;
use self::predictor::Predictor;
use self::small::dispatch::Dispatch;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::InputError;
use crate::holonomic::{MomentumProjection, NoProjection};
use crate::mechanics::{Constraint, NoForce, State, Unconstrained};
use crate::numerics::ad::HessianParts;
use crate::numerics::newton::{NewtonOptions, NewtonReport, NewtonWorkspace};
use crate::numerics::short;
use crate::separable::{ExplicitWorkspace, JacobianWorkspace, SeparableWorkspace};

/// Steps a discrete action `A` with discrete forces `F`, constraints `C` and a momentum
/// projection `P` (applied after each solved step; [`NoProjection`] by default).
///
/// ```
/// use marsden::{Integrator, Midpoint, Rule, State, systems::Pendulum};
///
/// let mut integrator = Integrator::new(Midpoint.discretize(Pendulum::default()));
/// let mut state = State { t: 0.0, q: vec![1.5], p: vec![0.0] };
/// let report = integrator.step(&mut state, 0.1).unwrap();
/// assert!(report.residual < 1e-12);
/// assert!((state.t - 0.1).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct Integrator<A, F = NoForce, C = Unconstrained, P = NoProjection> {
    action: A,
    force: F,
    constraint: C,
    projection: P,
    options: NewtonOptions,
    shape: StepShape,
    buffers: Buffers,
    predictor: Predictor,
    statistics: Statistics,
    /// The solver of the steps, chosen when the integrator is built ([`path`]).
    path: Path,
    /// Use the fast paths ([`crate::separable::explicit`], [`crate::separable::alpha`], [`crate::integrator::small::unconstrained`]) when
    /// the step allows them.
    fast_paths: bool,
    /// Compensated summation of the state update ([`crate::integrator::compensated`]).
    compensation: Compensation,
    /// The instruction set of the small kernels ([`crate::integrator::small::dispatch`]).
    dispatch: Dispatch,
}

#[derive(Debug, Clone, Default)]
struct Buffers {
    newton: NewtonWorkspace,
    parts: HessianParts,
    points: Vec<f64>,
    z: Vec<f64>,
    p_next: Vec<f64>,
    phi: Vec<f64>,
    dphi0: Vec<f64>,
    explicit: ExplicitWorkspace,
    separable: SeparableWorkspace,
    /// `q_{k+1}` for the momentum projection, and `φ`, `Dφ` there.
    q_next: Vec<f64>,
    phi_next: Vec<f64>,
    dphi_next: Vec<f64>,
    /// Whether `dphi0` already holds `Dφ` at the current `state.q` (computed by the projection
    /// of the previous step; checked against `q_next` before reuse).
    dphi0_current: bool,
    /// Projection multipliers `μ_k = ν/h` of the last step.
    mu: Vec<f64>,
    /// `μ_k / w`: the continuous multipliers at the end of the last step.
    lambda_end: Vec<f64>,
    /// The stage multipliers of the general path's evaluations.
    stage_multipliers: Vec<f64>,
    /// Scratch of the stage constraints (`X_i`, `φ`, `Dφ`).
    stage_scratch: Vec<f64>,
    /// `q_k` of a step taken for its Jacobian ([`jacobian`]).
    start: Vec<f64>,
    /// The buffers of the separable step Jacobian ([`crate::separable::jacobian`]).
    jacobian: JacobianWorkspace,
    /// Whether the start of each step is kept ([`Integrator::keep_step_starts`]): then
    /// `start_q` holds `q_k` after the step, and `p_next` holds `p_k`.
    keep_start: bool,
    start_q: Vec<f64>,
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Whether steps are compensated: asked for and unconstrained
    /// ([`Integrator::with_compensated_summation`]).
    pub fn is_compensated(&self) -> bool {
        self.compensation.enabled && self.shape.d == 0
    }

    /// The discrete action being stepped.
    pub fn action(&self) -> &A {
        &self.action
    }

    /// The discrete forces.
    pub fn force(&self) -> &F {
        &self.force
    }

    /// The constraints.
    pub fn constraint(&self) -> &C {
        &self.constraint
    }

    /// The momentum projection.
    pub fn projection(&self) -> &P {
        &self.projection
    }

    /// Sizes of the step's Newton system.
    pub fn shape(&self) -> StepShape {
        self.shape
    }

    /// The Newton options in use.
    pub fn options(&self) -> &NewtonOptions {
        &self.options
    }

    /// Work counters so far.
    pub fn statistics(&self) -> &Statistics {
        &self.statistics
    }

    /// Multipliers `λ_k` of the last completed step (length d; the constraint forces are
    /// `h Dφ(q_k)ᵀ λ_k`).
    pub fn multipliers(&self) -> &[f64] {
        let sn = self.shape.s * self.shape.n;
        self.buffers.z.get(sn..sn + self.shape.d).unwrap_or(&[])
    }

    /// Stage multipliers `Λ₁ … Λ_c` of the last completed step (length `c·d`; empty without
    /// stage constraints, [`DiscreteAction::constrained_stages`]).
    pub fn stage_multipliers(&self) -> &[f64] {
        let start = self.shape.s * self.shape.n + self.shape.d;
        self.buffers.z.get(start..).unwrap_or(&[])
    }

    /// Why this integrator's rule cannot impose its constraints at the order it has, if it
    /// cannot (a Gauss rule with constraints: the step would be order 2).
    pub fn stage_constraint_refusal(&self) -> Option<String> {
        if self.shape.d == 0 {
            return None;
        }
        self.action.constrained_stages().err()
    }

    /// The multipliers `λ(t_{k+1})` of the continuous equations at the state the last step
    /// reached, estimated as `μ_k / w` from the projection multipliers and the end weight `w`
    /// of the rule ([`DiscreteAction::end_weight`]); empty without an active projection.
    pub fn end_multipliers(&self) -> &[f64] {
        &self.buffers.lambda_end
    }

    /// Projection multipliers `μ_k` of the last completed step: the projection replaced
    /// `p̃_{k+1}` by `p_{k+1} = p̃_{k+1} − h Dφ(q_{k+1})ᵀ μ_k` (length d; empty without an active
    /// projection).
    pub fn projection_multipliers(&self) -> &[f64] {
        &self.buffers.mu
    }

    /// Offsets `Q_j − q_k` of the control points of the last completed step (`j = 1 … s`).
    pub fn stage_offsets(&self) -> &[f64] {
        let sn = self.shape.s * self.shape.n;
        self.buffers.z.get(..sn).unwrap_or(&[])
    }

    /// Forgets the step history, so the next predictor starts afresh (call when jumping to an
    /// unrelated state or changing the sign of `h`).
    pub fn reset(&mut self) {
        self.predictor = Predictor::default();
    }

    /// Gives the predictor the velocity at the next starting state (used for the first step
    /// after a reset: `Q_j ≈ q_k + c_j h v_k`).
    pub fn set_velocity_hint(&mut self, v: &[f64]) {
        self.predictor.set_velocity(v);
    }

    /// The step's Newton solve from the predicted `z`, its result checked (finite) and, when
    /// constrained, projected. Written out rather than chained through closures: the closures
    /// were compiled as calls of their own where the build does not optimise across crates.
    #[inline(always)]
    fn solve_checked(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
        step: usize,
    ) -> Result<NewtonReport, Error> {
        let report = match self.solve(z, state, h) {
            Ok(report) => report,
            Err(failure) => return Err(self.newton_error(failure, step, state, z)),
        };
        self.check_finite(z, step, state.t)?;
        if self.projection.is_active() {
            self.project(z, state, h, step)?;
        }
        Ok(report)
    }

    /// One step of the discrete Hamiltonian map from `state` (advanced in place by `h`).
    ///
    /// On error `state` is left unchanged.
    pub fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        let step = self.statistics.steps;
        Error::check_len("q", &state.q, self.shape.n)?;
        Error::check_len("p", &state.p, self.shape.n)?;
        if h == 0.0 || !h.is_finite() {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        if let Some(report) = self.step_explicit(state, h, step)? {
            return Ok(report);
        }
        let mut z = std::mem::take(&mut self.buffers.z);
        self.predictor.predict(&mut z, h, self.shape);
        let result = match self.solve_checked(&mut z, state, h, step) {
            Ok(report) => {
                self.predictor.record(&z, h);
                self.accept(&z, state, h);
                self.count(report);
                Ok(StepReport {
                    iterations: report.iterations,
                    residual: report.residual,
                })
            }
            Err(e) => {
                self.statistics.failed_steps += 1;
                Err(e)
            }
        };
        self.buffers.z = z;
        result
    }

    /// `steps` steps from `state` on the grid `t_k = t₀ + k h` (`t₀ = state.t`): in one loop
    /// when the step is explicit ([`crate::separable::explicit`], no per-step dispatch, copies or cache
    /// checks; the same numbers as repeated steps), else by repeated [`Integrator::step`].
    /// Returns the report of the last step.
    ///
    /// On error `state` holds the last good state, at its grid time, and the error names the
    /// failing step.
    ///
    /// ```
    /// use marsden::{Integrator, Rule, State, Trapezoid, systems::Kepler};
    ///
    /// let mut integrator = Integrator::new(Trapezoid.discretize(Kepler::default()));
    /// let mut state = State { t: 0.0, q: vec![1.0, 0.0], p: vec![0.0, 1.0] };
    /// integrator.advance(&mut state, 0.01, 1000)?;
    /// assert_eq!(integrator.statistics().steps, 1000);
    /// assert!((state.t - 10.0).abs() < 1e-12);
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn advance(
        &mut self,
        state: &mut State,
        h: f64,
        steps: usize,
    ) -> Result<StepReport, Error> {
        Error::check_len("q", &state.q, self.shape.n)?;
        Error::check_len("p", &state.p, self.shape.n)?;
        if h == 0.0 || !h.is_finite() {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        if self.is_explicit() {
            return self.advance_explicit(state, h, steps);
        }
        let t0 = state.t;
        let mut report = StepReport::default();
        for k in 1..=steps {
            report = self.step(state, h)?;
            state.t = t0 + k as f64 * h;
        }
        Ok(report)
    }

    /// Whether the steps take the explicit path ([`crate::separable::explicit`]): the action has an
    /// explicit form, nothing else (forces, constraints) enters the step, and the fast paths
    /// are on.
    pub fn is_explicit(&self) -> bool {
        self.path == Path::Explicit
    }

    /// Writes the converged step into `state`; when the starts of the steps are kept, the new
    /// momenta trade places with the old ones instead of being copied, and `q_k` is copied
    /// beside the update (the same numbers either way). Inlined into [`Integrator::step`], its
    /// one caller: a call of its own cost the pendulum's step 3 % (callgrind).
    #[inline(always)]
    fn accept(&mut self, z: &[f64], state: &mut State, h: f64) {
        let sn = self.shape.s * self.shape.n;
        let dq = &z[sn - self.shape.n..sn];
        let compensated = self.is_compensated();
        let b = &mut self.buffers;
        if compensated {
            self.compensation
                .update(&self.action, &self.force, state, h, &z[..sn]);
        } else if b.keep_start {
            short::copy(&mut b.start_q, &state.q);
            short::add(&mut state.q, dq);
            std::mem::swap(&mut state.p, &mut b.p_next);
        } else {
            short::add(&mut state.q, dq);
            short::copy(&mut state.p, &b.p_next);
        }
        state.t += h;
    }

    /// Keeps (`keep = true`) or stops keeping the start `(q_k, p_k)` of each step, so that
    /// whoever watches the steps one by one reads it after the step
    /// ([`Integrator::kept_start`]) instead of copying every state it may need again (an
    /// event detector needs the start of the step where `g` changed sign). Returns whether
    /// the starts are kept: not on the explicit path, nor with compensated summation, whose
    /// update of the state is its own.
    pub(crate) fn keep_step_starts(&mut self, keep: bool) -> bool {
        let kept = keep && !self.is_explicit() && !self.is_compensated();
        let b = &mut self.buffers;
        if kept && b.start_q.len() != self.shape.n {
            b.start_q.resize(self.shape.n, 0.0);
        }
        b.keep_start = kept;
        kept
    }

    /// The start `(q_k, p_k)` of the last step taken while the starts are kept
    /// ([`Integrator::keep_step_starts`]); `None` when they are not.
    pub(crate) fn kept_start(&self) -> Option<(&[f64], &[f64])> {
        let b = &self.buffers;
        b.keep_start.then_some((&b.start_q[..], &b.p_next[..]))
    }

    fn count(&mut self, report: NewtonReport) {
        let s = &mut self.statistics;
        s.steps += 1;
        s.newton_iterations += report.iterations;
        s.jacobian_factorizations += report.factorizations;
        s.max_newton_iterations = s.max_newton_iterations.max(report.iterations);
    }
}
