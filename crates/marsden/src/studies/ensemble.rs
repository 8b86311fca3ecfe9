//! Ensembles: many independent runs (initial conditions, parameter sets) in parallel.
//!
//! Each member is run on the current [rayon] pool by a function of its index and its data; the
//! results come back **in member order**, one [`Member`] each with its own `Result`, so one
//! failing member is reported and the others go on. Members share nothing mutable: every
//! member builds its own integrator and buffers, so the results are bit for bit the same
//! whatever the number of threads (test `ensemble_is_independent_of_thread_count`). To choose
//! the number of threads, run inside a local pool:
//!
//! ```
//! use marsden::studies::ensemble;
//!
//! let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
//! let squares = pool.install(|| {
//!     ensemble::run(&[1.0, 2.0, -1.0], |_, x: &f64| {
//!         if *x > 0.0 { Ok(x * x) } else { Err(format!("{x} is not positive")) }
//!     })
//! });
//! assert_eq!(squares[1].result, Ok(4.0));
//! assert_eq!(squares[2].index, 2);
//! assert!(squares[2].result.is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [`solve`] runs an ensemble of [`Problem`]s and reports for each member its final state, the
//! energy error and drift of its stored samples ([`EnergyReport`]) and its work counters.

use rayon::prelude::*;

use crate::analysis::diagnostics::EnergyReport;
use crate::discrete::rules::Rule;
use crate::error::Error;
use crate::integrator::Statistics;
use crate::mechanics::{Constraint, Force, Lagrangian};
use crate::run::{Problem, SolveOptions};

/// The outcome of one member, with its index in the ensemble.
#[derive(Debug, Clone, PartialEq)]
pub struct Member<T, E> {
    /// Position of the member in the ensemble (0-based).
    pub index: usize,
    /// What the member produced, or why it failed.
    pub result: Result<T, E>,
}

/// Runs `f(index, member)` for every member on the current rayon pool; the results are in
/// member order. `f` must not panic (errors are values): a panic would end the whole ensemble.
pub fn run<M, T, E, F>(members: &[M], f: F) -> Vec<Member<T, E>>
where
    M: Sync,
    T: Send,
    E: Send,
    F: Fn(usize, &M) -> Result<T, E> + Sync,
{
    members
        .par_iter()
        .enumerate()
        .map(|(index, member)| Member {
            index,
            result: f(index, member),
        })
        .collect()
}

/// Like [`run`] for members made from their index (nothing is built in advance).
///
/// ```
/// let members = marsden::studies::ensemble::run_indexed(4, |k| Ok::<_, ()>(k * k));
/// let squares: Vec<usize> = members.into_iter().filter_map(|m| m.result.ok()).collect();
/// assert_eq!(squares, [0, 1, 4, 9]);
/// ```
pub fn run_indexed<T, E, F>(count: usize, f: F) -> Vec<Member<T, E>>
where
    T: Send,
    E: Send,
    F: Fn(usize) -> Result<T, E> + Sync,
{
    (0..count)
        .into_par_iter()
        .map(|index| Member {
            index,
            result: f(index),
        })
        .collect()
}

/// What one member of a problem ensemble did.
#[derive(Debug, Clone, PartialEq)]
pub struct MemberReport {
    /// Steps completed.
    pub steps: usize,
    /// Time of the final state.
    pub t: f64,
    /// Final positions.
    pub q: Vec<f64>,
    /// Final momenta.
    pub p: Vec<f64>,
    /// Energy error and drift over the stored samples (every `stride`-th step).
    pub energy: EnergyReport,
    /// Newton work of the run.
    pub statistics: Statistics,
}

/// Why a member failed, and how far it got.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{error} (after {steps} steps, last good state at t = {t})")]
pub struct MemberFailure {
    /// What went wrong (a step that failed, or an energy that could not be evaluated).
    pub error: Error,
    /// Steps completed before the failure.
    pub steps: usize,
    /// Time of the last good state (NaN if there is none).
    pub t: f64,
}

/// Solves every problem with `rule` and `options` in parallel; each member keeps only the
/// samples of `options.run.stride` (so memory per member is bounded by the stride) and reports
/// its final state and energy diagnostics.
///
/// ```
/// use marsden::studies::ensemble;
/// use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, systems::Pendulum};
///
/// let grid = TimeGrid::new(0.0, 0.05, 200)?;
/// let problems = [0.5, 1.0, 1.5]
///     .map(|q0| Problem::new(Pendulum::default(), Initial::velocity(&[q0], &[0.0]), grid));
/// let problems: Vec<_> = problems.into_iter().collect::<Result<_, _>>()?;
/// let members = ensemble::solve(&problems, &Midpoint, &SolveOptions::default());
/// for member in &members {
///     let report = member.result.as_ref().map_err(|e| e.to_string())?;
///     assert_eq!(report.steps, 200);
///     assert!(report.energy.max_rel_error < 1e-2);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn solve<L, F, C, R>(
    problems: &[Problem<L, F, C>],
    rule: &R,
    options: &SolveOptions,
) -> Vec<Member<MemberReport, MemberFailure>>
where
    L: Lagrangian + Sync,
    F: Force + Sync,
    C: Constraint + Sync,
    R: Rule + Sync,
{
    run(problems, |_, problem| solve_one(problem, rule, options))
}

/// One member: solve, then the energy of the stored samples.
fn solve_one<L: Lagrangian, F: Force, C: Constraint, R: Rule>(
    problem: &Problem<L, F, C>,
    rule: &R,
    options: &SolveOptions,
) -> Result<MemberReport, MemberFailure> {
    let trajectory = problem.solve(rule, options).map_err(|failure| {
        let last = failure.trajectory.times.last().copied();
        MemberFailure {
            steps: failure.trajectory.steps,
            t: last.unwrap_or(f64::NAN),
            error: failure.error,
        }
    })?;
    let last = trajectory.len().checked_sub(1);
    let t = last.map_or(f64::NAN, |i| trajectory.t(i));
    let energy =
        EnergyReport::of(problem.lagrangian(), &trajectory).map_err(|error| MemberFailure {
            error,
            steps: trajectory.steps,
            t,
        })?;
    let (q, p) = last.map_or((Vec::new(), Vec::new()), |i| {
        (trajectory.q(i).to_vec(), trajectory.p(i).to_vec())
    });
    Ok(MemberReport {
        steps: trajectory.steps,
        t,
        q,
        p,
        energy,
        statistics: trajectory.statistics,
    })
}
