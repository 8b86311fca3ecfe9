//! `marsden run FILE [--steps N] [--h H] [--out DIR] [--quiet] [--no-progress]`.

use super::RunArgs;
use crate::error::{CliError, Status};
use crate::{problem, run};

/// Runs the problem file; status 1 if the simulation failed (results still written).
pub fn run(args: &RunArgs) -> Result<Status, CliError> {
    let spec = problem::load(&args.file.file, &args.file.overrides())?;
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
