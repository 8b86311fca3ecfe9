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
pub mod maps;
mod report;
pub(crate) mod small;

pub use equations::StepShape;
pub use report::{Statistics, StepReport};

use self::equations::{StepFunction, StepSystem};
use self::small::constrained::{MAX_CONSTRAINTS, SmallConstrainedStep};
use self::small::solve_sized;
use self::small::unconstrained::SmallStep;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::Error;
use crate::holonomic::{MomentumProjection, NoProjection};
use crate::integrator::compensated::Compensation;
use crate::integrator::small::dispatch::Dispatch;
use crate::mechanics::State;
use crate::mechanics::constraint_jacobian;
use crate::mechanics::{Constraint, NoForce, Unconstrained};
use crate::numerics::ad::HessianParts;
use crate::numerics::newton::{self, NewtonFailure, NewtonOptions, NewtonReport, NewtonWorkspace};
use crate::separable::ExplicitWorkspace;
use crate::separable::{Frame, SeparableWorkspace};

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
}

impl<A: DiscreteAction> Integrator<A> {
    /// An unforced, unconstrained integrator with default Newton options.
    pub fn new(action: A) -> Self {
        let shape = StepShape {
            n: action.dof(),
            s: action.internal_stages() + 1,
            d: 0,
            forced: false,
        };
        Self {
            action,
            force: NoForce,
            constraint: Unconstrained,
            projection: NoProjection,
            options: NewtonOptions::default(),
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics: Statistics::default(),
            fast_paths: true,
            compensation: Compensation::default(),
            dispatch: Dispatch::detect(),
        }
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
        Integrator {
            action: self.action,
            force,
            constraint: self.constraint,
            projection: self.projection,
            options: self.options,
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics: self.statistics,
            fast_paths: self.fast_paths,
            compensation: self.compensation,
            dispatch: self.dispatch,
        }
    }

