//! The generic runner: a `Problem` from any [`Lagrangian`], [`Force`] and [`Constraint`],
//! solved with the file's method while the [`StreamObserver`] stores the samples.

use std::time::Instant;

use marsden::discrete::exact::ExactDiscreteLagrangian;
use marsden::discrete::rules::Method as Rule;
use marsden::{
    Constraint, Force, Integrator, Lagrangian, NewtonOptions, Observer, Problem, Rule as _,
    RunFailure, SolveOptions, Statistics, Trajectory, simulate,
};
use marsden_io::RowSink;

use super::balance::{BalanceSeries, BalanceSummary, Balanced, TimeDerivative};
use super::certify::{Certificate, Ends, certify, without_step_jacobian};
use super::controls::Controls;
use super::diagnostics::Diagnostics;
use super::noether_balance::{NoetherBalance, NoetherBalanced};
use super::observer::StreamObserver;
use super::start;
use super::summary::FinalState;
use crate::catalog::WithLagrangian;
use crate::error::Diagnostic;
use crate::model::{ExprDiscreteLagrangian, MomentumMap};
use crate::problem::{Method, RunSpec};
use marsden::symmetry::GroupAction;

/// What a run did, before it is written up.
#[derive(Debug, Clone)]
pub struct RunRecord {
    /// The failure's message (`None`: completed or interrupted).
    pub error: Option<String>,
    /// Whether the run was stopped through [`Controls::stop`].
    pub interrupted: bool,
    /// Steps completed.
    pub steps: usize,
    /// The last good state.
    pub final_state: FinalState,
    /// Newton work.
    pub statistics: Statistics,
    /// Wall-clock seconds of the integration.
    pub wall_seconds: f64,
    /// What was monitored.
    pub diagnostics: Diagnostics,
    /// Rows written.
    pub rows: u64,
    /// The discrete energy balance of a forced run with a two-point rule (`None` otherwise).
    pub balance: Option<BalanceSummary>,
    /// The same at the stored steps, for the plot.
    pub balance_series: Option<BalanceSeries>,
    /// The forced Noether balance of each symmetry, with the energy balance (empty otherwise).
    pub noether_balance: Vec<(String, NoetherBalance)>,
    /// The certificates (`[analysis] certify = true`).
    pub certificate: Option<Certificate>,
}

/// Solves `problem` with `method`: the method itself is the rule (one compiled integrator per
/// system for every rule, [`marsden::discrete::rules::chosen`]); `exact` steps `L_d^E` by
/// shooting.
pub fn solve<L: Lagrangian, F: Force, C: Constraint, O: Observer + ?Sized>(
    problem: &Problem<L, F, C>,
    method: &Method,
    options: &SolveOptions,
    observer: &mut O,
) -> Result<Trajectory, Box<RunFailure>> {
    match method.rule() {
        Some(rule) => problem.solve_with(rule, options, observer),
        None => solve_exact(problem, options, observer),
    }
}

/// How a run takes its steps, fixed by type so that each kind of run compiles only its own
/// code: a rule of the core ([`ByRule`], compiled once per Lagrangian type) or the exact
/// discrete Lagrangian by shooting ([`Exact`], compiled once for the whole catalog, through
/// [`crate::problem::LagrangianSpec::dispatch_shared`]).
pub trait Stepping: Copy {
    /// The run of `problem` with the energy and Noether balances where they apply
    /// ([`solve_balanced`]).
    fn run<L: Lagrangian, F: Force, C: Constraint, M, O: Observer + ?Sized>(
        self,
        parts: (&Problem<L, F, C>, &[M]),
        output: (usize, bool),
        options: &SolveOptions,
        observer: &mut O,
    ) -> Balance
    where
        M: MomentumMap + GroupAction;

    /// The certificates of a run that ended at `ends` (see [`certify`]).
    fn certify<L: Lagrangian, F: Force, C: Constraint, G: GroupAction>(
        self,
        problem: &Problem<L, F, C>,
        symmetries: (&[String], &[G]),
        step: (NewtonOptions, f64),
        ends: &Ends<'_>,
    ) -> Certificate;
}

/// Steps by a rule of the core.
#[derive(Debug, Clone, Copy)]
pub struct ByRule<'a>(pub &'a Rule);

/// Steps by `L_d^E`, the exact discrete Lagrangian by shooting (`method = "exact"`).
#[derive(Debug, Clone, Copy)]
pub struct Exact;

