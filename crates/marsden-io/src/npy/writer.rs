//! Streaming writer for one `.npy` file.

use std::fs::File;
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use super::header::header;
use crate::error::{Error, Result};

/// Rows are gathered up to this many bytes before being written.
const SPILL_BYTES: usize = 1 << 16;

/// The shape of the array being streamed; the row count grows as rows are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NpyShape {
    /// A 1-D array `(rows,)`: each row is one value.
    Vector,
    /// A 2-D array `(rows, columns)`.
    Matrix {
        /// Values per row.
        columns: usize,
    },
    /// A 3-D array `(rows, r, c)`: each row is one `r × c` matrix, row-major.
    Stack {
        /// Rows of each matrix.
        rows: usize,
        /// Columns of each matrix.
        columns: usize,
    },
}

impl NpyShape {
    /// Values per row.
    pub fn row_width(self) -> usize {
        match self {
            Self::Vector => 1,
            Self::Matrix { columns } => columns,
            Self::Stack { rows, columns } => rows * columns,
        }
    }

    fn dims(self, rows: u64) -> Vec<u64> {
        match self {
            Self::Vector => vec![rows],
            Self::Matrix { columns } => vec![rows, columns as u64],
            Self::Stack {
                rows: r,
                columns: c,
            } => vec![rows, r as u64, c as u64],
        }
    }
}

/// Writes one `.npy` array (`<f8`, C order) row by row, patching the shape in the header.
///
/// See the [module docs](crate::npy) for what is on disk at each moment. Dropping an
/// unfinished writer finishes it on a best-effort basis (errors ignored).
#[derive(Debug)]
pub struct NpyWriter<W: Write + Seek> {
    inner: Option<W>,
    path: PathBuf,
    shape: NpyShape,
    rows: u64,
    /// Rows the header on disk counts (all of them followed by their data).
    on_disk: u64,
    buf: Vec<u8>,
}

impl NpyWriter<File> {
    /// Creates (or truncates) `path` and writes a header for zero rows.
    ///
    /// # Errors
    /// An I/O error naming `path`.
    pub fn create(path: impl AsRef<Path>, shape: NpyShape) -> Result<Self> {
        let path = path.as_ref();
        let file = File::create(path).map_err(|e| Error::io("create", path, e))?;
        Self::from_writer(file, path, shape)
    }

    /// Opens a file this writer streamed `rows` rows into, to go on after them: cuts off any
    /// data past those rows (the rows of a run killed after its checkpoint), rewrites the
    /// header's count, and appends from there.
    ///
    /// # Errors
    /// [`Error::Resume`] if the file holds fewer rows than `rows`; an I/O error naming `path`.
    pub fn reopen(path: impl AsRef<Path>, shape: NpyShape, rows: u64) -> Result<Self> {
        let path = path.as_ref();
        let file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .open(path)
            .map_err(|e| Error::io("open", path, e))?;
        let row_bytes = 8 * shape.row_width() as u64;
        let length = (rows.checked_mul(row_bytes))
            .and_then(|data| data.checked_add(super::header::HEADER_BYTES as u64));
        let found = (file.metadata())
            .map_err(|e| Error::io("read the length of", path, e))?
            .len();
        match length {
            Some(length) if found >= length => {
                file.set_len(length)
                    .map_err(|e| Error::io("cut", path, e))?;
            }
            _ => {
                let reason = format!("{found} bytes, fewer than the {rows} rows of the checkpoint");
                return Err(Error::resume(path, reason));
            }
        }
        let mut w = Self {
            inner: Some(file),
            path: path.to_path_buf(),
            shape,
            rows,
            on_disk: rows,
            buf: Vec::with_capacity(SPILL_BYTES + 1024),
        };
        w.flush()?;
        Ok(w)
    }
}

impl<W: Write + Seek> NpyWriter<W> {
    /// Wraps an empty seekable writer; `path` only names it in errors.
    ///
    /// # Errors
    /// An I/O error naming `path`.
    pub fn from_writer(writer: W, path: impl Into<PathBuf>, shape: NpyShape) -> Result<Self> {
        let mut w = Self {
            inner: Some(writer),
            path: path.into(),
            shape,
            rows: 0,
            on_disk: 0,
            buf: Vec::with_capacity(SPILL_BYTES + 1024),
        };
        w.spill()?;
        Ok(w)
    }

    /// Appends one row of `shape.row_width()` values.
    ///
    /// # Errors
    /// [`Error::RowLength`], [`Error::Finished`], or an I/O error naming the file.
    pub fn write_row(&mut self, row: &[f64]) -> Result<()> {
        if self.inner.is_none() {
            return Err(Error::Finished {
                path: self.path.clone(),
            });
        }
        if row.len() != self.shape.row_width() {
            return Err(Error::RowLength {
                path: self.path.clone(),
                row: self.rows,
                expected: self.shape.row_width(),
                found: row.len(),
            });
        }
        for x in row {
            self.buf.extend_from_slice(&x.to_le_bytes());
        }
        self.rows += 1;
        if self.buf.len() >= SPILL_BYTES {
            self.spill()?;
        }
        Ok(())
    }

