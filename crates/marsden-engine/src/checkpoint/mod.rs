//! Checkpoints of a run: everything it carries from one step to the next, saved every
//! `[output] checkpoint_every` steps into the output directory, so that a run killed at any
//! moment continues from its last checkpoint (`marsden resume DIR`) and leaves the files an
//! uninterrupted run leaves, byte for byte (the wall-clock times of `summary.json` aside).
//!
//! A [`RunCheckpoint`] holds
//!
//! * what identifies the run: the problem file's path and SHA-256, and the command-line values
//!   that changed it ([`RunIdentity`]) — a resume refuses a file changed since;
//! * the step index and the exact state `(t, q, p)` after it;
//! * the integrator's carried data (predictor history, warm starts, reused Jacobians,
//!   compensated-summation remainders, the projection's starting guess, the work counters:
//!   [`marsden::integrator::IntegratorCheckpoint`]);
//! * the monitors' accumulators (energy, momentum maps, constraint residuals) and the
//!   Legendre transform's warm start of the streaming observer ([`StreamCheckpoint`]);
//! * the event detector's state and the events written ([`EventsCheckpoint`]);
//! * where each output file stood, flushed ([`Mark`]): the rows written after the checkpoint
//!   by a run that was then killed are cut off before the resumed run goes on.
//!
//! The file format ([`file`]) is versioned and checked by a CRC-32.

pub mod file;
pub mod observer;

use serde::{Deserialize, Serialize};

use crate::diagnostics::Diagnostics;
use marsden::integrator::IntegratorCheckpoint;
use marsden::run::events::DetectorCheckpoint;

/// The checkpoint file of an output directory.
pub const CHECKPOINT_FILE: &str = "checkpoint.bin";

/// What identifies the run a checkpoint belongs to.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunIdentity {
    /// The problem file, as given to `marsden run` (`summary.json` names it so).
    pub file: String,
    /// The same, made absolute (where a resume reads it again).
    pub absolute: String,
    /// The SHA-256 of its text, in hex.
    pub sha256: String,
    /// Its text (a problem given as text, not as a file, is resumed from this copy).
    pub text: String,
    /// `--steps`, if given.
    pub steps: Option<u64>,
    /// `--h`, if given.
    pub h: Option<f64>,
    /// `--checkpoint-every`, if given.
    pub checkpoint_every: Option<u64>,
    /// The sampling stride given by the caller (Python's `every`), if given.
    pub every: Option<u64>,
}

/// Where an output file stood when the checkpoint was taken ([`marsden_io::SinkMark`]).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Mark {
    /// Data rows written.
    pub rows: u64,
    /// Length of each file in bytes.
    pub bytes: Vec<u64>,
}

impl From<marsden_io::SinkMark> for Mark {
    fn from(m: marsden_io::SinkMark) -> Self {
        Self {
            rows: m.rows,
            bytes: m.bytes,
        }
    }
}

impl From<&Mark> for marsden_io::SinkMark {
    fn from(m: &Mark) -> Self {
        Self {
            rows: m.rows,
            bytes: m.bytes.clone(),
        }
    }
}

/// What the observer streaming the rows carries to the next step.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StreamCheckpoint {
    /// The monitors' accumulators.
    pub diagnostics: Diagnostics,
    /// The velocities of the last state evaluated (the next inverse Legendre transform's
    /// starting guess).
    pub velocity: Vec<f64>,
    /// The step of the last row written.
    pub last_written: Option<usize>,
    /// Where the trajectory files stood.
    pub trajectory: Mark,
}

/// What the event watch carries to the next step.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct EventsCheckpoint {
    /// The detector.
    pub detector: DetectorCheckpoint,
    /// Records already written.
    pub written: usize,
    /// Crossings recorded per event.
    pub counts: Vec<usize>,
    /// Where `events.csv` stood (`None`: the records were only counted).
    pub file: Option<Mark>,
}

/// A whole run's checkpoint (see the [module](self) docs).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunCheckpoint {
    /// The run it belongs to.
    pub identity: RunIdentity,
    /// Steps completed.
    pub step: usize,
    /// Time after them.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Momenta.
    pub p: Vec<f64>,
    /// The integrator's carried data.
    pub integrator: IntegratorCheckpoint,
    /// The streaming observer's.
    pub stream: StreamCheckpoint,
    /// The event watch's (`None`: the file has no events).
    pub events: Option<EventsCheckpoint>,
}

/// Checkpoints asked of a run: how often, into which file, for which run, and the checkpoint
/// it resumes from (if it does).
#[derive(Debug, Clone)]
pub struct CheckpointPlan {
    /// Every this many steps.
    pub every: usize,
    /// The checkpoint file.
    pub path: std::path::PathBuf,
    /// The run's identity, written into each checkpoint.
    pub identity: RunIdentity,
    /// The checkpoint the run resumes from (`None`: it starts at step 0).
    pub resume: Option<Box<RunCheckpoint>>,
}
