//! `marsden run FILE [--steps N] [--h H] [--out DIR] [--quiet] [--no-progress]
//! [--shard I/N] [--threads N]`.

use super::RunArgs;
use crate::error::{CliError, Diagnostic, Status};
use crate::problem::{RunSpec, SweepSpec};
use crate::run::shard::Shard;
use crate::run::sweep::{self, SweepOptions};
use crate::{problem, run};

/// Runs the problem file (or its sweep); status 1 if the simulation (or a member) failed,
/// results still written.
pub fn run(args: &RunArgs) -> Result<Status, CliError> {
    let spec = problem::load(&args.file.file, &args.file.overrides())?;
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
    let outcome = run::execute(&spec, !args.no_progress)?;
    for warning in &outcome.warnings {
        eprintln!("warning: {warning}");
    }
    if !args.quiet {
        print!("{}", run::report::render(&outcome));
    }
    match &outcome.summary.error {
        None => Ok(Status::Completed),
        Some(e) => {
            eprintln!(
                "error: the simulation failed after {} of {} steps: {e}\n  = note: the partial \
                 trajectory and summary.json (status \"failed\") are in {}",
                outcome.summary.steps,
                outcome.summary.steps_requested,
                outcome.dir.display()
            );
            Ok(Status::Failed)
        }
    }
}

fn run_sweep(args: &RunArgs, spec: &RunSpec, sweep: &SweepSpec) -> Result<Status, CliError> {
    let options = SweepOptions {
        shard: args.shard.unwrap_or(Shard::ALL),
        threads: args.threads.map(usize::from),
    };
    let outcome = sweep::execute(spec, sweep, &args.file.overrides(), options)?;
    if !args.quiet {
        println!(
            "{}: sweep of {} over {} member{} ({} run here), {}",
            spec.name,
            outcome.label,
            outcome.total,
            if outcome.total == 1 { "" } else { "s" },
            outcome.rows.len(),
            spec.integrator.method
        );
        print!(
            "{}",
            run::sweep_table::render(&outcome.label, &outcome.rows)
        );
        println!(
            "wrote {} in {}",
            outcome.files.join(", "),
            outcome.dir.display()
        );
    }
    match outcome.failed() {
        0 => Ok(Status::Completed),
        n => {
            eprintln!(
                "error: {n} of {} member{} failed (rows with status \"failed\" in {})",
                outcome.rows.len(),
                if outcome.rows.len() == 1 { "" } else { "s" },
                outcome.dir.join(&outcome.files[0]).display()
            );
            Ok(Status::Failed)
        }
    }
}
