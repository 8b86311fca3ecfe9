//! The run of a `discrete_lagrangian` file: the core's integrator built from the file's own
//! [`ExprDiscreteLagrangian`] (general Newton path: the discrete Legendre transforms
//! `p_k = −D₁L_d(q_k, q_{k+1})`, `p_{k+1} = D₂L_d(q_k, q_{k+1})`, [MW01] §1.3), streamed by the
//! same observer as every run, without an energy: there is no continuous `L` to define one.
//! Momentum maps `J(q, p)` are monitored as usual.
//!
//! [MW01]: marsden#references

use std::time::Instant;

use marsden::{DiscreteLagrangian as _, Integrator, RunFailure, State, Trajectory, simulate};

use crate::controls::Controls;
use crate::observer::{StreamObserver, StreamRows, StreamSystem};
use crate::solve::{Destination, RunRecord, finish};
use marsden_problem::error::Diagnostic;
use marsden_problem::model::{ExprDiscreteLagrangian, ExprLagrangian};
use marsden_problem::problem::{InitialData, RunSpec};

/// Runs `spec`, whose system is the discrete Lagrangian `ld`, streaming rows into
/// `destination`.
///
/// # Errors
/// Initial data given as velocities (refused when the file was read; said again for a spec
/// built otherwise). A failing run is a [`RunRecord`] with an error message, not an `Err`.
pub fn run(
    ld: &ExprDiscreteLagrangian,
    spec: &RunSpec,
    destination: Destination<'_>,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic> {
    let InitialData::Momentum(p) = &spec.initial.data else {
        return Err(Diagnostic::new(
            "a `discrete_lagrangian` run starts from momenta `p`, not velocities",
        ));
    };
    let start = State {
        t: spec.initial.t0,
        q: spec.initial.q.clone(),
        p: p.clone(),
    };
    let (grid, n) = (spec.integrator.grid, ld.dof());
    let s = &spec.system;
    // No continuous Lagrangian: the observer's type parameter is never used for a value.
    let system = StreamSystem {
        lagrangian: None::<&ExprLagrangian>,
        n,
        constraint: &s.constraint,
        maps: s.symmetries.as_slice(),
    };
    let rows = StreamRows {
        sink: destination.sink,
        with_velocity: destination.with_velocity,
        every: spec.output.every,
        total: grid.steps,
    };
    let mut observer = StreamObserver::new(system, rows, controls)
        .monitoring_every_step(spec.analysis.every_step)
        .with_observables(&spec.events.observables);
    let (clock, jit_before) = (
        Instant::now(),
        marsden_problem::model::jit_compile_seconds(),
    );
    let result = solve(ld.clone(), spec, start, &mut observer);
    let mut record = finish(observer, result, clock.elapsed().as_secs_f64());
    record.jit_compile_seconds = marsden_problem::model::jit_compile_seconds() - jit_before;
    Ok(record)
}

/// Steps `ld` over the spec's grid from `start`, with the file's Newton options and summation.
fn solve<O: marsden::Observer>(
    ld: ExprDiscreteLagrangian,
    spec: &RunSpec,
    start: State,
    observer: &mut O,
) -> Result<Trajectory, Box<RunFailure>> {
    let i = &spec.integrator;
    let failure = |error| {
        let trajectory = Trajectory::new(ld.dof(), 0, i.grid.h);
        Box::new(RunFailure { error, trajectory })
    };
    let mut integrator = Integrator::new(ld.clone())
        .with_options(i.newton)
        .map_err(failure)?
        .with_compensated_summation(i.compensated);
    let options = marsden::RunOptions { stride: usize::MAX };
    simulate(&mut integrator, start, &i.grid, &options, observer).into_result()
}
