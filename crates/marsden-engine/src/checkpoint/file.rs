//! The checkpoint file, `checkpoint.bin`:
//!
//! | bytes | content |
//! |---|---|
//! | 0–7 | the magic `MARSDENC` |
//! | 8–11 | the format version, `u32` little-endian ([`VERSION`]) |
//! | 12–15 | the CRC-32 (IEEE) of the body, `u32` little-endian |
//! | 16– | the body: a [`RunCheckpoint`] (or, for a sweep, the sweep's checkpoint) in postcard's encoding |
//!
//! Version 1 is the first. Version 2 adds to a run's checkpoint the balances of a forced or
//! time-dependent run ([`super::RunCheckpoint::balances`]); a version-1 file is read as a run
//! without them ([`super::RunCheckpoint::load`]; a test reads a version-1 fixture), and the
//! other bodies (a sweep's, a tangent run's) are the same in both. Version 3 adds the sampler
//! of `[output] times` ([`super::RunCheckpoint::samples`]); a version-2 file is read as a run
//! without sampled times (a test reads a version-2 fixture). A later version that changes
//! a body keeps reading the earlier ones; a file of a version this build does not know, a body
//! whose CRC does not match (a torn or damaged file) or that does not decode is refused with
//! the reason. Files are written through a temporary file and a rename, so a checkpoint is
//! whole or the previous one stays.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

/// The first bytes of a checkpoint file.
pub const MAGIC: &[u8; 8] = b"MARSDENC";
/// The format version this build writes.
pub const VERSION: u32 = 3;
const HEADER: usize = 16;

/// Why a checkpoint cannot be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CheckpointError {
    /// No checkpoint file (the run was never checkpointed, or not in this directory).
    #[error(
        "there is no checkpoint {path}: the run was not started with `checkpoint_every`, or was stopped before its first checkpoint"
    )]
    Missing {
        /// The file looked for.
        path: String,
    },
    /// It could not be read.
    #[error("cannot read the checkpoint {path}: {reason}")]
    Unreadable {
        /// The file.
        path: String,
        /// The operating system's reason.
        reason: String,
    },
    /// Not a checkpoint, or damaged.
    #[error("the checkpoint {path} is damaged: {reason}")]
    Corrupt {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// A format version this build cannot read.
    #[error(
        "the checkpoint {path} has format version {found}; this marsden reads versions 1 to {VERSION}"
    )]
    Version {
        /// The file.
        path: String,
        /// Its version.
        found: u32,
    },
}

/// The bytes of a checkpoint file holding `checkpoint`.
///
/// # Errors
/// postcard's error, as text (it cannot fail on these types short of running out of memory).
pub fn encode<T: Serialize>(checkpoint: &T) -> Result<Vec<u8>, String> {
    let body = postcard::to_allocvec(checkpoint).map_err(|e| e.to_string())?;
    let mut bytes = Vec::with_capacity(HEADER + body.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&VERSION.to_le_bytes());
    bytes.extend_from_slice(&crc32fast::hash(&body).to_le_bytes());
    bytes.extend_from_slice(&body);
    Ok(bytes)
}

/// The checkpoint in `bytes` (read from `path`, which names it in errors), for a body that is
/// the same in every version.
///
/// # Errors
/// [`CheckpointError::Corrupt`] or [`CheckpointError::Version`].
pub fn decode<T: DeserializeOwned>(bytes: &[u8], path: &Path) -> Result<T, CheckpointError> {
    let (_, body) = open(bytes, path)?;
    decode_body(body, path)
}

/// The format version and the body of the checkpoint in `bytes`, its header and CRC-32 checked.
///
/// # Errors
/// [`CheckpointError::Corrupt`] or [`CheckpointError::Version`].
pub fn open<'b>(bytes: &'b [u8], path: &Path) -> Result<(u32, &'b [u8]), CheckpointError> {
    let (Some(magic), Some(version), Some(crc)) =
        (bytes.get(..8), bytes.get(8..12), bytes.get(12..HEADER))
    else {
        return Err(corrupt(
            path,
            format!("{} bytes, shorter than its header", bytes.len()),
        ));
    };
    if magic != MAGIC {
        return Err(corrupt(
            path,
            "it does not start with `MARSDENC`".to_owned(),
        ));
    }
    let word = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    let found = word(version);
    if found == 0 || found > VERSION {
        return Err(CheckpointError::Version {
            path: path.display().to_string(),
            found,
        });
    }
    let body = &bytes[HEADER..];
    let (expected, actual) = (word(crc), crc32fast::hash(body));
    if expected != actual {
        return Err(corrupt(
            path,
            format!("its CRC-32 is {actual:08x}, the header says {expected:08x}"),
        ));
    }
    Ok((found, body))
}

/// A checkpoint's body, decoded as `T`.
///
/// # Errors
/// [`CheckpointError::Corrupt`] if it does not decode.
pub fn decode_body<T: DeserializeOwned>(body: &[u8], path: &Path) -> Result<T, CheckpointError> {
    postcard::from_bytes(body).map_err(|e| corrupt(path, format!("its body does not decode: {e}")))
}

fn corrupt(path: &Path, reason: String) -> CheckpointError {
    CheckpointError::Corrupt {
        path: path.display().to_string(),
        reason,
    }
}

/// Writes `checkpoint` to `path` atomically.
///
/// # Errors
/// The I/O or encoding error, as text.
pub fn save<T: Serialize>(path: &Path, checkpoint: &T) -> Result<(), String> {
    let bytes = encode(checkpoint)?;
    marsden_io::write_atomically(path, &bytes)
        .map_err(|e| format!("cannot write the checkpoint {}: {e}", path.display()))
}

/// Reads the checkpoint at `path`, for a body that is the same in every version.
///
/// # Errors
/// A [`CheckpointError`] saying why it cannot be used.
pub fn load<T: DeserializeOwned>(path: &Path) -> Result<T, CheckpointError> {
    decode(&read(path)?, path)
}

/// The bytes of the checkpoint file at `path`.
///
/// # Errors
/// [`CheckpointError::Missing`] or [`CheckpointError::Unreadable`].
pub fn read(path: &Path) -> Result<Vec<u8>, CheckpointError> {
    std::fs::read(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => CheckpointError::Missing {
            path: path.display().to_string(),
        },
        _ => CheckpointError::Unreadable {
            path: path.display().to_string(),
            reason: e.to_string(),
        },
    })
}
