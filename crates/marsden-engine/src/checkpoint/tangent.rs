//! Checkpoints of the tangent run of `[sensitivity]`, `sensitivity-checkpoint.bin`.
//!
//! The tangent run is a second loop over the grid, after the run itself has completed
//! ([`crate::sensitivity`]). While it goes, every `checkpoint_every` steps it saves what it
//! carries — the step, the state, the sensitivity `S_k`, what its integrator carries
//! ([`marsden::sensitivity::TangentCheckpoint`]) — with the Jacobians handed on so far and
//! where the sensitivity file stood. A resumed run first finishes the run itself from
//! `checkpoint.bin` (its last stretch replayed, its files rewritten as they were), then
//! continues the tangent run from here instead of from its start: the sensitivity file comes out
//! byte for byte that of an uninterrupted run.
//!
//! The file has the format of `checkpoint.bin` ([`super::file`]: magic, version, CRC-32,
//! postcard body), its body a [`SensitivityCheckpoint`].

use std::path::PathBuf;

use serde::{Deserialize, Serialize};

use super::{Mark, RunIdentity};
use marsden::sensitivity::TangentCheckpoint;

/// The tangent run's checkpoint file of an output directory.
pub const SENSITIVITY_CHECKPOINT_FILE: &str = "sensitivity-checkpoint.bin";

/// Where the tangent run of `[sensitivity]` stood (see the [module](self) docs).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SensitivityCheckpoint {
    /// The run it belongs to.
    pub identity: RunIdentity,
    /// The tangent run's carried state.
    pub tangent: TangentCheckpoint,
    /// Stored Jacobians handed on before it.
    pub samples: usize,
    /// Where the sensitivity file stood (`None`: the Jacobians went to memory only).
    pub file: Option<Mark>,
}

/// Checkpoints asked of a tangent run: how often, into which file, for which run, and the
/// checkpoint it continues from (if it does).
#[derive(Debug, Clone)]
pub struct TangentPlan {
    /// Every this many steps.
    pub every: usize,
    /// The checkpoint file.
    pub path: PathBuf,
    /// The run's identity, written into each checkpoint.
    pub identity: RunIdentity,
    /// The checkpoint the tangent run continues from (`None`: it starts at step 0).
    pub resume: Option<Box<SensitivityCheckpoint>>,
}
