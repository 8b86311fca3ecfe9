//! `marsden check FILE`: validates the problem file and prints the problem as it will run,
//! defaults filled in and the initial state completed.

use marsden_spec::report;

use super::FileArgs;
use crate::error::{CliError, Status};

/// Validates and prints; status 2 on the first mistake.
pub fn check(args: &FileArgs) -> Result<Status, CliError> {
    let spec = marsden_spec::load(&args.file, &args.overrides())?;
    let start = marsden_spec::prepare(&spec)?;
    for warning in &start.warnings {
        eprintln!("warning: {warning}");
    }
    print!("{}", report::check::render(&spec, &start));
    Ok(Status::Completed)
}
