//! `marsden run` on a file with `[sweep]`: every member (or those of one `--shard`) run in
//! parallel with [`marsden::studies::ensemble`], one summary row each, streamed to `sweep.csv`
//! (or `sweep.npy`) chunk by chunk so memory does not grow with the number of members, and
//! shown on stdout (the first rows and the first failures).
//!
//! A member is the problem file with the swept values replaced ([`crate::problem::member`]),
//! checked and run like a single file but without writing its trajectory: the rows of the
//! [`StreamObserver`](super::observer::StreamObserver) (every `[output] every`-th step) only
//! feed the diagnostics. A member that cannot start or fails is a row with status `failed`
//! and its message; the others run on. Rows are in member order whatever the number of
//! threads.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use marsden::studies::ensemble;

use super::controls::Controls;
use super::execute::{Outcome, Store};
use super::samples::NullSink;
use super::shard::Shard;
use super::solve::{Destination, RunRecord};
use super::summary::RunStatus;
use super::sweep_checkpoint::{self, SweepCheckpoint};
use super::sweep_table::{SweepColumns, SweepRow};
use super::sweep_writer::SweepWriter;
use crate::error::{Diagnostic, Error};
use crate::problem::{self, Overrides, RunSpec, SweepSpec};

/// The message of a member that did not run because the sweep was stopped.
pub const NOT_RUN: &str = "not run: the sweep was interrupted";

/// What `marsden run` did with a sweep.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The rows to show, in member order: the first `SHOWN` (20) members' and up to as many
    /// more that did not complete (the table file has every row).
    pub rows: Vec<SweepRow>,
    /// The table's columns.
    pub columns: SweepColumns,
    /// The names of the swept values, joined (`l` or `l × q[0]`).
    pub label: String,
    /// Where the table and the summary are.
    pub dir: PathBuf,
    /// The files written in `dir`.
    pub files: Vec<String>,
    /// Members in the whole sweep.
    pub total: usize,
    /// Members run here (this shard's).
    pub members_run: usize,
    /// Members that failed.
    pub failed: usize,
    /// Members interrupted or not run because the sweep was stopped.
    pub interrupted: usize,
    /// Problems that did not stop the sweep (a plot not drawn).
    pub warnings: Vec<String>,
}

/// Rows shown on the console: the first ones, and as many of the failures after them.
pub const SHOWN: usize = 20;

/// Members run between two writes of the table.
const CHUNK: usize = 4096;

impl SweepOutcome {
    /// Number of members that did not complete (failed or interrupted).
    pub fn not_completed(&self) -> usize {
        self.failed + self.interrupted
    }

    /// Rows in the table file but not in [`Self::rows`].
    pub fn hidden(&self) -> usize {
        self.members_run - self.rows.len()
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
    /// The checkpoint the sweep resumes from (`marsden resume`): its table is cut back to it
    /// and the members after it run.
    pub resume: Option<Box<SweepCheckpoint>>,
}

/// Runs the members of `base`'s sweep selected by `options.shard` and writes the table
/// (streamed, `CHUNK` members at a time), its summary and, with `[output] plots` on the
/// whole sweep, `sweep.png`.
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
    let pool = pool(options.threads)?;
    let dir = base.output.dir.clone();
    std::fs::create_dir_all(&dir).map_err(|e| {
        Diagnostic::new(format!(
            "cannot create the output directory {}: {e}",
            dir.display()
        ))
    })?;
    // Held until the summary is written: the same sweep (or shard) into `dir` is refused.
    let lock_name = format!(".marsden{}.lock", options.shard.suffix());
    let _lock = super::output::lock_named(&dir, &lock_name).map_err(|m| {
        Error::bad_input(Diagnostic::new(m).help("give this sweep another `--out` directory"))
    })?;
    let columns = SweepColumns::of(base, sweep);
    let failed = |e: String| Error::failed(Diagnostic::new(e));
    let (mut writer, done) = open_table(base, &dir, &columns, options)?;
    let checkpoints = base.output.checkpoint_every.is_some();
    let identity = checkpoints.then(|| super::resume::identity(base));
    let chunk_size = match checkpoints {
        true => {
            2 * pool
                .as_ref()
                .map_or_else(rayon::current_num_threads, |p| p.current_num_threads())
        }
        false => CHUNK,
    };
    let mut shown = Vec::new();
    let mut members = options.shard.iter(sweep.count()).skip(done);
    loop {
        let chunk: Vec<usize> = members.by_ref().take(chunk_size).collect();
        if chunk.is_empty() {
            break;
        }
        let rows = run_rows(base, sweep, overrides, &chunk, options, pool.as_ref());
        let whole = rows.iter().all(|r| r.status != RunStatus::Interrupted);
        for row in rows {
            writer.push(&row).map_err(failed)?;
            keep(&mut shown, row);
        }
        if let (Some(identity), true) = (&identity, whole) {
            let (table, counts) = writer.mark().map_err(failed)?;
            let shard = (options.shard.index, options.shard.count);
            let checkpoint = SweepCheckpoint {
                identity: identity.clone(),
                shard,
                table,
                counts,
            };
            sweep_checkpoint::save(&dir, &checkpoint).map_err(failed)?;
        }
    }
    let (members_run, failed_count, interrupted) = writer.counts();
    let mut files = writer.finish(sweep.count(), base).map_err(failed)?;
    let mut warnings = Vec::new();
    if base.output.plots && options.shard == Shard::ALL && members_run > 0 {
        match super::plots::draw_sweep(&dir) {
            Ok(report) => files.extend(
                report
                    .path
                    .file_name()
                    .map(|f| f.to_string_lossy().into_owned()),
            ),
            Err(e) => warnings.push(format!("the sweep plot was not drawn: {e}")),
        }
    }
    Ok(SweepOutcome {
        rows: shown,
        columns,
        label: sweep.label(),
        dir,
        files,
        total: sweep.count(),
        members_run,
        failed: failed_count,
        interrupted,
        warnings,
    })
}