impl Stepping for ByRule<'_> {
    fn run<L: Lagrangian, F: Force, C: Constraint, M, O: Observer + ?Sized>(
        self,
        parts: (&Problem<L, F, C>, &[M]),
        (every, time_dependent): (usize, bool),
        options: &SolveOptions,
        observer: &mut O,
    ) -> Balance
    where
        M: MomentumMap + GroupAction,
    {
        solve_balanced(parts, (self.0, every, time_dependent), options, observer)
    }

    fn certify<L: Lagrangian, F: Force, C: Constraint, G: GroupAction>(
        self,
        problem: &Problem<L, F, C>,
        symmetries: (&[String], &[G]),
        (newton, h): (NewtonOptions, f64),
        ends: &Ends<'_>,
    ) -> Certificate {
        certify(problem, symmetries, (self.0, newton, h), ends)
    }
}

impl Stepping for Exact {
    fn run<L: Lagrangian, F: Force, C: Constraint, M, O: Observer + ?Sized>(
        self,
        (problem, _): (&Problem<L, F, C>, &[M]),
        _: (usize, bool),
        options: &SolveOptions,
        observer: &mut O,
    ) -> Balance
    where
        M: MomentumMap + GroupAction,
    {
        (solve_exact(problem, options, observer), None)
    }

    fn certify<L: Lagrangian, F: Force, C: Constraint, G: GroupAction>(
        self,
        problem: &Problem<L, F, C>,
        _: (&[String], &[G]),
        _: (NewtonOptions, f64),
        _: &Ends<'_>,
    ) -> Certificate {
        without_step_jacobian(problem.force().is_active())
    }
}

/// `method = "exact"`: the integrator steps `L_d^E` of the problem's Lagrangian by shooting
/// (forces and constraints were refused when the file was read).
fn solve_exact<L: Lagrangian, F: Force, C: Constraint, O: Observer + ?Sized>(
    problem: &Problem<L, F, C>,
    options: &SolveOptions,
    observer: &mut O,
) -> Result<Trajectory, Box<RunFailure>> {
    let l = problem.lagrangian();
    let failure = |error| {
        let trajectory = Trajectory::new(l.dof(), 0, problem.grid().h);
        Box::new(RunFailure { error, trajectory })
    };
    let exact = ExactDiscreteLagrangian::new(l);
    let mut integrator = Integrator::new(exact)
        .with_options(options.newton)
        .map_err(failure)?
        .with_compensated_summation(options.compensated);
    integrator.set_velocity_hint(problem.initial_velocity());
    let (start, grid) = (problem.start().clone(), problem.grid());
    simulate(&mut integrator, start, grid, &options.run, observer)
        .into_result()
        .map_err(|failure| explain_exact_failure(l, failure, grid.h))
}

/// A failed step of `L_d^E` is reported by the integrator as a non-finite value (the shooting
/// evaluates to NaN when its boundary value problem has no solution): the shooting's own error
/// at the last good state, from the chord `q₁ = q_k + h v_k` ([`ExactDiscreteLagrangian::boundary_value`]),
/// says why.
fn explain_exact_failure<L: Lagrangian>(
    l: &L,
    mut failure: Box<RunFailure>,
    h: f64,
) -> Box<RunFailure> {
    let marsden::Error::Step(step) = &failure.error else {
        return failure;
    };
    let trajectory = &failure.trajectory;
    let Some(last) = trajectory.len().checked_sub(1) else {
        return failure;
    };
    let (t, q, p) = (trajectory.t(last), trajectory.q(last), trajectory.p(last));
    let mut v = vec![0.0; q.len()];
    if marsden::mechanics::velocity(l, t, q, p, &mut v).is_err() {
        return failure;
    }
    let q1: Vec<f64> = q.iter().zip(&v).map(|(q, v)| q + h * v).collect();
    let exact = ExactDiscreteLagrangian::new(l);
    if let Err(why) = exact.boundary_value(t, h, q, &q1) {
        failure.error = marsden::Error::Setup(marsden::error::SetupError::ExactStepFailed {
            step: step.step,
            t: step.t,
            reason: why.to_string(),
        });
    }
    failure
}

