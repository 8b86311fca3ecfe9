//! The crate's one error type: every failure is a value, and every I/O failure names its path.

use std::path::{Path, PathBuf};

/// What went wrong while writing, reading or plotting.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// An operating-system I/O failure on a file or directory.
    #[error("cannot {action} {}: {source}", path.display())]
    Io {
        /// What was being done, e.g. `"create"` or `"write to"`.
        action: &'static str,
        /// The file or directory concerned.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },

    /// Two columns of one table have different lengths.
    #[error(
        "column `{column}` has {found} values but column `{first}` has {expected}: columns must have equal lengths"
    )]
    ColumnLength {
        /// The first column, which sets the expected length.
        first: String,
        /// The offending column.
        column: String,
        /// Length of the first column.
        expected: usize,
        /// Length of the offending column.
        found: usize,
    },

    /// A file a resumed run would go on writing does not match its checkpoint.
    #[error("cannot resume writing {}: {reason}", path.display())]
    Resume {
        /// The file.
        path: PathBuf,
        /// What does not match.
        reason: String,
    },

    /// A row handed to a streaming writer does not match the header.
    #[error("{}: row {row} has {found} values but there are {expected} columns", path.display())]
    RowLength {
        /// The file being written.
        path: PathBuf,
        /// Index of the offending row (0-based, counting data rows only).
        row: u64,
        /// Number of columns.
        expected: usize,
        /// Number of values given.
        found: usize,
    },

    /// A column or group name that cannot be written faithfully.
    #[error("invalid name {name:?}: {reason}")]
    InvalidName {
        /// The rejected name.
        name: String,
        /// Why it was rejected.
        reason: &'static str,
    },

    /// The same column or group name appears twice.
    #[error("duplicate name {name:?}")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },

    /// A column the operation needs is not in the table.
    #[error("no column named {name:?}")]
    MissingColumn {
        /// The missing column's name.
        name: String,
    },

    /// A table, header or layout with no columns at all.
    #[error("no columns: a table needs at least one column")]
    NoColumns,

    /// A streaming writer was used after [`finish`](crate::CsvWriter::finish).
    #[error("{}: the writer is already finished", path.display())]
    Finished {
        /// The file that was being written.
        path: PathBuf,
    },

    /// A file that is not in the format this crate writes.
    #[error("{}, line {line}: {message}", path.display())]
    Parse {
        /// The file being read.
        path: PathBuf,
        /// 1-based line number (0 for a whole-file problem).
        line: u64,
        /// What is wrong.
        message: String,
    },

    /// A `.npy` file that cannot be read back as `f64` data of the expected shape.
    #[error("{}: {message}", path.display())]
    Npy {
        /// The `.npy` file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },

    /// Input to a plot function that cannot be plotted (e.g. `t` and `y` of different lengths).
    #[error("cannot plot {}: {message}", path.display())]
    PlotInput {
        /// The PNG that was to be written.
        path: PathBuf,
        /// What is wrong with the input.
        message: String,
    },

    /// The drawing library failed while rendering a plot.
    #[error("cannot draw {}: {message}", path.display())]
    Plot {
        /// The PNG that was to be written.
        path: PathBuf,
        /// The drawing library's message.
        message: String,
    },
}

/// Shorthand for results whose error is [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Wraps an I/O error with the action and the path it concerns.
    pub(crate) fn io(action: &'static str, path: &Path, source: std::io::Error) -> Self {
        Self::Io {
            action,
            path: path.to_path_buf(),
            source,
        }
    }

    /// A file that does not match the checkpoint a run resumes from.
    pub(crate) fn resume(path: &Path, reason: String) -> Self {
        Self::Resume {
            path: path.to_path_buf(),
            reason,
        }
    }
}