/// The table of the sweep, created, or reopened at the checkpoint it resumes from; and the
/// number of the shard's members already in it.
fn open_table(
    base: &RunSpec,
    dir: &std::path::Path,
    columns: &SweepColumns,
    options: &SweepOptions,
) -> Result<(SweepWriter, usize), Error> {
    let format = base.output.format;
    let failed = |e: String| Error::failed(Diagnostic::new(e));
    match &options.resume {
        Some(c) => {
            let (shard, counts) = (options.shard, c.counts.clone());
            let writer = SweepWriter::reopen(dir, shard, columns.clone(), format, &c.table, counts)
                .map_err(|e| Error::bad_input(Diagnostic::new(e)))?;
            Ok((writer, c.counts.rows))
        }
        None => {
            sweep_checkpoint::remove_stale(dir, options.shard).map_err(failed)?;
            let writer =
                SweepWriter::create(dir, options.shard, columns.clone(), format).map_err(failed)?;
            Ok((writer, 0))
        }
    }
}

/// Keeps `row` for the console if it is among the first [`SHOWN`], or among the first
/// [`SHOWN`] after them that did not complete.
fn keep(shown: &mut Vec<SweepRow>, row: SweepRow) {
    let later_failures = shown.iter().skip(SHOWN).count();
    if shown.len() < SHOWN || (row.status != RunStatus::Completed && later_failures < SHOWN) {
        shown.push(row);
    }
}

/// A pool of `threads` workers (`None`: rayon's global pool, one worker per core).
fn pool(threads: Option<usize>) -> Result<Option<rayon::ThreadPool>, Error> {
    threads
        .map(|n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| {
                    Diagnostic::new(format!("cannot start {n} worker threads: {e}")).into()
                })
        })
        .transpose()
}

/// Runs `f` in `pool` (or the global pool).
fn in_pool<T: Send>(pool: Option<&rayon::ThreadPool>, f: impl FnOnce() -> T + Send) -> T {
    match pool {
        None => f(),
        Some(p) => p.install(f),
    }
}

/// Runs the members `ks` of `base`'s sweep in parallel; their rows in the order of `ks`.
fn run_rows(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    ks: &[usize],
    options: &SweepOptions,
    pool: Option<&rayon::ThreadPool>,
) -> Vec<SweepRow> {
    let stop = &options.stop;
    let results = in_pool(pool, || {
        ensemble::run(ks, |_, &k| {
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
    });
    let steps = base.integrator.grid.steps;
    let conserved = base.system.energy_not_conserved().is_none();
    results
        .into_iter()
        .map(|m| {
            let k = ks[m.index];
            let values = sweep.values_of(k);
            match m.result {
                Ok(Some(record)) => SweepRow::new(k, values, steps, conserved, Ok(record)),
                Ok(None) => SweepRow::not_run(k, values, steps, NOT_RUN),
                Err(message) => SweepRow::new(k, values, steps, conserved, Err(message)),
            }
        })
        .collect()
}

/// Runs the members of `base`'s sweep selected by `options.shard` in parallel and returns
/// their rows, in member order (nothing is written; every row is held in memory).
///
/// # Errors
/// Bad input if the thread pool cannot be made. Failing members are rows, not errors.
pub fn run_members(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    options: &SweepOptions,
) -> Result<Vec<SweepRow>, Error> {
    let pool = pool(options.threads)?;
    let members = options.shard.members(sweep.count());
    Ok(run_rows(
        base,
        sweep,
        overrides,
        &members,
        options,
        pool.as_ref(),
    ))
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
    let pool = pool(options.threads)?;
    let members = options.shard.members(sweep.count());
    let stop = &options.stop;
    let results = in_pool(pool.as_ref(), || {
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
    });
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
    let engine = crate::engine_for(&spec);
    engine.prepare(&spec)?;
    let mut sink = NullSink::default();
    let destination = Destination {
        sink: &mut sink,
        with_velocity: false,
        events: None,
        // `times` is refused with `[sweep]` when the file was read.
        samples: None,
        // Refused with `[sweep]` when the file was read.
        checkpoints: None,
    };
    engine.run(&spec, destination, controls)
}