/// [`solve`], and for an active force or a Lagrangian depending on `t` (`time_dependent`) and
/// a two-point rule the discrete energy balance of every step ([`Balanced`], with the
/// `∂L_d/∂t₀` term when `time_dependent`) and the forced Noether balance of every symmetry in
/// `maps` ([`NoetherBalanced`]) on the way (the energy series keeps every `every`-th step).
pub fn solve_balanced<L: Lagrangian, F: Force, C: Constraint, M, O: Observer + ?Sized>(
    (problem, maps): (&Problem<L, F, C>, &[M]),
    (rule, every, time_dependent): (&Rule, usize, bool),
    options: &SolveOptions,
    observer: &mut O,
) -> Balance
where
    M: MomentumMap + GroupAction,
{
    use marsden::discrete::DiscreteAction as _;
    let l = problem.lagrangian();
    let two_point = rule.discretize(l).internal_stages() == 0;
    if !(problem.force().is_active() || time_dependent) || !two_point {
        return (problem.solve_with(rule, options, observer), None);
    }
    let force = rule.discretize_force(problem.force(), l.dof());
    let noether_force = rule.discretize_force(problem.force(), l.dof());
    let h = problem.grid().h;
    let total = problem.grid().steps;
    let names = maps
        .iter()
        .map(|m| MomentumMap::name(m).to_owned())
        .collect();
    let mut noether = NoetherBalanced::new((names, maps), (&noether_force, h), observer);
    let time = time_dependent.then(|| rule.discretize_force(TimeDerivative(l), l.dof()));
    let mut balanced = Balanced::new(l, (force, time, h), (every, total), &mut noether);
    let result = problem.solve_with(rule, options, &mut balanced);
    let (summary, series) = (balanced.summary, balanced.series);
    (result, Some((summary, series, noether.balances())))
}

/// A run's result and, for a forced run with a two-point rule, its energy balance and the
/// forced Noether balance of each symmetry.
pub type Balance = (
    Result<Trajectory, Box<RunFailure>>,
    Option<(BalanceSummary, BalanceSeries, Vec<(String, NoetherBalance)>)>,
);

/// Where the rows of a run go: a sink, and whether each row carries the velocities too (for
/// the in-memory [`Samples`](super::samples::Samples)).
pub struct Destination<'s> {
    /// The writer.
    pub sink: &'s mut (dyn RowSink + 's),
    /// Append `v` to every row.
    pub with_velocity: bool,
}

/// Runs `spec` with the given system parts, streaming rows into `destination`.
///
/// # Errors
/// Only if the core rejects the initial state (already checked by [`start::prepare`]); a
/// failing run is a [`RunRecord`] with an error message, not an `Err`.
pub fn run_problem<L: Lagrangian, F: Force, C: Constraint, M, X: Stepping>(
    (lagrangian, force, constraint, maps): (&L, &F, &C, &[M]),
    (spec, stepping): (&RunSpec, X),
    destination: Destination<'_>,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic>
where
    M: MomentumMap + GroupAction,
{
    let grid = spec.integrator.grid;
    let problem = start::constrained_problem(spec, lagrangian, constraint)?.with_force(force);
    let options = SolveOptions {
        newton: spec.integrator.newton,
        // The observer stores the samples; the core keeps only the first and the last.
        run: marsden::RunOptions { stride: usize::MAX },
        general_path: !spec.integrator.fast_paths,
        compensated: spec.integrator.compensated,
    };
    let parts = ((Some(lagrangian), lagrangian.dof()), constraint, maps);
    let sink = (destination.sink, destination.with_velocity);
    let mut observer = StreamObserver::new(parts, sink, (spec.output.every, grid.steps), controls)
        .monitoring_every_step(spec.analysis.every_step);
    let clock = Instant::now();
    let time_dependent = spec.system.depends_on_time();
    let output = (spec.output.every, time_dependent);
    let (result, balance) = stepping.run((&problem, maps), output, &options, &mut observer);
    let wall_seconds = clock.elapsed().as_secs_f64();
    let mut record = finish(observer, result, wall_seconds);
    if let Some((b, series, noether)) = balance {
        (record.balance, record.balance_series) = (Some(b), Some(series));
        record.noether_balance = noether;
    }
    Ok(record)
}

/// The record of a run that ended with `result` after `wall_seconds`, its last state written
/// (no balances, no certificate).
pub(super) fn finish<L: Lagrangian, C: Constraint, M: MomentumMap>(
    mut observer: StreamObserver<'_, '_, L, C, M>,
    result: Result<Trajectory, Box<RunFailure>>,
    wall_seconds: f64,
) -> RunRecord {
    let (trajectory, error) = match result {
        Ok(t) => (t, None),
        Err(failure) => (failure.trajectory, Some(failure.error.to_string())),
    };
    observer.finish(trajectory.steps);
    observer.record_last(&trajectory);
    let io = observer
        .io_error
        .as_ref()
        .map(|e| format!("writing the trajectory failed: {e}"));
    let energy = non_finite_energy(&observer.diagnostics, observer.rows());
    RunRecord {
        error: error.or(io).or(energy),
        interrupted: observer.interrupted,
        steps: trajectory.steps,
        final_state: final_state(&trajectory),
        statistics: trajectory.statistics,
        wall_seconds,
        rows: observer.rows(),
        diagnostics: observer.diagnostics,
        balance: None,
        balance_series: None,
        noether_balance: Vec::new(),
        certificate: None,
    }
}

/// A failure if any stored energy was not finite: a run whose energies are NaN or infinite
/// preserved nothing that can be reported, even if every step converged.
fn non_finite_energy(diagnostics: &Diagnostics, rows: u64) -> Option<String> {
    let bad = diagnostics.energy.report().failures;
    (bad > 0).then(|| {
        format!(
            "the energy ⟨p, q̇⟩ − L is not finite at {bad} of the {rows} stored states: the \
             Lagrangian or its derivatives are not finite along the trajectory"
        )
    })
}

fn final_state(trajectory: &Trajectory) -> FinalState {
    match trajectory.len().checked_sub(1) {
        Some(i) => FinalState {
            t: trajectory.t(i),
            q: trajectory.q(i).to_vec(),
            p: trajectory.p(i).to_vec(),
        },
        None => FinalState {
            t: f64::NAN,
            q: Vec::new(),
            p: Vec::new(),
        },
    }
}

/// [`run_problem`] with the system of the spec, whichever Lagrangian type it has.
pub struct Runner<'a> {
    /// The problem.
    pub spec: &'a RunSpec,
    /// Where the rows go.
    pub destination: Destination<'a>,
    /// The caller's callback and stop flag.
    pub controls: &'a Controls<'a>,
}

