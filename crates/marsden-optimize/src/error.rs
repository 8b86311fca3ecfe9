//! What can stop `marsden optimize`: a problem the core refuses before solving (nothing
//! written), or a failed write of the results.

use std::path::PathBuf;

use thiserror::Error;

/// An error of an optimal control run.
#[derive(Debug, Error)]
pub enum OptimizeError {
    /// The problem as checked from the file is refused by the DMOC core (nothing was solved).
    #[error("the optimal control problem cannot be set up: {0}")]
    Setup(#[from] marsden_control::ControlError),
    /// A result file could not be written.
    #[error("cannot write {path}: {message}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The reason.
        message: String,
    },
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] marsden_io::Error),
}

impl OptimizeError {
    /// A write error naming `path`.
    pub fn write(path: impl Into<PathBuf>, e: impl std::fmt::Display) -> Self {
        Self::Write {
            path: path.into(),
            message: e.to_string(),
        }
    }
}
