//! The generic runner: a `Problem` from any [`Lagrangian`], [`Force`] and [`Constraint`],
//! solved with the file's rule ([`run_by_rule`]) or by shooting ([`run_exact`]) while the
//! [`StreamObserver`] stores the samples. Reached through [`crate::engine::Engine`].

use std::time::Instant;

use marsden::discrete::exact::ExactDiscreteLagrangian;
use marsden::discrete::rules::Method as Rule;
use marsden::{
    Constraint, Force, Integrator, Lagrangian, Observer, Problem, Rule as _, RunFailure,
    SolveOptions, Statistics, Trajectory, simulate,
};
use marsden_io::RowSink;
use serde::Serialize;

use crate::balance::{BalanceSeries, BalanceSummary, Balanced, TimeDerivative};
use crate::certify::{Certificate, Ends, StepRule, certify, without_step_jacobian};
use crate::checkpoint::observer::{Carries, Checkpointing};
use crate::checkpoint::{BalancesCheckpoint, CheckpointPlan};
use crate::controls::Controls;
use crate::diagnostics::Diagnostics;
use crate::events::{EventTally, Watched};
use crate::noether_balance::{NoetherBalance, NoetherBalanced};
use crate::observer::{StreamObserver, StreamRows, StreamSystem};
use crate::samples::{SampleTally, TimeSamples};
use crate::start;
use marsden::run::Resumed;
use marsden::symmetry::GroupAction;
use marsden_problem::error::Diagnostic;
use marsden_problem::model::{ExprConstraint, MomentumMap, Symmetry};
use marsden_problem::problem::RunSpec;

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
    /// The part of [`RunRecord::wall_seconds`] spent compiling expressions to native code (at
    /// their first use, inside the run).
    pub jit_compile_seconds: f64,
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
    /// A rigid body's own invariants and last attitude (`None` for other systems).
    pub rigid: Option<crate::rigid::RigidRecord>,
    /// A multibody run's joints, attitudes and momenta (`None` for other systems).
    pub multibody: Option<crate::multibody::MultibodyRecord>,
    /// What the file's `[[events]]` came to (empty without events).
    pub events: EventTally,
    /// What the samples at `[output] times` came to (`None`: none requested).
    pub samples: Option<SampleTally>,
}