impl Runner<'_> {
    /// Runs the spec's system.
    ///
    /// # Errors
    /// As [`run_problem`].
    pub fn run(self) -> Result<RunRecord, Diagnostic> {
        let Runner {
            spec,
            destination,
            controls,
        } = self;
        let lagrangian = &spec.system.lagrangian;
        match spec.integrator.method.rule() {
            Some(rule) => lagrangian.dispatch(Run {
                spec,
                destination,
                controls,
                stepping: ByRule(rule),
            }),
            // Shooting costs far more per step than a branch per evaluation of `L`: one compiled
            // run for the whole catalog.
            None => lagrangian.dispatch_shared(Run {
                spec,
                destination,
                controls,
                stepping: Exact,
            }),
        }
    }
}

/// A [`Runner`] with the kind of stepping fixed by type.
struct Run<'a, X> {
    spec: &'a RunSpec,
    destination: Destination<'a>,
    controls: &'a Controls<'a>,
    stepping: X,
}

impl<X: Stepping> WithLagrangian for Run<'_, X> {
    type Output = Result<RunRecord, Diagnostic>;
    fn call<L: Lagrangian>(self, lagrangian: &L) -> Self::Output {
        let s = &self.spec.system;
        let force = s.force.on(lagrangian);
        let parts = (lagrangian, &force, &s.constraint, s.symmetries.as_slice());
        let spec = (self.spec, self.stepping);
        let mut record = run_problem(parts, spec, self.destination, self.controls)?;
        if self.spec.analysis.certify {
            let parts = (lagrangian, &force);
            record.certificate = Some(certificate(spec, parts, &record)?);
        }
        Ok(record)
    }

    fn discrete(self, ld: &ExprDiscreteLagrangian) -> Self::Output {
        super::discrete::run(ld, self.spec, self.destination, self.controls)
    }
}

/// The certificates of `record`, a run of `spec` with `lagrangian` (from its initial state and
/// its last good state).
fn certificate<L: Lagrangian, F: Force, X: Stepping>(
    (spec, stepping): (&RunSpec, X),
    (lagrangian, force): (&L, &F),
    record: &RunRecord,
) -> Result<Certificate, Diagnostic> {
    let s = &spec.system;
    let problem = start::constrained_problem(spec, lagrangian, &s.constraint)?.with_force(force);
    let f = &record.final_state;
    let end = marsden::State {
        t: f.t,
        q: f.q.clone(),
        p: f.p.clone(),
    };
    let ends = Ends {
        start: problem.start(),
        v0: problem.initial_velocity(),
        end: &end,
    };
    let names: Vec<String> = s
        .symmetries
        .iter()
        .map(|m| MomentumMap::name(m).to_owned())
        .collect();
    let i = &spec.integrator;
    let symmetries = (names.as_slice(), s.symmetries.as_slice());
    Ok(stepping.certify(&problem, symmetries, (i.newton, i.grid.h), &ends))
}