    /// Writes buffered rows, rewrites the header's row count, and flushes.
    ///
    /// # Errors
    /// [`Error::Finished`] or an I/O error naming the file.
    pub fn flush(&mut self) -> Result<()> {
        self.spill()?;
        match self.inner.as_mut() {
            Some(w) => w.flush().map_err(|e| Error::io("flush", &self.path, e)),
            None => Err(Error::Finished {
                path: self.path.clone(),
            }),
        }
    }

    /// Flushes and stops; the file is a complete `.npy` of all rows written. Idempotent.
    ///
    /// # Errors
    /// An I/O error naming the file.
    pub fn finish(&mut self) -> Result<()> {
        if self.inner.is_none() {
            return Ok(());
        }
        let result = self.flush();
        self.inner = None;
        result
    }

    /// Finishes and returns the underlying writer.
    ///
    /// # Errors
    /// [`Error::Finished`] if already finished, or an I/O error naming the file.
    pub fn into_inner(mut self) -> Result<W> {
        self.flush()?;
        self.inner.take().ok_or_else(|| Error::Finished {
            path: self.path.clone(),
        })
    }

    /// Rows written so far, less those a failed write lost (then: the rows the header on disk
    /// counts).
    pub fn rows_written(&self) -> u64 {
        self.rows
    }

    /// The path given at creation.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The array's shape (apart from the growing row count).
    pub fn shape(&self) -> NpyShape {
        self.shape
    }

    /// Appends the buffer, then rewrites the header for the rows now on disk.
    fn spill(&mut self) -> Result<()> {
        let Some(w) = self.inner.as_mut() else {
            return Err(Error::Finished {
                path: self.path.clone(),
            });
        };
        let path = &self.path;
        let io = |e| Error::io("write to", path, e);
        // Data first, then the header: the count on disk never exceeds the data on disk.
        let data = w.seek(SeekFrom::End(0)).and_then(|end| {
            let end = if end == 0 {
                // Fresh file: reserve the header's bytes.
                w.write_all(&header(&self.shape.dims(0)))?;
                super::header::HEADER_BYTES as u64
            } else {
                end
            };
            w.write_all(&self.buf)?;
            Ok(end)
        });
        self.buf.clear();
        let patched = data.and_then(|_| {
            w.seek(SeekFrom::Start(0))?;
            w.write_all(&header(&self.shape.dims(self.rows)))?;
            w.seek(SeekFrom::End(0))
        });
        match patched {
            Ok(_) => {
                self.on_disk = self.rows;
                Ok(())
            }
            Err(e) => {
                // A failed write loses the buffered rows: the count goes back to the header's.
                self.rows = self.on_disk;
                Err(io(e))
            }
        }
    }
}

impl<W: Write + Seek> Drop for NpyWriter<W> {
    fn drop(&mut self) {
        if self.inner.is_some() {
            let _ = self.finish();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Cursor;

    #[test]
    fn streams_and_patches_row_count() {
        let mut w = NpyWriter::from_writer(
            Cursor::new(Vec::new()),
            "mem.npy",
            NpyShape::Matrix { columns: 2 },
        )
        .unwrap();
        for i in 0..10_000 {
            w.write_row(&[i as f64, -(i as f64)]).unwrap();
        }
        assert!(matches!(
            w.write_row(&[1.0]),
            Err(Error::RowLength {
                expected: 2,
                found: 1,
                row: 10_000,
                ..
            })
        ));
        let bytes = w.into_inner().unwrap().into_inner();
        assert_eq!(bytes.len(), 128 + 10_000 * 16);
        let text = std::str::from_utf8(&bytes[10..128]).unwrap();
        assert!(text.contains("'shape': (10000, 2), }"), "{text}");
        assert_eq!(&bytes[128 + 16..128 + 24], &1.0f64.to_le_bytes());
    }

    #[test]
    fn unfinished_file_is_valid_up_to_last_spill() {
        let mut w =
            NpyWriter::from_writer(Cursor::new(Vec::new()), "mem.npy", NpyShape::Vector).unwrap();
        // 10_000 values = 80_000 bytes: more than one spill of 64 KiB.
        for i in 0..10_000 {
            w.write_row(&[i as f64]).unwrap();
        }
        let snapshot = w.inner.as_ref().unwrap().get_ref().clone();
        let text = std::str::from_utf8(&snapshot[10..128]).unwrap().to_owned();
        let rows: u64 = text
            .split("'shape': (")
            .nth(1)
            .and_then(|s| s.split(',').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!(rows > 0 && rows < 10_000, "{text}");
        assert!(snapshot.len() as u64 >= 128 + rows * 8);
    }
}