/// `method = "exact"`: the integrator steps `L_d^E` of the problem's Lagrangian by shooting
/// (forces and constraints were refused when the file was read).
fn solve_exact<L: Lagrangian, F: Force, C: Constraint, O: Observer>(
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

/// Runs `problem` by `rule` with the solver's `options`, shown to `observer`; for a forced or
/// time-dependent run with a two-point rule, around the energy balance of every step
/// ([`Balanced`], with `output.every`'s series) and the forced Noether balance of every
/// symmetry in `maps` ([`NoetherBalanced`]). With `checkpoints`, the run (balances included)
/// is checkpointed as planned, and continued from the plan's checkpoint when it has one.
///
/// Returns the result, the balances (`None` when the run keeps none), and why a checkpoint
/// could not be written or restored (the run then stopped there, or did not start).
pub fn solve_balanced<L: Lagrangian, F: Force, C: Constraint, M, O>(
    problem: &Problem<L, F, C>,
    maps: &[M],
    rule: &Rule,
    output: Output,
    options: &SolveOptions,
    checkpoints: Option<&CheckpointPlan>,
    observer: &mut O,
) -> Solved
where
    M: MomentumMap + GroupAction,
    O: Observer + Carries,
{
    use marsden::discrete::DiscreteAction as _;
    let Output {
        every,
        time_dependent,
    } = output;
    let l = problem.lagrangian();
    let two_point = rule.discretize(l).internal_stages() == 0;
    if !(problem.force().is_active() || time_dependent) || !two_point {
        let (result, error) = solve_checkpointed(problem, rule, options, checkpoints, observer);
        return (result, None, error);
    }
    let force = rule.discretize_force(problem.force(), l.dof());
    let noether_force = rule.discretize_force(problem.force(), l.dof());
    let grid = problem.grid();
    let names = maps
        .iter()
        .map(|m| MomentumMap::name(m).to_owned())
        .collect();
    let mut noether = NoetherBalanced::new(names, maps, &noether_force, grid, observer);
    let time = time_dependent.then(|| rule.discretize_force(TimeDerivative(l), l.dof()));
    let mut balanced = Balanced::new(l, force, time, grid, every, &mut noether);
    let resumed = checkpoints.and_then(|p| p.resume.as_deref());
    if let Some(c) = resumed
        && let Err(e) = restore_balances(&mut balanced, c.balances.as_ref())
    {
        let failure = RunFailure {
            error: marsden::Error::Input(marsden::error::InputError::Restored {
                reason: e.clone(),
            }),
            trajectory: marsden::Trajectory::new(l.dof(), problem.constraint().count(), grid.h),
        };
        return (Err(Box::new(failure)), None, Some(e));
    }
    let (result, error) = solve_checkpointed(problem, rule, options, checkpoints, &mut balanced);
    let balances = Balances {
        energy: balanced.summary,
        series: balanced.series,
        noether: noether.balances(),
    };
    (result, Some(balances), error)
}

/// What [`solve_balanced`] gives: the run's result, its balances, and a checkpoint's error.
pub type Solved = (
    Result<Trajectory, Box<RunFailure>>,
    Option<Balances>,
    Option<String>,
);

/// Restores the balances of a resumed forced run from its checkpoint's.
fn restore_balances<L, F, T, G, F2, O>(
    balanced: &mut Balanced<'_, L, F, T, NoetherBalanced<'_, G, F2, O>>,
    carried: Option<&BalancesCheckpoint>,
) -> Result<(), String>
where
    L: Lagrangian,
    F: marsden::discrete::DiscreteForce,
    T: marsden::discrete::DiscreteForce,
    G: GroupAction,
    F2: marsden::discrete::DiscreteForce,
    O: Observer,
{
    let Some(carried) = carried else {
        return Err("the checkpoint holds no energy balance for this forced run".to_owned());
    };
    balanced.restore(&carried.energy)?;
    balanced.inner_mut().restore(&carried.noether)
}

/// Runs `problem` by `rule` with the solver's `options`, shown to `observer`, checkpointed as
/// `checkpoints` plans (from its start, or from the plan's checkpoint); and why a checkpoint
/// could not be written, if one could not.
fn solve_checkpointed<L: Lagrangian, F: Force, C: Constraint, O>(
    problem: &Problem<L, F, C>,
    rule: &Rule,
    options: &SolveOptions,
    checkpoints: Option<&CheckpointPlan>,
    observer: &mut O,
) -> (Result<Trajectory, Box<RunFailure>>, Option<String>)
where
    O: Observer + Carries,
{
    let Some(plan) = checkpoints else {
        return (problem.solve_with(rule, options, observer), None);
    };
    let mut watch = Checkpointing::new(observer, plan);
    let result = match plan.resume.as_deref() {
        None => problem.solve_with(rule, options, &mut watch),
        Some(c) => {
            let state = marsden::State {
                t: c.t,
                q: c.q.clone(),
                p: c.p.clone(),
            };
            let from = Resumed {
                step: c.step,
                state,
            };
            problem.solve_resumed(rule, options, &mut watch, from, &c.integrator)
        }
    };
    (result, watch.error)
}

/// The balances of a forced run with a two-point rule: the discrete energy balance (its
/// summary, and its series at the stored steps for the plot) and the forced Noether balance of
/// each symmetry.
pub struct Balances {
    /// The energy balance's summary.
    pub energy: BalanceSummary,
    /// The energy balance at the stored steps.
    pub series: BalanceSeries,
    /// The forced Noether balance of each symmetry, by name.
    pub noether: Vec<(String, NoetherBalance)>,
}

/// The last good state of a run (`summary.json`'s `final_state { … }`).
#[derive(Debug, Clone, Serialize)]
pub struct FinalState {
    /// Time.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Momenta.
    pub p: Vec<f64>,
}

/// Where the rows of a run go: a sink, and whether each row carries the velocities too (for
/// the in-memory samples of the caller).
pub struct Destination<'s> {
    /// The writer.
    pub sink: &'s mut (dyn RowSink + 's),
    /// Append `v` to every row.
    pub with_velocity: bool,
    /// Where the event records go, as rows `event, t, q…, p…` (`None`: counted only).
    pub events: Option<&'s mut (dyn RowSink + 's)>,
    /// Where the samples at `[output] times` go, as rows `t, q…, p…, observables…` (`None`:
    /// counted only).
    pub samples: Option<&'s mut (dyn RowSink + 's)>,
    /// Checkpoints of the run, and the one it resumes from (`None`: none; the sinks of a
    /// resumed run were reopened at the checkpoint's marks).
    pub checkpoints: Option<&'s CheckpointPlan>,
}

