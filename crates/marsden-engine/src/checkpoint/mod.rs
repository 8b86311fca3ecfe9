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
//! * the sampler of `[output] times` and the samples written ([`SamplesCheckpoint`]);
//! * for a forced or time-dependent run, its energy and Noether balances so far
//!   ([`BalancesCheckpoint`]);
//! * where each output file stood, flushed ([`Mark`]): the rows written after the checkpoint
//!   by a run that was then killed are cut off before the resumed run goes on.
//!
//! The file format ([`file`]) is versioned and checked by a CRC-32. The tangent run of
//! `[sensitivity]`, a second loop after the run, has its own checkpoints ([`tangent`]).

pub mod file;
pub mod observer;
pub mod tangent;

use serde::{Deserialize, Serialize};

use crate::balance::EnergyBalanceCarry;
use crate::diagnostics::Diagnostics;
use marsden::analysis::diagnostics::MonitorCarry;
use marsden::integrator::IntegratorCheckpoint;
use marsden::run::events::{DetectorCheckpoint, SamplerCheckpoint};

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

/// What the samples of `[output] times` carry to the next step.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SamplesCheckpoint {
    /// The sampler.
    pub sampler: SamplerCheckpoint,
    /// Samples already written.
    pub written: usize,
    /// Where `samples.csv` stood (`None`: the samples were only counted).
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
    /// The balances of a forced or time-dependent run with a two-point rule (`None`: the run
    /// keeps none; always `None` in a version-1 file, which could not hold them).
    pub balances: Option<BalancesCheckpoint>,
    /// The samples at `[output] times` (`None`: none requested; always `None` in a file of
    /// version 1 or 2, which could not hold them).
    pub samples: Option<SamplesCheckpoint>,
}

impl RunCheckpoint {
    /// Reads the run checkpoint at `path`, of any version this build reads (a version-1 file
    /// is a run without balances, a version-2 file one without sampled times).
    ///
    /// # Errors
    /// A [`file::CheckpointError`] saying why it cannot be used.
    pub fn load(path: &std::path::Path) -> Result<Self, file::CheckpointError> {
        let bytes = file::read(path)?;
        match file::open(&bytes, path)? {
            (1, body) => file::decode_body::<RunCheckpointV1>(body, path).map(Into::into),
            (2, body) => file::decode_body::<RunCheckpointV2>(body, path).map(Into::into),
            (_, body) => file::decode_body(body, path),
        }
    }
}

/// The body of a version-1 run checkpoint: [`RunCheckpoint`] without `balances`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunCheckpointV1 {
    /// As [`RunCheckpoint::identity`].
    pub identity: RunIdentity,
    /// As [`RunCheckpoint::step`].
    pub step: usize,
    /// As [`RunCheckpoint::t`].
    pub t: f64,
    /// As [`RunCheckpoint::q`].
    pub q: Vec<f64>,
    /// As [`RunCheckpoint::p`].
    pub p: Vec<f64>,
    /// As [`RunCheckpoint::integrator`].
    pub integrator: IntegratorCheckpoint,
    /// As [`RunCheckpoint::stream`].
    pub stream: StreamCheckpoint,
    /// As [`RunCheckpoint::events`].
    pub events: Option<EventsCheckpoint>,
}

impl From<RunCheckpointV1> for RunCheckpoint {
    fn from(v1: RunCheckpointV1) -> Self {
        Self {
            identity: v1.identity,
            step: v1.step,
            t: v1.t,
            q: v1.q,
            p: v1.p,
            integrator: v1.integrator,
            stream: v1.stream,
            events: v1.events,
            balances: None,
            samples: None,
        }
    }
}

/// The body of a version-2 run checkpoint: [`RunCheckpoint`] without `samples`. Postcard
/// writes a struct as its fields one after the other, with no framing, so the version-1 body
/// nested first reads the same bytes as its fields written out here would.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunCheckpointV2 {
    /// The version-1 fields, in their order.
    pub v1: RunCheckpointV1,
    /// As [`RunCheckpoint::balances`].
    pub balances: Option<BalancesCheckpoint>,
}

impl From<RunCheckpointV2> for RunCheckpoint {
    fn from(v2: RunCheckpointV2) -> Self {
        Self {
            balances: v2.balances,
            ..v2.v1.into()
        }
    }
}

/// What the balances of a forced run carry to the next step: the discrete energy balance's and
/// each symmetry's forced Noether balance's.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BalancesCheckpoint {
    /// The energy balance ([`crate::balance::Balanced`]).
    pub energy: EnergyBalanceCarry,
    /// The Noether balances, in the order of the file's symmetries
    /// ([`crate::noether_balance::NoetherBalanced`]).
    pub noether: Vec<MonitorCarry>,
}

/// What the observers of a run carry to the next step (everything of a [`RunCheckpoint`] but
/// the state and the integrator's).
#[derive(Debug, Clone)]
pub struct Carried {
    /// The streaming observer's.
    pub stream: StreamCheckpoint,
    /// The event watch's.
    pub events: Option<EventsCheckpoint>,
    /// The balances'.
    pub balances: Option<BalancesCheckpoint>,
    /// The samples'.
    pub samples: Option<SamplesCheckpoint>,
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
