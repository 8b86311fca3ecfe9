//! The streaming interface shared by the CSV and `.npy` writers.

use crate::error::Result;

/// Something that takes a trajectory one row at a time and can stop at any row.
///
/// Implemented by [`CsvWriter`](crate::CsvWriter) and [`NpyDirWriter`](crate::NpyDirWriter),
/// so the CLI can hold a `Box<dyn RowSink>` whatever `format` the user chose.
pub trait RowSink {
    /// Appends one row; its length must equal the number of columns.
    ///
    /// # Errors
    /// [`Error::RowLength`](crate::Error::RowLength), [`Error::Finished`](crate::Error::Finished)
    /// or an I/O error naming the file.
    fn write_row(&mut self, row: &[f64]) -> Result<()>;

    /// Pushes every row written so far to the operating system, leaving a valid file.
    ///
    /// # Errors
    /// An I/O error naming the file.
    fn flush(&mut self) -> Result<()>;

    /// Flushes and closes the output; later writes fail with
    /// [`Error::Finished`](crate::Error::Finished). Calling it again does nothing.
    /// A run that fails half-way calls this to keep the rows written so far.
    ///
    /// # Errors
    /// An I/O error naming the file.
    fn finish(&mut self) -> Result<()>;

    /// Number of data rows accepted so far.
    fn rows_written(&self) -> u64;

    /// Flushes, and says where the output stands: the rows on disk and the length of each
    /// file, so that a resumed run can cut the files back to this point and go on writing
    /// ([`crate::CsvWriter::reopen`], [`crate::NpyDirWriter::reopen`]).
    ///
    /// Default: the flushed row count alone (a sink in memory has no files to cut).
    ///
    /// # Errors
    /// An I/O error naming the file.
    fn mark(&mut self) -> Result<SinkMark> {
        self.flush()?;
        Ok(SinkMark {
            rows: self.rows_written(),
            bytes: Vec::new(),
        })
    }
}

/// Where a sink's output stands after a flush ([`RowSink::mark`]): what a checkpoint records so
/// that the files can be cut back to it when the run resumes.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SinkMark {
    /// Data rows on disk.
    pub rows: u64,
    /// The length of each file in bytes (one for a CSV, one per group of a `.npy` directory;
    /// empty for a sink in memory).
    pub bytes: Vec<u64>,
}
