//! `marsden resume DIR [--quiet] [--no-progress] [--shard I/N] [--threads N]`: the run whose
//! checkpoint is in `DIR`, continued from it to its end (`[output] checkpoint_every` or
//! `--checkpoint-every` wrote it); a sweep's checkpoint continues the sweep (its finished
//! members kept; `--shard` picks one shard's when several ran into `DIR`). Exit statuses as `marsden run`; 2, with nothing changed, for a missing or damaged
//! checkpoint, a version this build cannot read, or a problem file changed since.

use marsden_spec::resume::{self, Found, SweepCheckpoint};
use marsden_spec::sweep::SweepOptions;

use super::ResumeArgs;
use super::run::{conclude, conclude_sweep, stop_on_ctrl_c, with_controls};
use crate::error::{CliError, Status};

/// The step of the tangent run's checkpoint in `dir`, if there is a readable one (an unreadable
/// one is refused by the resume itself, with the reason).
fn tangent_step(dir: &std::path::Path) -> Option<usize> {
    use marsden_spec::checkpoint::{file, tangent};
    let path = dir.join(tangent::SENSITIVITY_CHECKPOINT_FILE);
    let found: tangent::SensitivityCheckpoint = file::load(&path).ok()?;
    Some(found.tangent.step)
}

/// Continues the run (or the sweep) in `args.dir`.
pub fn resume(args: &ResumeArgs) -> Result<Status, CliError> {
    let checkpoint = match resume::find(&args.dir, args.shard)? {
        Found::Run(checkpoint) => *checkpoint,
        Found::Sweep(checkpoint) => return resume_sweep(args, *checkpoint),
    };
    if !args.quiet {
        println!(
            "resuming {} from step {} (t = {}), its checkpoint in {}",
            checkpoint.identity.absolute,
            checkpoint.step,
            checkpoint.t,
            args.dir.display()
        );
        if let Some(step) = tangent_step(&args.dir) {
            println!("  then its tangent run ([sensitivity]) from step {step}, its own checkpoint");
        }
    }
    let (spec, outcome) = with_controls(args.no_progress, |controls| {
        resume::resume_from(&args.dir, checkpoint, controls)
    })?;
    Ok(conclude(&spec, &outcome, args.quiet))
}

/// Continues the sweep of `checkpoint` in `args.dir`.
fn resume_sweep(args: &ResumeArgs, checkpoint: SweepCheckpoint) -> Result<Status, CliError> {
    if !args.quiet {
        println!(
            "resuming the sweep of {} after {} member{} (shard {}/{}), its checkpoint in {}",
            checkpoint.identity.absolute,
            checkpoint.counts.rows,
            if checkpoint.counts.rows == 1 { "" } else { "s" },
            checkpoint.shard.0,
            checkpoint.shard.1,
            args.dir.display()
        );
    }
    let options = SweepOptions {
        threads: args.threads.map(usize::from),
        stop: stop_on_ctrl_c(),
        ..SweepOptions::default()
    };
    let (spec, outcome) = resume::resume_sweep(&args.dir, checkpoint, options)?;
    Ok(conclude_sweep(&spec, &outcome, args.quiet))
}
