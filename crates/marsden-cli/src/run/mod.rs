//! Running a validated problem: build it, stream the trajectory to disk through an observer,
//! then write the summary and the plots.
//!
//! * [`run_problem`] — the generic runner: `Problem` from any [`Lagrangian`], [`Force`] and
//!   [`Constraint`], solved with the file's method while [`observer::StreamObserver`] writes
//!   the rows; catalog systems and expressions reach it through
//!   [`crate::catalog::WithLagrangian`].
//! * [`execute`] — the whole `marsden run`: directories, writer, runner, plots, summary.
//! * [`output`] (columns, writers), [`diagnostics`], [`progress`], [`start`] (the initial
//!   state), [`summary`] (`summary.json`), [`report`] (the text on stdout).
//! * [`sweep`] — `marsden run` on a file with `[sweep]`: the members in parallel
//!   ([`marsden::studies::ensemble`]), a [`shard`] of them, one row each ([`sweep_table`]).

pub mod diagnostics;
pub mod observer;
pub mod output;
pub mod progress;
pub mod report;
pub mod shard;
pub mod start;
pub mod summary;
pub mod sweep;
pub mod sweep_table;

use std::path::PathBuf;
use std::time::Instant;

use marsden::discrete::rules::WithRule;
use marsden::{
    Constraint, Force, Lagrangian, Observer, Problem, Rule, RunFailure, SolveOptions, Statistics,
    Trajectory,
};
use marsden_io::{PlotOptions, RowSink, plot_run, read_csv, read_npy_dir};

use crate::catalog::WithLagrangian;
use crate::error::{CliError, Diagnostic};
use crate::model::MomentumMap;
use crate::problem::{Format, Method, RunSpec};
use diagnostics::Diagnostics;
use observer::StreamObserver;
use progress::Progress;
use summary::{FinalState, Summary};

/// What a run did, before it is written up.
#[derive(Debug, Clone)]
pub struct RunRecord {
    /// The failure's message (`None`: completed).
    pub error: Option<String>,
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
}

/// Solves `problem` with `method` (dispatch on the rule type: one monomorphised run per rule).
pub fn solve<L: Lagrangian, F: Force, C: Constraint, O: Observer + ?Sized>(
    problem: &Problem<L, F, C>,
    method: &Method,
    options: &SolveOptions,
    observer: &mut O,
) -> Result<Trajectory, Box<RunFailure>> {
    struct Solve<'a, L, F, C, O: ?Sized> {
        problem: &'a Problem<L, F, C>,
        options: &'a SolveOptions,
        observer: &'a mut O,
    }
    impl<L: Lagrangian, F: Force, C: Constraint, O: Observer + ?Sized> WithRule
        for Solve<'_, L, F, C, O>
    {
        type Output = Result<Trajectory, Box<RunFailure>>;
        fn call<R: Rule>(self, rule: &R) -> Self::Output {
            self.problem.solve_with(rule, self.options, self.observer)
        }
    }
    method.dispatch(Solve {
        problem,
        options,
        observer,
    })
}

