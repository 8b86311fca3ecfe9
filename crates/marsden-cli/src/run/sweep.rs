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

use marsden::studies::ensemble;
use marsden_io::RowSink;

use super::progress::Progress;
use super::shard::Shard;
use super::sweep_table::{self, SweepRow};
use super::{RunRecord, Runner};
use crate::error::{CliError, Diagnostic};
use crate::problem::{self, Overrides, RunSpec, SweepSpec};

/// A sink that keeps nothing (sweep members write no trajectory).
#[derive(Debug, Default)]
pub struct NullSink {
    rows: u64,
}

impl RowSink for NullSink {
    fn write_row(&mut self, _row: &[f64]) -> marsden_io::Result<()> {
        self.rows += 1;
        Ok(())
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn rows_written(&self) -> u64 {
        self.rows
    }
}

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
    /// Number of members that did not complete.
    pub fn failed(&self) -> usize {
        self.rows.iter().filter(|r| r.error.is_some()).count()
    }
}

/// How to run a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SweepOptions {
    /// Which members.
    pub shard: Shard,
    /// Worker threads (`None`: one per core).
    pub threads: Option<usize>,
}

/// Runs the members of `base`'s sweep selected by `options.shard` and writes the table.
///
/// # Errors
/// Status 2 if the thread pool or the output directory cannot be made; status 1 if the
/// table cannot be written. Failing members are rows, not errors.
pub fn execute(
    base: &RunSpec,
    sweep: &SweepSpec,
    overrides: &Overrides,
    options: SweepOptions,
) -> Result<SweepOutcome, CliError> {
    let members = options.shard.members(sweep.values.len());
    let run_all = || {
        ensemble::run(&members, |_, &k| {
            run_member(base, overrides, k).map_err(|d| d.message)
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
    let rows: Vec<SweepRow> = results
        .into_iter()
        .map(|m| {
            let k = members[m.index];
            SweepRow::new(k, sweep.values[k], base.integrator.grid.steps, m.result)
        })
        .collect();
    let dir = base.output.dir.clone();
    std::fs::create_dir_all(&dir).map_err(|e| {
        Diagnostic::new(format!(
            "cannot create the output directory {}: {e}",
            dir.display()
        ))
    })?;
    let label = sweep.target.label();
    let files = sweep_table::write(&dir, options.shard, &label, &rows, sweep.values.len())
        .map_err(|e| CliError::failed(Diagnostic::new(e)))?;
    Ok(SweepOutcome {
        rows,
        label,
        dir,
        files,
        total: sweep.values.len(),
    })
}

/// Builds, checks and runs member `k` (no trajectory written).
fn run_member(base: &RunSpec, overrides: &Overrides, k: usize) -> Result<RunRecord, Diagnostic> {
    let spec = problem::member(base, overrides, k)?;
    super::start::prepare(&spec)?;
    let mut sink = NullSink::default();
    let runner = Runner {
        spec: &spec,
        sink: &mut sink,
        progress: Progress::new(spec.integrator.grid.steps, false),
    };
    spec.system.lagrangian.dispatch(runner)
}