/// Runs `spec` with `lagrangian` by `rule` (the file's forces, constraints and symmetries),
/// streaming rows into `destination`; with the energy and Noether balances of a forced run
/// ([`solve_balanced`]) and the certificates when `[analysis] certify = true`.
///
/// # Errors
/// Only if the core rejects the initial state (already checked by
/// [`start::prepare_with`]); a failing run is a [`RunRecord`] with an error message, not an
/// `Err`.
pub fn run_by_rule<L: Lagrangian>(
    spec: &RunSpec,
    rule: &Rule,
    lagrangian: &L,
    destination: Destination<'_>,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic> {
    let s = &spec.system;
    let force = s.force.on(lagrangian);
    let maps = s.symmetries.as_slice();
    let plan = destination.checkpoints;
    let mut session = Session::open(spec, lagrangian, &force, destination, controls)?;
    let output = Output {
        every: spec.output.every,
        time_dependent: s.depends_on_time(),
    };
    let (result, balance, checkpoint_error) = solve_balanced(
        &session.problem,
        maps,
        rule,
        output,
        &session.options,
        plan,
        &mut session.observer,
    );
    let (mut record, problem) = session.finish(result, balance);
    if let Some(e) = checkpoint_error {
        record.error.get_or_insert(e);
    }
    if spec.analysis.certify {
        let ends = RunEnds::of(&problem, &record);
        let (names, i) = (symmetry_names(spec), &spec.integrator);
        let step = StepRule {
            rule,
            newton: i.newton,
            h: i.grid.h,
        };
        record.certificate = Some(certify(&problem, &names, maps, step, &ends.view()));
    }
    Ok(record)
}

/// Runs `spec` with `method = "exact"`: the integrator steps `L_d^E` of `lagrangian` by
/// shooting (forces and constraints were refused when the file was read); its certificate has
/// no step Jacobian to offer.
///
/// # Errors
/// As [`run_by_rule`].
pub fn run_exact<L: Lagrangian>(
    spec: &RunSpec,
    lagrangian: &L,
    destination: Destination<'_>,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic> {
    let force = spec.system.force.on(lagrangian);
    let mut session = Session::open(spec, lagrangian, &force, destination, controls)?;
    let result = solve_exact(&session.problem, &session.options, &mut session.observer);
    let (mut record, _) = session.finish(result, None);
    if spec.analysis.certify {
        record.certificate = Some(without_step_jacobian(force.is_active()));
    }
    Ok(record)
}

/// What a run streams besides the states: the energy series keeps every `every`-th step, and
/// a Lagrangian that reads `t` adds the `∂L_d/∂t₀` term to the energy balance.
#[derive(Debug, Clone, Copy)]
pub struct Output {
    /// Store every `every`-th step.
    pub every: usize,
    /// The Lagrangian depends on `t`.
    pub time_dependent: bool,
}

/// A run being made: the problem (built once), the solver's options, the observer streaming
/// the rows, and the clock.
struct Session<'a, 's, L, F> {
    problem: Problem<&'a L, &'a F, &'a ExprConstraint>,
    options: SolveOptions,
    observer: Watched<'a, 's, L, StreamObserver<'a, 's, L, ExprConstraint, Symmetry>>,
    clock: Instant,
    /// This thread's JIT compilation seconds when the clock started.
    jit_before: f64,
}

