//! `marsden resume DIR`: a run continued from the last checkpoint in its output directory.
//!
//! The checkpoint names its problem file (path, SHA-256 and text) and the command-line values
//! that changed it. The file is read again and must be unchanged — a file edited since would
//! make the resumed run another run; a problem that never was a file (text given from Python)
//! is taken from the checkpoint. The run's files are then cut back to the checkpoint and
//! continued ([`super::execute::execute_from`]): what the resumed run leaves is byte for byte
//! what the uninterrupted run leaves, the wall-clock times of `summary.json` aside. A sweep's
//! checkpoint ([`super::sweep_checkpoint`]) resumes the sweep: its finished members kept, the
//! others run.

use std::path::Path;

use super::controls::Controls;
use super::execute::{Outcome, Store, execute_from};
use super::shard::Shard;
use super::sweep::{self, SweepOptions, SweepOutcome};
use super::sweep_checkpoint::{self, SweepCheckpoint};
use crate::error::{Diagnostic, Error};
use crate::problem::RunSpec;
use crate::source::SourceFile;
use marsden_engine::checkpoint::{CHECKPOINT_FILE, RunCheckpoint, RunIdentity};
use marsden_problem::Overrides;

/// What identifies `spec`'s run in its checkpoints: its file (made absolute when it is one),
/// the SHA-256 and text of the problem, the command-line values that changed it.
pub fn identity(spec: &RunSpec) -> RunIdentity {
    let path = spec.source.path();
    let absolute = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let o = &spec.overrides;
    RunIdentity {
        file: path.display().to_string(),
        absolute: absolute.display().to_string(),
        sha256: spec.source.sha256().to_owned(),
        text: spec.source.text().to_owned(),
        steps: o.steps,
        h: o.h,
        checkpoint_every: o.checkpoint_every,
        every: o.every,
    }
}

/// The run whose checkpoint `checkpoint` was read from `dir` ([`find`]), continued to its end
/// with `controls` watching; its files written into `dir` as an uninterrupted run writes them.
///
/// # Errors
/// Bad input (status 2), with nothing in `dir` changed: no checkpoint, a damaged one or one of
/// a format version this build cannot read, a problem file changed since the checkpoint, or
/// output files that no longer reach the checkpoint.
pub fn resume_from(
    dir: &Path,
    checkpoint: RunCheckpoint,
    controls: &Controls<'_>,
) -> Result<(RunSpec, Outcome), Error> {
    let (spec, _) = spec_of(dir, &checkpoint.identity)?;
    let outcome = execute_from(&spec, Store::Files, controls, Some(Box::new(checkpoint)))?;
    Ok((spec, outcome))
}

/// The checkpoint in `dir`, read and checked (its format version and CRC-32).
///
/// # Errors
/// As [`resume_from`].
fn peek(dir: &Path) -> Result<RunCheckpoint, Error> {
    RunCheckpoint::load(&dir.join(CHECKPOINT_FILE))
        .map_err(|e| Error::bad_input(Diagnostic::new(e.to_string())))
}

/// The checkpoint of what ran in a directory: a run's, or a sweep's.
#[derive(Debug)]
pub enum Found {
    /// A single run's (`checkpoint.bin`).
    Run(Box<RunCheckpoint>),
    /// A sweep's (`sweep-checkpoint.bin`, or a shard's).
    Sweep(Box<SweepCheckpoint>),
}

/// The checkpoint in `dir`: the run's if there is one, else the sweep's — of `shard` when
/// given, else the only one there.
///
/// # Errors
/// As [`resume_from`]; also several shards' checkpoints in `dir` and no `shard` to choose one.
pub fn find(dir: &Path, shard: Option<Shard>) -> Result<Found, Error> {
    if let Some(shard) = shard {
        return sweep_checkpoint::load(&sweep_checkpoint::path(dir, shard))
            .map(|c| Found::Sweep(Box::new(c)));
    }
    if dir.join(CHECKPOINT_FILE).exists() {
        return peek(dir).map(|c| Found::Run(Box::new(c)));
    }
    match sweep_checkpoint::find(dir).as_slice() {
        [] => peek(dir).map(|c| Found::Run(Box::new(c))),
        [one] => sweep_checkpoint::load(one).map(|c| Found::Sweep(Box::new(c))),
        several => {
            let names: Vec<String> = (several.iter())
                .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                .collect();
            Err(Error::bad_input(
                Diagnostic::new(format!(
                    "{} holds the checkpoints of several shards of a sweep: {}",
                    dir.display(),
                    names.join(", ")
                ))
                .help("resume one of them with `--shard i/n`"),
            ))
        }
    }
}

/// The sweep whose checkpoint is `checkpoint` (read from `dir`), continued: the table cut
/// back to it, the members after it run with `options`' threads and stop flag.
///
/// # Errors
/// As [`resume_from`].
pub fn resume_sweep(
    dir: &Path,
    checkpoint: SweepCheckpoint,
    options: SweepOptions,
) -> Result<(RunSpec, SweepOutcome), Error> {
    let (spec, overrides) = spec_of(dir, &checkpoint.identity)?;
    let Some(sweep) = spec.sweep.clone() else {
        return Err(Error::bad_input(Diagnostic::new(
            "the checkpoint is a sweep's, but its problem has no [sweep]",
        )));
    };
    let options = SweepOptions {
        shard: checkpoint.shard(),
        resume: Some(Box::new(checkpoint)),
        ..options
    };
    let outcome = sweep::execute(&spec, &sweep, &overrides, &options)?;
    Ok((spec, outcome))
}

/// The problem of `identity`, read again and checked unchanged, its output in `dir`; and the
/// command-line values it was run with.
fn spec_of(dir: &Path, identity: &RunIdentity) -> Result<(RunSpec, Overrides), Error> {
    let path = Path::new(&identity.absolute);
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        // Never a file (a problem given as text from Python): the checkpoint's copy.
        Err(e) if e.kind() == std::io::ErrorKind::NotFound && !identity.text.is_empty() => {
            identity.text.clone()
        }
        Err(e) => {
            return Err(Error::bad_input(Diagnostic::new(format!(
                "cannot read the problem file {} of the checkpoint: {e}",
                path.display()
            ))));
        }
    };
    let source = SourceFile::new(&identity.file, text);
    if source.sha256() != identity.sha256 {
        return Err(Error::bad_input(
            Diagnostic::new(format!(
                "the problem file {} has changed since the checkpoint was taken (SHA-256 {} \
                 then, {} now): the resumed run would be another run",
                path.display(),
                short(&identity.sha256),
                short(source.sha256()),
            ))
            .help("restore the file as it was, or start the run again with `marsden run`"),
        ));
    }
    let overrides = Overrides {
        steps: identity.steps,
        h: identity.h,
        out: Some(dir.to_path_buf()),
        checkpoint_every: identity.checkpoint_every,
        every: identity.every,
    };
    let spec = marsden_problem::problem::validate(source, &overrides).map_err(Error::bad_input)?;
    if spec.output.checkpoint_every.is_none() {
        return Err(Error::bad_input(Diagnostic::new(
            "the checkpoint's problem no longer asks for checkpoints",
        )));
    }
    Ok((spec, overrides))
}

/// The first 12 hex digits of a SHA-256.
fn short(sha: &str) -> &str {
    sha.get(..12).unwrap_or(sha)
}
