//! `marsden run FILE [--steps N] [--h H] [--out DIR] [--quiet] [--no-progress]
//! [--shard I/N] [--threads N]`.
//!
//! Ctrl-C stops the run within 256 steps (a sweep: its running members, the others are not
//! started); what was computed is written, with status "interrupted", and the command exits
//! with 1. A second Ctrl-C ends the process at once (130).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use marsden_spec::report::sweep_table;
use marsden_spec::sweep::{self, SweepOptions, SweepOutcome};
use marsden_spec::{Controls, Diagnostic, Progress, RunSpec, RunStatus, Store, SweepSpec, report};

use super::RunArgs;
use crate::error::{CliError, Status};
use crate::progress::Bar;

/// Runs the problem file (or its sweep); status 1 if the simulation (or a member) failed,
/// results still written.
pub fn run(args: &RunArgs) -> Result<Status, CliError> {
    let spec = marsden_spec::load(&args.file.file, &args.file.overrides())?;
    if let Some(sweep) = &spec.sweep {
        return run_sweep(args, &spec, sweep);
    }
    if args.shard.is_some() || args.threads.is_some() {
        let flag = if args.shard.is_some() {
            "--shard"
        } else {
            "--threads"
        };
        return Err(CliError::bad_input(
            Diagnostic::new(format!(
                "{flag} applies to sweeps, but the problem file has no [sweep] table"
            ))
            .help("add [sweep] with `parameter = \"...\"` and `values = [...]`"),
        ));
    }
    let outcome = with_controls(args.no_progress, |controls| {
        marsden_spec::execute(&spec, Store::Files, controls)
    })?;
    Ok(conclude(&spec, &outcome, args.quiet))
}

/// Runs `body` with the progress bar (unless `no_progress`) and Ctrl-C watched.
pub(super) fn with_controls<T>(no_progress: bool, body: impl FnOnce(&Controls<'_>) -> T) -> T {
    let bar = Bar::new(!no_progress);
    let update = |p: Progress| {
        if let Some(bar) = &bar {
            bar.update(p);
        }
    };
    let controls = Controls {
        progress: bar.is_some().then_some(&update as &dyn Fn(Progress)),
        stop: stop_on_ctrl_c(),
    };
    body(&controls)
}

/// Prints what a run came to (unless `quiet`) and its exit status.
pub(super) fn conclude(spec: &RunSpec, outcome: &marsden_spec::Outcome, quiet: bool) -> Status {
    for warning in &outcome.warnings {
        eprintln!("warning: {warning}");
    }
    if !quiet {
        print!("{}", report::run::render(outcome));
        if let Some(sensitivity) = &outcome.summary.sensitivity {
            println!("{}", marsden_spec::sensitivity::describe(sensitivity));
        }
    }
    let s = &outcome.summary;
    let dir = spec.output.dir.display();
    match (&s.error, s.status) {
        (None, RunStatus::Completed | RunStatus::Stopped) => Status::Completed,
        (Some(e), _) => {
            eprintln!(
                "error: the simulation failed after {} of {} steps: {e}\n  = note: the partial \
                 trajectory and summary.json (status \"failed\") are in {dir}",
                s.steps, s.steps_requested,
            );
            Status::Failed
        }
        (None, _) => {
            // The run's steps all taken, its tangent run (`[sensitivity]`) stopped.
            let when = match s.sensitivity.as_ref().and_then(|b| b.error.as_deref()) {
                Some(why) if s.steps == s.steps_requested => format!("in its tangent run ({why})"),
                _ => format!("after {} of {} steps", s.steps, s.steps_requested),
            };
            eprintln!(
                "error: the run was interrupted {when}\n  = note: the partial trajectory and \
                 summary.json (status \"interrupted\") are in {dir}",
            );
            if spec.output.checkpoint_every.is_some() {
                eprintln!("  = help: `marsden resume {dir}` continues it from its last checkpoint");
            }
            Status::Failed
        }
    }
}

fn run_sweep(args: &RunArgs, spec: &RunSpec, sweep: &SweepSpec) -> Result<Status, CliError> {
    let options = SweepOptions {
        shard: args.shard.unwrap_or_default(),
        threads: args.threads.map(usize::from),
        stop: stop_on_ctrl_c(),
        resume: None,
    };
    let outcome = sweep::execute(spec, sweep, &args.file.overrides(), &options)?;
    Ok(conclude_sweep(spec, &outcome, args.quiet))
}

/// Prints what a sweep came to (unless `quiet`) and its exit status.
pub(super) fn conclude_sweep(spec: &RunSpec, outcome: &SweepOutcome, quiet: bool) -> Status {
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    if !quiet {
        println!(
            "{}: sweep of {} over {} member{} ({} run here), {}",
            spec.name,
            outcome.label,
            outcome.total,
            plural(outcome.total),
            outcome.members_run,
            spec.integrator.method
        );
        print!("{}", sweep_table::render(&outcome.columns, &outcome.rows));
        if outcome.hidden() > 0 {
            println!(
                "… {} more row{} in {}",
                outcome.hidden(),
                plural(outcome.hidden()),
                outcome.files[0]
            );
        }
        println!(
            "wrote {} in {}",
            outcome.files.join(", "),
            outcome.dir.display()
        );
    }
    for w in &outcome.warnings {
        eprintln!("warning: {w}");
    }
    let table = outcome.dir.join(&outcome.files[0]);
    match (outcome.not_completed(), outcome.interrupted) {
        (0, _) => Status::Completed,
        (n, 1..) => {
            eprintln!(
                "error: the sweep was interrupted: {n} of {} member{} did not complete (rows \
                 with status \"interrupted\" or \"failed\" in {})",
                outcome.members_run,
                plural(outcome.members_run),
                table.display()
            );
            Status::Failed
        }
        (n, 0) => {
            eprintln!(
                "error: {n} of {} member{} failed (rows with status \"failed\" in {})",
                outcome.members_run,
                plural(outcome.members_run),
                table.display()
            );
            Status::Failed
        }
    }
}

/// A flag that the first Ctrl-C sets (the second one exits with 130); `None` if the handler
/// cannot be installed (then Ctrl-C ends the process as usual).
pub(super) fn stop_on_ctrl_c() -> Option<Arc<AtomicBool>> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let handler = move || {
        if flag.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    };
    ctrlc::set_handler(handler).ok().map(|()| stop)
}
