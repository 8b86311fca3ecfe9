//! Checkpoints of a sweep: the members whose rows are in the table are kept, the others run
//! again. A sweep with `[output] checkpoint_every` (or `--checkpoint-every`) writes its rows in
//! chunks of a few members per worker thread and, after each chunk whose members all ended
//! (completed, failed or stopped by an event: none interrupted), saves where the table stands
//! and the writer's counts in `sweep-checkpoint.bin` (`sweep-checkpoint.shard-i-of-n.bin` for a
//! shard). `marsden resume DIR` cuts the table back to that point and runs the remaining
//! members: their rows are those an uninterrupted sweep writes, since a member's row depends
//! on the member alone. The members themselves are not checkpointed (each one is rerun whole),
//! so any kind of member can be in such a sweep.
//!
//! The file is the run checkpoint's format ([`marsden_engine::checkpoint::file`]: magic,
//! version, CRC-32, postcard body) with a [`SweepCheckpoint`] body.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::shard::Shard;
use super::sweep_writer::SweepCounts;
use crate::error::{Diagnostic, Error};
use marsden_engine::checkpoint::{Mark, RunIdentity, file};

/// The start of a sweep checkpoint's file name.
const PREFIX: &str = "sweep-checkpoint";

/// A sweep's checkpoint: where the table of a sweep stands after its last chunk of ended
/// members, which `marsden resume` cuts the table back to before running the others.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepCheckpoint {
    /// The problem file and the command-line values of the sweep.
    pub identity: RunIdentity,
    /// Which members: shard `index` of `count`.
    pub shard: (usize, usize),
    /// Where the table stood.
    pub table: Mark,
    /// The writer's counts then (`counts.rows` members of the shard are done).
    pub counts: SweepCounts,
}

impl SweepCheckpoint {
    /// The shard it belongs to.
    pub fn shard(&self) -> Shard {
        Shard {
            index: self.shard.0,
            count: self.shard.1,
        }
    }
}

/// The checkpoint file of `shard`'s sweep in `dir`.
pub fn path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("{PREFIX}{}.bin", shard.suffix()))
}

/// The sweep checkpoints in `dir` (one per shard run there), sorted by name.
pub fn find(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut found: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
            name.is_some_and(|n| n.starts_with(PREFIX) && n.ends_with(".bin"))
        })
        .collect();
    found.sort();
    found
}

/// Reads the sweep checkpoint at `path`.
///
/// # Errors
/// Bad input: missing, unreadable, damaged or of a version this build cannot read.
pub fn load(path: &Path) -> Result<SweepCheckpoint, Error> {
    file::load(path).map_err(|e| Error::bad_input(Diagnostic::new(e.to_string())))
}

/// Saves `checkpoint` for `shard` in `dir`, atomically.
///
/// # Errors
/// The file cannot be written, as text.
pub fn save(dir: &Path, checkpoint: &SweepCheckpoint) -> Result<(), String> {
    file::save(&path(dir, checkpoint.shard()), checkpoint)
}

/// Removes a checkpoint a previous sweep of `shard` left in `dir` (a new sweep starts afresh).
///
/// # Errors
/// It exists but cannot be removed, as text.
pub fn remove_stale(dir: &Path, shard: Shard) -> Result<(), String> {
    let p = path(dir, shard);
    match std::fs::remove_file(&p) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(format!(
            "cannot remove the old checkpoint {}: {e}",
            p.display()
        )),
        _ => Ok(()),
    }
}
