//! The integrator: a discrete action (rule applied to `L`), discrete forces, constraints,
//! Newton's method and its buffers. One call to [`Integrator::step`] is one application of the
//! (forced, constrained) discrete Hamiltonian map `F̃_{L_d}: (q_k, p_k) ↦ (q_{k+1}, p_{k+1})`
//! ([MW01] §1.5, seed: *discrete Hamiltonian map*). With constraints, an optional
//! [`MomentumProjection`] (RATTLE, [`crate::holonomic::Rattle`]) is applied to the momenta after
//! the SHAKE solve ([`crate::holonomic`] describes the constrained scheme).
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001).

pub(crate) mod compensated;
pub(crate) mod equations;
mod explicit;
mod failure;
pub mod maps;
mod path;
mod predictor;
mod projection;
mod report;
pub(crate) mod small;

pub use equations::StepShape;
pub use report::{Statistics, StepReport};

use self::compensated::Compensation;
use self::path::{Path, separable_applies};
use self::predictor::Predictor;
use self::small::dispatch::Dispatch;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::error::InputError;
use crate::holonomic::{MomentumProjection, NoProjection};
use crate::mechanics::{Constraint, NoForce, State, Unconstrained};
use crate::numerics::ad::HessianParts;
use crate::numerics::newton::{NewtonOptions, NewtonReport, NewtonWorkspace};
use crate::separable::{ExplicitWorkspace, SeparableWorkspace};

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
}

impl<A: DiscreteAction> Integrator<A> {
    /// An unforced, unconstrained integrator with default Newton options.
    pub fn new(action: A) -> Self {
        let shape = StepShape {
            n: action.dof(),
            s: action.internal_stages() + 1,
            d: 0,
            forced: false,
            stages: 0,
        };
        Integrator {
            action,
            force: NoForce,
            constraint: Unconstrained,
            projection: NoProjection,
            options: NewtonOptions::default(),
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics: Statistics::default(),
            path: Path::General,
            fast_paths: true,
            compensation: Compensation::default(),
            dispatch: Dispatch::detect(),
        }
        .with_path()
    }
}