    /// Adds holonomic constraints (replacing any previous ones).
    pub fn with_constraint<C2: Constraint>(self, constraint: C2) -> Integrator<A, F, C2, P> {
        let shape = StepShape {
            d: constraint.count(),
            ..self.shape
        };
        Integrator {
            action: self.action,
            force: self.force,
            constraint,
            projection: self.projection,
            options: self.options,
            shape,
            buffers: Buffers::default(),
            predictor: Predictor::default(),
            statistics: self.statistics,
            fast_paths: self.fast_paths,
            compensation: self.compensation,
            dispatch: self.dispatch,
        }
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
            fast_paths: self.fast_paths,
            compensation: self.compensation,
            dispatch: self.dispatch,
        }
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
        self
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
    /// gradient of the discrete action per step (2 % more instructions for gauss-4 on Kepler;
    /// `⌈n/8⌉` dual evaluations of the action, so think twice for large `n`), and the explicit
    /// run loop is not used (the explicit step of the trapezoid rule goes through Newton's
    /// method). Constrained steps are not compensated.
    ///
    /// ```
    /// use marsden::{Integrator, Rule, State, rules::Galerkin, systems::Kepler};
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
        self
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
        self.buffers.z.get(sn..).unwrap_or(&[])
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
        self.predictor.velocity = Some(v.to_vec());
    }

    /// One step of the discrete Hamiltonian map from `state` (advanced in place by `h`).
    ///
    /// On error `state` is left unchanged.
    pub fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        let step = self.statistics.steps;
        Error::check_len("q", &state.q, self.shape.n)?;
        Error::check_len("p", &state.p, self.shape.n)?;
        if h == 0.0 || !h.is_finite() {
            return Err(Error::InvalidStep { h });
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
            return Err(Error::InvalidStep { h });
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
        let sh = self.shape;
        self.fast_paths
            && !sh.forced
            && sh.d == 0
            && !self.compensation.enabled
            && self.action.explicit().is_some()
    }

    /// [`Integrator::advance`] on the explicit path: the first `steps − 1` steps in one
    /// [`crate::separable::ExplicitStep::explicit_run`], the last by [`Integrator::step`], so
    /// that [`Integrator::stage_offsets`] holds the last step's exact offset, as after single
    /// steps (the run loop keeps no offsets).
    fn advance_explicit(
        &mut self,
        state: &mut State,
        h: f64,
        steps: usize,
    ) -> Result<StepReport, Error> {
        let Some(last) = steps.checked_sub(1) else {
            return Ok(StepReport::default());
        };
        let t0 = state.t;
        if let (Some(explicit), true) = (self.action.explicit(), last > 0) {
            let run = explicit.explicit_run(
                (t0, h),
                last,
                (&mut state.q, &mut state.p),
                &mut self.buffers.explicit,
            );
            let st = &mut self.statistics;
            st.potential_gradients += run.gradients;
            st.steps += run.steps;
            st.explicit_steps += run.steps;
            state.t = t0 + run.steps as f64 * h;
            if run.steps < last {
                st.failed_steps += 1;
                return Err(Error::NonFinite {
                    step: st.steps,
                    t: state.t,
                    what: "the new state",
                });
            }
        }
        let report = self.step(state, h)?;
        state.t = t0 + steps as f64 * h;
        Ok(report)
    }

    fn solve(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Result<NewtonReport, NewtonFailure> {
        if let Some(result) = self.solve_separable(z, state, h) {
            return result;
        }
        if let Some(result) = self.solve_small(z, state, h) {
            return result;
        }
        let sh = self.shape;
        let b = &mut self.buffers;
        b.p_next.resize(sh.n, 0.0);
        // Dφ(q_k): reused from the previous step's projection when the state is the one it left.
        let reuse = b.dphi0_current && b.q_next == state.q;
        if sh.d > 0 && !reuse {
            b.phi.resize(sh.d, 0.0);
            b.dphi0.resize(sh.d * sh.n, 0.0);
            constraint_jacobian(&self.constraint, &state.q, &mut b.phi, &mut b.dphi0);
        }
        b.dphi0_current = false;
        if let Some(result) = self.solve_small_constrained(z, state, h) {
            return result;
        }
        let b = &mut self.buffers;
        let mut system = StepSystem {
            func: StepFunction {
                action: &self.action,
                force: &self.force,
                constraint: &self.constraint,
                t0: state.t,
                h,
                shape: sh,
            },
            q0: &state.q,
            p0: &state.p,
            dphi0: &b.dphi0,
            points: &mut b.points,
            parts: &mut b.parts,
            p_next: &mut b.p_next,
            ad_evaluations: 0,
        };
        let result = newton::solve(&mut system, z, &self.options, &mut b.newton);
        self.statistics.action_evaluations += system.ad_evaluations;
        if let Ok(r) | Err(NewtonFailure::NotConverged(r)) | Err(NewtonFailure::NonFinite(r)) =
            &result
        {
            self.statistics.system_evaluations += r.evaluations;
        }
        result
    }

    /// The explicit step ([`crate::separable::explicit`]) when the action has one and nothing else (forces,
    /// constraints) enters the step; `Ok(None)` when it does not apply.
    fn step_explicit(
        &mut self,
        state: &mut State,
        h: f64,
        step: usize,
    ) -> Result<Option<StepReport>, Error> {
        let sh = self.shape;
        // An action with internal stages may be explicit too (a composition of Verlet steps).
        if !self.is_explicit() {
            return Ok(None);
        }
        let Some(explicit) = self.action.explicit() else {
            return Ok(None);
        };
        let b = &mut self.buffers;
        b.p_next.clone_from(&state.p);
        b.z.resize(sh.n, 0.0);
        let gradients = explicit.explicit_step(
            state.t,
            h,
            &state.q,
            &mut b.p_next,
            &mut b.z,
            &mut b.explicit,
        );
        self.statistics.potential_gradients += gradients;
        if !b.z.iter().chain(&b.p_next).all(|x| x.is_finite()) {
            self.statistics.failed_steps += 1;
            return Err(Error::NonFinite {
                step,
                t: state.t,
                what: "the new state",
            });
        }
        state.q.iter_mut().zip(&b.z).for_each(|(q, d)| *q += d);
        state.p.copy_from_slice(&b.p_next);
        state.t += h;
        self.statistics.steps += 1;
        self.statistics.explicit_steps += 1;
        Ok(Some(StepReport::default()))
    }

    /// The structured Newton step of a separable Lagrangian ([`crate::separable::alpha`]) for
    /// two-point, unforced, unconstrained steps; `None` when it does not apply.
    fn solve_separable(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Option<Result<NewtonReport, NewtonFailure>> {
        let sh = self.shape;
        if !self.fast_paths || sh.s != 1 || sh.d != 0 || sh.forced {
            return None;
        }
        let step = self.action.separable()?;
        let b = &mut self.buffers;
        if !b.separable.applies(step) {
            return None;
        }
        b.p_next.resize(sh.n, 0.0);
        let frame = Frame {
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
        };
        let result = step.solve_separable(frame, z, &mut b.p_next, &self.options, &mut b.separable);
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.potential_gradients += evaluations;
        Some(result)
    }

    /// The statically sized step ([`crate::integrator::small::unconstrained`]) for two-point, unconstrained steps with
    /// `n ≤ 4`; `None` when it does not apply.
    fn solve_small(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Option<Result<NewtonReport, NewtonFailure>> {
        let sh = self.shape;
        if !self.fast_paths || sh.s != 1 || sh.d != 0 || sh.n > 4 {
            return None;
        }
        let small = SmallStep {
            action: &self.action,
            force: &self.force,
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
        };
        let o = &self.options;
        let p_next = &mut self.buffers.p_next;
        p_next.resize(sh.n, 0.0);
        let result = solve_sized(self.dispatch, &small, sh.n, z, o, p_next);
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.action_evaluations += evaluations;
        Some(result)
    }

    /// The statically sized constrained (SHAKE) step ([`crate::integrator::small::constrained`]) for
    /// two-point steps with `n ≤ 4` and `1 ≤ d ≤ 4`, once `Dφ(q_k)` is in the buffers; `None`
    /// when it does not apply.
    fn solve_small_constrained(
        &mut self,
        z: &mut [f64],
        state: &State,
        h: f64,
    ) -> Option<Result<NewtonReport, NewtonFailure>> {
        let sh = self.shape;
        let fits = sh.s == 1 && sh.n <= 4 && (1..=MAX_CONSTRAINTS).contains(&sh.d);
        if !self.fast_paths || !fits {
            return None;
        }
        let b = &mut self.buffers;
        let small = SmallConstrainedStep {
            action: &self.action,
            force: &self.force,
            constraint: &self.constraint,
            t0: state.t,
            h,
            q0: &state.q,
            p0: &state.p,
            dphi0: &b.dphi0,
            d: sh.d,
        };
        let (o, p_next) = (&self.options, &mut b.p_next);
        let result = solve_sized(self.dispatch, &small, sh.n, z, o, p_next);
        let evaluations = evaluations_of(&result);
        self.statistics.system_evaluations += evaluations;
        self.statistics.action_evaluations += evaluations;
        Some(result)
    }

    /// Fails if the converged `Δ_s = q_{k+1} − q_k` or `p_{k+1}` is not finite.
    fn check_finite(&self, z: &[f64], step: usize, t: f64) -> Result<(), Error> {
        let sn = self.shape.s * self.shape.n;
        let q_next = &z[sn - self.shape.n..sn];
        if q_next
            .iter()
            .chain(&self.buffers.p_next)
            .all(|x| x.is_finite())
        {
            Ok(())
        } else {
            Err(Error::NonFinite {
                step,
                t,
                what: "the new state",
            })
        }
    }

    /// Applies the momentum projection to `p_{k+1}` (in the buffers, so that a failure leaves
    /// `state` untouched) and keeps its multipliers as `μ_k = ν/h`.
    fn project(&mut self, z: &[f64], state: &State, h: f64, step: usize) -> Result<(), Error> {
        if !self.projection.is_active() {
            return Ok(());
        }
        let (n, sn) = (self.shape.n, self.shape.s * self.shape.n);
        let (b, d) = (&mut self.buffers, self.shape.d);
        b.q_next.clear();
        b.q_next
            .extend(state.q.iter().zip(&z[sn - n..sn]).map(|(q, d)| q + d));
        b.phi_next.resize(d, 0.0);
        b.dphi_next.resize(d * n, 0.0);
        if d > 0 {
            constraint_jacobian(
                &self.constraint,
                &b.q_next,
                &mut b.phi_next,
                &mut b.dphi_next,
            );
        }
        let t = state.t + h;
        let projected = self
            .projection
            .project(t, &b.q_next, &b.dphi_next, &mut b.p_next);
        match projected {
            Ok(_) => {
                b.mu.clear();
                b.mu.extend(self.projection.multipliers().iter().map(|nu| nu / h));
                // Dφ(q_{k+1}) serves the next step too (see `solve`).
                std::mem::swap(&mut b.dphi0, &mut b.dphi_next);
                b.dphi0_current = d > 0;
                Ok(())
            }
            Err(failure) => Err(Error::MomentumProjectionFailed {
                step,
                t,
                iterations: failure.iterations,
                residual: failure.residual,
            }),
        }
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

    fn newton_error(&self, failure: NewtonFailure, step: usize, state: &State, z: &[f64]) -> Error {
        let t = state.t;
        if let Some(error) = self.constraint_error(&failure, step, state, z) {
            return error;
        }
        match failure {
            NewtonFailure::NotConverged(r) => Error::NewtonDidNotConverge {
                step,
                t,
                iterations: r.iterations,
                residual: r.residual,
                tolerance: self.options.residual_tolerance,
            },
            NewtonFailure::Singular { iteration, pivot } => Error::SingularJacobian {
                step,
                t,
                iteration,
                pivot,
            },
            NewtonFailure::NonFinite(_) => Error::NonFinite {
                step,
                t,
                what: "the Newton residual",
            },
        }
    }

    /// A failed constrained step whose constraint equations `φ(q_{k+1}) = 0` were left unsolved
    /// is reported as [`Error::ConstraintNotSatisfied`] (e.g. an unsatisfiable constraint).
    fn constraint_error(
        &self,
        failure: &NewtonFailure,
        step: usize,
        state: &State,
        z: &[f64],
    ) -> Option<Error> {
        let sh = self.shape;
        if sh.d == 0 {
            return None;
        }
        // φ at the last Newton iterate q_k + Δ_s (both solvers leave it in `z`).
        let delta = z.get(sh.s * sh.n - sh.n..sh.s * sh.n)?;
        let q_end: Vec<f64> = state.q.iter().zip(delta).map(|(q, d)| q + d).collect();
        let mut phi = vec![0.0; sh.d];
        self.constraint.constraint(&q_end, &mut phi);
        let (index, value) = phi.iter().enumerate().fold((0, 0.0_f64), |best, (i, &v)| {
            if v.abs() > best.1.abs() { (i, v) } else { best }
        });
        let tol =
            self.options.residual_tolerance * crate::numerics::dense::max_norm(&state.p).max(1.0);
        let iterations = match *failure {
            NewtonFailure::NotConverged(r) | NewtonFailure::NonFinite(r) => r.iterations,
            NewtonFailure::Singular { iteration, .. } => iteration,
        };
        (value.is_finite() && value.abs() > tol).then_some(Error::ConstraintNotSatisfied {
            step,
            t: state.t,
            index,
            residual: value,
            iterations,
        })
    }

    fn count(&mut self, report: NewtonReport) {
        let s = &mut self.statistics;
        s.steps += 1;
        s.newton_iterations += report.iterations;
        s.jacobian_factorizations += report.factorizations;
        s.max_newton_iterations = s.max_newton_iterations.max(report.iterations);
    }
}

/// Starting guess for the unknowns of the next step.
///
/// The unknowns are offsets `Δ_j ≈ c_j h v`, smooth in time: each is extrapolated from the same
/// unknown in the last three steps (quadratic: `3z₁ − 3z₂ + z₃`, error `O(h⁴)` in positions),
/// falling back to linear, constant, and for a fresh start `Δ_j = c_j h v_k` with the velocity
/// hint (or 0). Multipliers start from their last values. The history is a flat ring of three
/// solutions (no allocation per step).
#[derive(Debug, Clone, Default)]
struct Predictor {
    /// Three solutions back to back.
    ring: Vec<f64>,
    /// Slots of the newest, previous and oldest solution.
    order: [usize; 3],
    /// Number of valid solutions in the ring (0 … 3).
    len: usize,
    h: f64,
    velocity: Option<Vec<f64>>,
}

impl Predictor {
    fn predict(&mut self, z: &mut Vec<f64>, h: f64, sh: StepShape) {
        let m = sh.unknowns();
        z.resize(m, 0.0);
        if h != self.h || self.ring.len() != 3 * m {
            self.reset_ring(m);
        }
        let [a, b, c] = self.order.map(|slot| slot * m);
        let (r, z) = (&self.ring, &mut z[..m]);
        match self.len {
            0 => return self.fresh(z, h, sh),
            1 => z.copy_from_slice(&r[a..a + m]),
            2 => z
                .iter_mut()
                .enumerate()
                .for_each(|(i, zi)| *zi = 2.0 * r[a + i] - r[b + i]),
            _ => z
                .iter_mut()
                .enumerate()
                .for_each(|(i, zi)| *zi = 3.0 * (r[a + i] - r[b + i]) + r[c + i]),
        }
        let sn = sh.s * sh.n;
        z[sn..].copy_from_slice(&r[a + sn..a + m]);
    }

    fn reset_ring(&mut self, m: usize) {
        self.ring.resize(3 * m, 0.0);
        self.order = [0, 1, 2];
        self.len = 0;
    }

    fn fresh(&self, z: &mut [f64], h: f64, sh: StepShape) {
        let n = sh.n;
        for j in 1..=sh.s {
            let c = j as f64 / sh.s as f64;
            for a in 0..n {
                let v = self.velocity.as_ref().map_or(0.0, |v| v[a]);
                z[(j - 1) * n + a] = c * h * v;
            }
        }
        z[sh.s * n..].fill(0.0);
    }

    fn record(&mut self, z: &[f64], h: f64) {
        let m = z.len();
        if self.ring.len() != 3 * m {
            self.reset_ring(m);
        }
        let [newest, previous, oldest] = self.order;
        self.order = [oldest, newest, previous];
        self.ring[oldest * m..(oldest + 1) * m].copy_from_slice(z);
        self.len = (self.len + 1).min(3);
        self.h = h;
        self.velocity = None;
    }
}

/// System evaluations of one Newton solve, converged or not (a singular Jacobian at iteration
/// `i` follows `i + 1` evaluations).
fn evaluations_of(result: &Result<NewtonReport, NewtonFailure>) -> usize {
    match result {
        Ok(r) | Err(NewtonFailure::NotConverged(r)) | Err(NewtonFailure::NonFinite(r)) => {
            r.evaluations
        }
        Err(NewtonFailure::Singular { iteration, .. }) => iteration + 1,
    }
}
