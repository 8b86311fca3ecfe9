//! `marsden resume DIR [--quiet] [--no-progress]`: the run whose checkpoint is in `DIR`,
//! continued from it to its end (`[output] checkpoint_every` or `--checkpoint-every` wrote
//! it). Exit statuses as `marsden run`; 2, with nothing changed, for a missing or damaged
//! checkpoint, a version this build cannot read, or a problem file changed since.

use marsden_spec::run::resume;

use super::ResumeArgs;
use super::run::{conclude, with_controls};
use crate::error::{CliError, Status};

/// Continues the run in `args.dir`.
pub fn resume(args: &ResumeArgs) -> Result<Status, CliError> {
    let checkpoint = resume::peek(&args.dir)?;
    if !args.quiet {
        println!(
            "resuming {} from step {} (t = {}), its checkpoint in {}",
            checkpoint.identity.absolute,
            checkpoint.step,
            checkpoint.t,
            args.dir.display()
        );
    }
    let (spec, outcome) = with_controls(args.no_progress, |controls| {
        resume::resume_from(&args.dir, checkpoint, controls)
    })?;
    Ok(conclude(&spec, &outcome, args.quiet))
}