impl<A: DiscreteAction, F: DiscreteForce, C: Constraint, P: MomentumProjection>
    Integrator<A, F, C, P>
{
    /// Adds discrete forces (replacing any previous ones).
    pub fn with_force<F2: DiscreteForce>(self, force: F2) -> Integrator<A, F2, C, P> {
        let shape = StepShape {
            forced: force.is_active(),
            ..self.shape
        };
        let switches = self.switches();
        let parts = (self.action, force, self.constraint, self.projection);
        Integrator::assemble(parts, shape, self.options, self.statistics, switches)
    }

    /// Adds holonomic constraints (replacing any previous ones), imposed at the step's end and
    /// at the action's stage points ([`DiscreteAction::constrained_stages`]). A rule without
    /// stage constraints (Gauss) imposes them at the end only, which limits the order to 2:
    /// [`crate::run::Problem`] refuses it ([`Integrator::stage_constraint_refusal`]).
    pub fn with_constraint<C2: Constraint>(self, constraint: C2) -> Integrator<A, F, C2, P> {
        let d = constraint.count();
        let stages = if d > 0 {
            self.action.constrained_stages().unwrap_or(0)
        } else {
            0
        };
        let shape = StepShape {
            d,
            stages,
            ..self.shape
        };
        let switches = self.switches();
        let parts = (self.action, self.force, constraint, self.projection);
        Integrator::assemble(parts, shape, self.options, self.statistics, switches)
    }

    /// Adds a momentum projection applied after every solved step (replacing any previous one),
    /// e.g. [`crate::holonomic::Rattle`] for constrained systems.
    pub fn with_projection<P2: MomentumProjection>(
        self,
        projection: P2,
    ) -> Integrator<A, F, C, P2> {
        Integrator {
            action: self.action,
            force: self.force,
            constraint: self.constraint,
            projection,
            options: self.options,
            shape: self.shape,
            buffers: self.buffers,
            predictor: self.predictor,
            statistics: self.statistics,
            path: self.path,
            fast_paths: self.fast_paths,
            compensation: self.compensation,
            dispatch: self.dispatch,
        }
    }

    /// An integrator of new parts with fresh buffers, keeping the options, counters and
    /// switches of the one it replaces; its path is chosen anew.
    fn assemble(
        (action, force, constraint, projection): (A, F, C, P),
        shape: StepShape,
        options: NewtonOptions,
        statistics: Statistics,
        (fast_paths, compensation, dispatch): (bool, Compensation, Dispatch),
    ) -> Self {
        Integrator {
            action,
            force,
            constraint,
            projection,
            options,
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics,
            path: Path::General,
            fast_paths,
            compensation,
            dispatch,
        }
        .with_path()
    }

    /// The switches a rebuilt integrator keeps.
    fn switches(&self) -> (bool, Compensation, Dispatch) {
        (self.fast_paths, self.compensation.clone(), self.dispatch)
    }

    /// Chooses the path of the steps ([`Path::choose`]).
    fn with_path(mut self) -> Self {
        let (shape, fast, compensated) = (self.shape, self.fast_paths, self.compensation.enabled);
        let explicit = self.action.explicit().is_some();
        let (action, workspace) = (&self.action, &mut self.buffers.separable);
        self.path = Path::choose(shape, fast, compensated, explicit, || {
            separable_applies(action, workspace)
        });
        self
    }

    /// Sets the Newton options (validated).
    pub fn with_options(mut self, options: NewtonOptions) -> Result<Self, Error> {
        options.validate()?;
        self.options = options;
        Ok(self)
    }

    /// Whether to use the fast paths (default: true): the explicit Störmer–Verlet step of the
    /// trapezoid rule on separable Lagrangians ([`crate::separable::explicit`]), the Newton step with
    /// Jacobian `M/h + hα(1−α)∇²V` of the α rules on separable Lagrangians
    /// ([`crate::separable::alpha`]) — both only without forces and constraints — and the statically
    /// sized Newton steps for small systems ([`crate::integrator::small::unconstrained`], [`crate::integrator::small::constrained`]).
    /// The general path solves the same equations (tests: equal to round-off); switching is
    /// for testing and measurement.
    pub fn with_fast_paths(mut self, enabled: bool) -> Self {
        self.fast_paths = enabled;
        self.with_path()
    }

    /// Whether the small kernels ([`crate::integrator::small::unconstrained`], [`crate::integrator::small::constrained`]) may run in code
    /// compiled for x86-64-v3 (AVX2, FMA) when the CPU has it (default: true; chosen at run
    /// time, [`crate::integrator::small::dispatch`]). Both give the same bits; switch it off for tools that do not
    /// decode every AVX instruction (valgrind 3.19) or to measure the difference.
    ///
    /// ```
    /// use marsden::{Integrator, Midpoint, Rule, State, systems::DoublePendulum};
    ///
    /// let mut wide = Integrator::new(Midpoint.discretize(DoublePendulum::default()));
    /// let mut baseline = Integrator::new(Midpoint.discretize(DoublePendulum::default()))
    ///     .with_wide_instructions(false);
    /// let start = State { t: 0.0, q: vec![1.0, 0.5], p: vec![0.0, 0.0] };
    /// let (mut a, mut b) = (start.clone(), start);
    /// wide.advance(&mut a, 0.01, 100)?;
    /// baseline.advance(&mut b, 0.01, 100)?;
    /// assert_eq!(a.q, b.q);
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn with_wide_instructions(mut self, enabled: bool) -> Self {
        self.dispatch = if enabled {
            Dispatch::detect()
        } else {
            Dispatch::baseline()
        };
        self
    }

    /// Whether to add each step's increments to the state with compensated summation
    /// (default: false; [`crate::integrator::compensated`]). For long runs of high-order rules, whose
    /// truncation error is below the rounding error of `q + Δ`: over 10⁵ steps of Kepler's
    /// problem gauss-4 keeps the angular momentum to 1.4e-15 instead of 1.6e-11. Costs one
    /// gradient of the discrete action per step (`⌈n/8⌉` dual evaluations of the action, so
    /// think twice for large `n`; measured costs in BENCHMARKS.md), and the explicit
    /// run loop is not used (the explicit step of the trapezoid rule goes through Newton's
    /// method). Constrained steps are not compensated.
    ///
    /// ```
    /// use marsden::discrete::rules::Galerkin;
    /// use marsden::{Integrator, Rule, State, systems::Kepler};
    ///
    /// let rule = Galerkin::gauss(4)?;
    /// let mut integrator =
    ///     Integrator::new(rule.discretize(Kepler::default())).with_compensated_summation(true);
    /// let mut state = State { t: 0.0, q: vec![0.4, 0.0], p: vec![0.0, 2.0] };
    /// integrator.advance(&mut state, 0.05, 100)?;
    /// assert!(integrator.is_compensated());
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn with_compensated_summation(mut self, enabled: bool) -> Self {
        self.compensation.enabled = enabled;
        self.with_path()
    }

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
        let outcome = self
            .solve(&mut z, state, h)
            .map_err(|failure| self.newton_error(failure, step, state, &z))
            .and_then(|report| self.check_finite(&z, step, state.t).map(|_| report))
            .and_then(|report| self.project(&z, state, h, step).map(|_| report));
        let result = match outcome {
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

    /// Writes the converged step into `state`.
    fn accept(&mut self, z: &[f64], state: &mut State, h: f64) {
        let sn = self.shape.s * self.shape.n;
        if self.is_compensated() {
            self.compensation.update(
                (&self.action, &self.force),
                (state.t, h),
                (&mut state.q, &mut state.p),
                &z[..sn],
            );
        } else {
            let delta = &z[sn - self.shape.n..sn];
            state.q.iter_mut().zip(delta).for_each(|(q, d)| *q += d);
            state.p.copy_from_slice(&self.buffers.p_next);
        }
        state.t += h;
    }

    fn count(&mut self, report: NewtonReport) {
        let s = &mut self.statistics;
        s.steps += 1;
        s.newton_iterations += report.iterations;
        s.jacobian_factorizations += report.factorizations;
        s.max_newton_iterations = s.max_newton_iterations.max(report.iterations);
    }
}