/// Runs `spec` with the given system parts, streaming rows into `sink`.
///
/// # Errors
/// Only if the core rejects the initial state (already checked by [`start::prepare`]); a
/// failing run is a [`RunRecord`] with an error message, not an `Err`.
pub fn run_problem<L: Lagrangian, F: Force, C: Constraint, M: MomentumMap>(
    (lagrangian, force, constraint, maps): (&L, &F, &C, &[M]),
    spec: &RunSpec,
    sink: &mut dyn RowSink,
    progress: Progress,
) -> Result<RunRecord, Diagnostic> {
    let grid = spec.integrator.grid;
    let problem = start::constrained_problem(spec, lagrangian, constraint)?.with_force(force);
    let options = SolveOptions {
        newton: spec.integrator.newton,
        // The observer stores the samples; the core keeps only the first and the last.
        run: marsden::RunOptions { stride: usize::MAX },
        general_path: !spec.integrator.fast_paths,
        compensated: spec.integrator.compensated,
    };
    let parts = (lagrangian, constraint, maps);
    let mut observer = StreamObserver::new(parts, sink, (spec.output.every, grid.steps), progress);
    let clock = Instant::now();
    let result = solve(&problem, &spec.integrator.method, &options, &mut observer);
    let wall_seconds = clock.elapsed().as_secs_f64();
    observer.progress.finish();
    let (trajectory, error) = match result {
        Ok(t) => (t, None),
        Err(failure) => (failure.trajectory, Some(failure.error.to_string())),
    };
    observer.record_last(&trajectory);
    let io = observer
        .io_error
        .as_ref()
        .map(|e| format!("writing the trajectory failed: {e}"));
    Ok(RunRecord {
        error: error.or(io),
        steps: trajectory.steps,
        final_state: final_state(&trajectory),
        statistics: trajectory.statistics,
        wall_seconds,
        rows: observer.rows(),
        diagnostics: observer.diagnostics,
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

struct Runner<'a> {
    spec: &'a RunSpec,
    sink: &'a mut dyn RowSink,
    progress: Progress,
}

impl WithLagrangian for Runner<'_> {
    type Output = Result<RunRecord, Diagnostic>;
    fn call<L: Lagrangian>(self, lagrangian: &L) -> Self::Output {
        let s = &self.spec.system;
        let parts = (lagrangian, &s.force, &s.constraint, s.symmetries.as_slice());
        run_problem(parts, self.spec, self.sink, self.progress)
    }
}

/// The result of `marsden run`: the summary (also on disk) and remarks for stderr.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// What `summary.json` holds.
    pub summary: Summary,
    /// Where the files are.
    pub dir: PathBuf,
    /// Problems that did not stop the run (a plot that could not be drawn, …).
    pub warnings: Vec<String>,
}

/// `marsden run`: checks the initial state, creates the output directory, runs with streaming
/// output, then draws the plots and writes `summary.json`.
///
/// # Errors
/// Status 2 if the problem cannot start (nothing written); status 1 only if not even the
/// summary could be written. A failed simulation is an `Ok` outcome with status "failed".
pub fn execute(spec: &RunSpec, show_progress: bool) -> Result<Outcome, CliError> {
    let start = start::prepare(spec)?;
    let dir = spec.output.dir.clone();
    let io = |what: &str, e: &dyn std::fmt::Display| {
        CliError::bad_input(Diagnostic::new(format!(
            "cannot {what} {}: {e}",
            dir.display()
        )))
    };
    std::fs::create_dir_all(&dir).map_err(|e| io("create the output directory", &e))?;
    output::clear_previous(&dir).map_err(|e| io("clear the previous results in", &e))?;
    let layout = output::layout(&spec.system).map_err(|e| io("lay out the columns of", &e))?;
    let mut sink = output::open_sink(&dir, spec.output.format, &layout)
        .map_err(|e| io("write the trajectory into", &e))?;
    let progress = Progress::new(spec.integrator.grid.steps, show_progress);
    let runner = Runner {
        spec,
        sink: sink.as_mut(),
        progress,
    };
    let mut record = spec.system.lagrangian.dispatch(runner)?;
    let mut warnings = start.warnings;
    if let Err(e) = sink.finish() {
        record
            .error
            .get_or_insert(format!("writing the trajectory failed: {e}"));
    }
    let mut files = output::trajectory_files(spec.output.format, &layout);
    files.push(output::SUMMARY_JSON.to_owned());
    if spec.output.plots && record.rows > 0 {
        match plot(spec, &layout) {
            Ok(pngs) => files.extend(pngs),
            Err(e) => warnings.push(format!("plots were not drawn: {e}")),
        }
    }
    let columns = layout
        .column_names()
        .into_iter()
        .map(str::to_owned)
        .collect();
    let summary = Summary::new(spec, &record, columns, files);
    summary
        .write(&dir)
        .map_err(|e| CliError::failed(Diagnostic::new(e)))?;
    Ok(Outcome {
        summary,
        dir,
        warnings,
    })
}

/// Reads the trajectory back and draws every plot; returns the PNG file names.
fn plot(spec: &RunSpec, layout: &marsden_io::Layout) -> marsden_io::Result<Vec<String>> {
    let dir = &spec.output.dir;
    let table = match spec.output.format {
        Format::Csv => read_csv(dir.join(output::TRAJECTORY_CSV))?,
        Format::Npy => read_npy_dir(dir, layout)?,
    };
    let reports = plot_run(&table, dir, &PlotOptions::default())?;
    Ok(reports
        .iter()
        .filter_map(|r| r.path.file_name())
        .map(|f| f.to_string_lossy().into_owned())
        .collect())
}
