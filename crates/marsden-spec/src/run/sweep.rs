//! `marsden run` on a file with `[sweep]`: every member (or those of one `--shard`) run in
//! parallel with [`marsden::studies::ensemble`], one summary row each, on stdout and in `sweep.csv`.
//!
//! A member is the problem file with the swept value replaced ([`crate::problem::member`]),
//! checked and run like a single file but without writing its trajectory: the rows of the
//! [`StreamObserver`](super::observer::StreamObserver) (every `[output] every`-th step) only
//! feed the energy diagnostics. A member that cannot start or fails is a row with status
//! `failed` and its message; the others run on. Rows are in member order whatever the number
//! of threads.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use marsden::studies::ensemble;

use super::controls::Controls;
use super::execute::{Outcome, Store};
use super::samples::NullSink;
use super::shard::Shard;
use super::solve::{Destination, RunRecord, Runner};
use super::summary::RunStatus;
use super::sweep_table::{self, SweepRow};
use crate::error::{Diagnostic, Error};
use crate::problem::{self, Overrides, RunSpec, SweepSpec};

/// The message of a member that did not run because the sweep was stopped.
pub const NOT_RUN: &str = "not run: the sweep was interrupted";

/// What `marsden run` did with a sweep.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// One row per member run, in member order.
    pub rows: Vec<SweepRow>,
    /// The name of the swept value.
    pub label: String,
    /// Where `sweep.csv` (or `sweep.shard-i-of-n.csv`) and the summary are.
    pub dir: PathBuf,
    /// The files written in `dir`.
    pub files: Vec<String>,
    /// Members in the whole sweep.
    pub total: usize,
}

impl SweepOutcome {
    /// Number of members that did not complete (failed or interrupted).
    pub fn failed(&self) -> usize {
        self.rows
            .iter()
            .filter(|r| r.status != RunStatus::Completed)
            .count()
    }
}

/// How to run a sweep.
#[derive(Debug, Clone, Default)]
pub struct SweepOptions {
    /// Which members.
    pub shard: Shard,
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
    /// Set it to stop the members running and skip the others (their rows say [`NOT_RUN`]).
    pub stop: Option<Arc<AtomicBool>>,
}

/// Runs the members of `base`'s sweep selected by `options.shard` and writes the table.
///
/// # Errors
/// Bad input if the thread pool or the output directory cannot be made; failed if the table
/// cannot be written. Failing members are rows, not errors.
pub fn execute(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    options: &SweepOptions,
) -> Result<SweepOutcome, Error> {
    let rows = run_members(base, sweep, overrides, options)?;
    let dir = base.output.dir.clone();
    std::fs::create_dir_all(&dir).map_err(|e| {
        Diagnostic::new(format!(
            "cannot create the output directory {}: {e}",
            dir.display()
        ))
    })?;
    let label = sweep.target.label();
    let files = sweep_table::write(&dir, options.shard, &label, &rows, sweep.values.len())
        .map_err(|e| Error::failed(Diagnostic::new(e)))?;
    Ok(SweepOutcome {
        rows,
        label,
        dir,
        files,
        total: sweep.values.len(),
    })
}

/// Runs the members of `base`'s sweep selected by `options.shard` in parallel and returns
/// their rows, in member order (nothing is written).
///
/// # Errors
/// Bad input if the thread pool cannot be made. Failing members are rows, not errors.
pub fn run_members(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    options: &SweepOptions,
) -> Result<Vec<SweepRow>, Error> {
    let members = options.shard.members(sweep.values.len());
    let stop = &options.stop;
    let run_all = || {
        ensemble::run(&members, |_, &k| {
            let controls = Controls {
                progress: None,
                stop: stop.clone(),
            };
            match controls.stop_requested() {
                true => Ok(None),
                false => run_member(base, overrides, k, &controls)
                    .map(Some)
                    .map_err(|d| d.message),
            }
        })
    };
    let results = match options.threads {
        None => run_all(),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| Diagnostic::new(format!("cannot start {n} worker threads: {e}")))?
            .install(run_all),
    };
    let steps = base.integrator.grid.steps;
    Ok(results
        .into_iter()
        .map(|m| {
            let k = members[m.index];
            match m.result {
                Ok(Some(record)) => SweepRow::new(k, sweep.values[k], steps, Ok(record)),
                Ok(None) => SweepRow::not_run(k, sweep.values[k], steps, NOT_RUN),
                Err(message) => SweepRow::new(k, sweep.values[k], steps, Err(message)),
            }
        })
        .collect())
}

/// Runs every member of `base`'s sweep in parallel and keeps each one's samples in memory
/// ([`Store::Memory`]): what a binding returns, one [`Outcome`] per member in member order.
/// A member is built exactly as [`run_members`] builds it ([`member_outcome`]), so each
/// outcome equals the one of that member run alone, bit for bit.
///
/// # Errors
/// Bad input if the thread pool cannot be made. A member that cannot start is an `Err` in its
/// place, a failing member an outcome whose status is failed; `Ok(None)`: not run, the sweep
/// was stopped.
pub fn member_outcomes(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    options: &SweepOptions,
) -> Result<Vec<Result<Option<Outcome>, Error>>, Error> {
    let members = options.shard.members(sweep.values.len());
    let stop = &options.stop;
    let run_all = || {
        ensemble::run(&members, |_, &k| {
            let controls = Controls {
                progress: None,
                stop: stop.clone(),
            };
            match controls.stop_requested() {
                true => Ok(None),
                false => member_outcome(base, overrides, k, &controls).map(Some),
            }
        })
    };
    let results = match options.threads {
        None => run_all(),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| Diagnostic::new(format!("cannot start {n} worker threads: {e}")))?
            .install(run_all),
    };
    Ok(results.into_iter().map(|m| m.result).collect())
}

/// Member `k` of `base`'s sweep, run alone with its samples in memory.
///
/// # Errors
/// The member cannot start (a value the problem cannot take).
pub fn member_outcome(
    base: &RunSpec,
    overrides: &Overrides,
    k: usize,
    controls: &Controls<'_>,
) -> Result<Outcome, Error> {
    let spec = problem::member(base, overrides, k)?;
    super::execute::execute(&spec, Store::Memory, controls)
}

/// Builds, checks and runs member `k` (no trajectory written).
fn run_member(
    base: &RunSpec,
    overrides: &Overrides,
    k: usize,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic> {
    let spec = problem::member(base, overrides, k)?;
    super::start::prepare(&spec)?;
    let mut sink = NullSink::default();
    let destination = Destination {
        sink: &mut sink,
        with_velocity: false,
    };
    Runner {
        spec: &spec,
        destination,
        controls,
    }
    .run()
}