impl<'a, 's, L: Lagrangian, F: Force> Session<'a, 's, L, F> {
    /// The problem of `spec` with `lagrangian` and `force`, and an observer writing into
    /// `destination`.
    fn open(
        spec: &'a RunSpec,
        lagrangian: &'a L,
        force: &'a F,
        destination: Destination<'s>,
        controls: &'a Controls<'a>,
    ) -> Result<Self, Diagnostic> {
        let s = &spec.system;
        let grid = spec.integrator.grid;
        let problem =
            start::constrained_problem(spec, lagrangian, &s.constraint)?.with_force(force);
        let options = SolveOptions {
            newton: spec.integrator.newton,
            // The observer stores the samples; the core keeps only the first and the last.
            run: marsden::RunOptions { stride: usize::MAX },
            general_path: !spec.integrator.fast_paths,
            compensated: spec.integrator.compensated,
        };
        let system = StreamSystem {
            lagrangian: Some(lagrangian),
            n: lagrangian.dof(),
            constraint: &s.constraint,
            maps: s.symmetries.as_slice(),
        };
        let rows = StreamRows {
            sink: destination.sink,
            with_velocity: destination.with_velocity,
            every: spec.output.every,
            total: grid.steps,
        };
        let stream = StreamObserver::new(system, rows, controls)
            .monitoring_every_step(spec.analysis.every_step)
            .with_observables(&spec.events.observables);
        let observables = &spec.events.observables;
        let samples = TimeSamples::new(lagrangian, &spec.output, observables, destination.samples)?;
        let watched = Watched::new(stream, lagrangian, &spec.events, destination.events)?;
        let mut observer = watched.with_samples(samples);
        if let Some(c) = destination.checkpoints.and_then(|p| p.resume.as_deref()) {
            let restored = (observer.inner.restore(&c.stream))
                .and_then(|()| observer.restore(c.events.as_ref()))
                .and_then(|()| observer.restore_samples(c.samples.as_ref()));
            restored.map_err(|e| Diagnostic::new(format!("cannot resume the run: {e}")))?;
        }
        Ok(Session {
            problem,
            options,
            observer,
            clock: Instant::now(),
            jit_before: marsden_problem::model::jit_compile_seconds(),
        })
    }

    /// The record of the run that ended with `result`, with its balances; and the problem,
    /// for the certificates.
    fn finish(
        self,
        result: Result<Trajectory, Box<RunFailure>>,
        balance: Option<Balances>,
    ) -> (RunRecord, Problem<&'a L, &'a F, &'a ExprConstraint>) {
        let wall_seconds = self.clock.elapsed().as_secs_f64();
        let (stream, events, samples) = self.observer.into_parts();
        let mut record = finish(stream, result, wall_seconds);
        record.jit_compile_seconds =
            marsden_problem::model::jit_compile_seconds() - self.jit_before;
        let io_errors = [
            &events.io_error,
            &samples.as_ref().and_then(|s| s.io_error.clone()),
        ];
        if let Some(e) = io_errors.into_iter().flatten().next() {
            record.error.get_or_insert_with(|| e.clone());
        }
        record.events = events;
        record.samples = samples;
        if let Some(b) = balance {
            (record.balance, record.balance_series) = (Some(b.energy), Some(b.series));
            record.noether_balance = b.noether;
        }
        (record, self.problem)
    }
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
        jit_compile_seconds: 0.0,
        rows: observer.rows(),
        diagnostics: observer.diagnostics,
        balance: None,
        balance_series: None,
        noether_balance: Vec::new(),
        certificate: None,
        rigid: None,
        multibody: None,
        events: EventTally::default(),
        samples: None,
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

/// The two ends of a run for its certificates: the problem's start and the last good state.
struct RunEnds<'p> {
    start: &'p marsden::State,
    v0: &'p [f64],
    end: marsden::State,
}

impl<'p> RunEnds<'p> {
    fn of<L: Lagrangian, F: Force, C: Constraint>(
        problem: &'p Problem<L, F, C>,
        record: &RunRecord,
    ) -> Self {
        let f = &record.final_state;
        RunEnds {
            start: problem.start(),
            v0: problem.initial_velocity(),
            end: marsden::State {
                t: f.t,
                q: f.q.clone(),
                p: f.p.clone(),
            },
        }
    }

    fn view(&self) -> Ends<'_> {
        Ends {
            start: self.start,
            v0: self.v0,
            end: &self.end,
        }
    }
}

/// The names of the file's symmetries, in its order.
fn symmetry_names(spec: &RunSpec) -> Vec<String> {
    (spec.system.symmetries.iter())
        .map(|m| MomentumMap::name(m).to_owned())
        .collect()
}
