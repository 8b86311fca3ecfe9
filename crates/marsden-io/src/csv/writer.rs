//! Streaming CSV writer and the one-shot table writer.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use super::number::format_f64;
use crate::error::{Error, Result};
use crate::sink::{RowSink, SinkMark};
use crate::table::{Table, check_names};

/// Rows are gathered in memory up to this many bytes, then handed to the file together.
const SPILL_BYTES: usize = 1 << 16;

/// Writes a CSV header, then rows one at a time, in bounded memory.
///
/// Whole rows are buffered (about 64 KiB) and handed to the underlying writer together, so
/// the output always ends at a row boundary. [`finish`](Self::finish) (or
/// [`flush`](Self::flush)) can be called at any row: a failed run keeps what it wrote. If the
/// writer is dropped unfinished, buffered rows are written on a best-effort basis (errors
/// ignored); call `finish` to see them.
///
/// ```
/// # fn main() -> Result<(), marsden_io::Error> {
/// # let dir = tempfile::tempdir().unwrap();
/// # let path = dir.path().join("trajectory.csv");
/// use marsden_io::CsvWriter;
/// let mut w = CsvWriter::create(&path, &["t", "q_x", "p_x", "energy"])?;
/// w.write_row(&[0.0, 1.0, 0.0, 0.5])?;
/// w.write_row(&[0.1, 0.995, -0.0998, 0.5])?;
/// w.finish()?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(),
///            "t,q_x,p_x,energy\n0,1,0,0.5\n0.1,0.995,-0.0998,0.5\n");
/// # Ok(()) }
/// ```
#[derive(Debug)]
pub struct CsvWriter<W: Write> {
    inner: Option<W>,
    path: PathBuf,
    width: usize,
    /// Rows on the writer's side plus rows in `buf`.
    rows: u64,
    /// Rows in `buf` (the header line is not one).
    buffered: u64,
    /// Bytes handed to the writer, all whole lines.
    written: u64,
    /// Cuts the output back to a length after a write failed mid-row (`None`: cannot).
    cut: Option<fn(&mut W, u64) -> std::io::Result<()>>,
    buf: String,
}

impl CsvWriter<File> {
    /// Creates (or truncates) the file at `path` and writes the header line to it at once.
    ///
    /// # Errors
    /// Invalid or duplicate names ([`Error::InvalidName`], [`Error::DuplicateName`],
    /// [`Error::NoColumns`]) or an I/O error naming `path`.
    pub fn create<S: AsRef<str>>(path: impl AsRef<Path>, header: &[S]) -> Result<Self> {
        let path = path.as_ref();
        // Check the names before touching the file system.
        check_names(header.iter().map(AsRef::as_ref))?;
        let file = File::create(path).map_err(|e| Error::io("create", path, e))?;
        let mut w = Self::from_writer(file, path, header)?;
        w.cut = Some(|file, len| {
            use std::io::Seek as _;
            file.set_len(len)?;
            file.seek(std::io::SeekFrom::Start(len)).map(drop)
        });
        Ok(w)
    }
}

impl CsvWriter<File> {
    /// Opens the file a run wrote up to `mark` ([`RowSink::mark`]) to go on writing after it:
    /// checks that it starts with this `header` and holds at least `mark`'s bytes, cuts off
    /// whatever was written after the mark (the rows of a run killed after its checkpoint), and
    /// appends from there.
    ///
    /// # Errors
    /// [`Error::Resume`] if the file is shorter than the mark or its header differs; an I/O
    /// error naming `path`.
    pub fn reopen<S: AsRef<str>>(
        path: impl AsRef<Path>,
        header: &[S],
        mark: &SinkMark,
    ) -> Result<Self> {
        use std::io::Read as _;
        let path = path.as_ref();
        check_names(header.iter().map(AsRef::as_ref))?;
        let line = header
            .iter()
            .map(AsRef::as_ref)
            .collect::<Vec<_>>()
            .join(",")
            + "\n";
        let bytes = match mark.bytes.as_slice() {
            [bytes] => *bytes,
            other => {
                return Err(Error::resume(
                    path,
                    format!(
                        "the checkpoint records {} file lengths for one CSV file",
                        other.len()
                    ),
                ));
            }
        };
        let mut file = open_at_least(path, bytes)?;
        let mut start = vec![0; line.len().min(usize::try_from(bytes).unwrap_or(usize::MAX))];
        file.read_exact(&mut start)
            .map_err(|e| Error::io("read", path, e))?;
        if start != line.as_bytes() {
            return Err(Error::resume(
                path,
                "its header line is not the one of this run".to_owned(),
            ));
        }
        cut_at(&mut file, path, bytes)?;
        Ok(Self {
            inner: Some(file),
            path: path.to_path_buf(),
            width: header.len(),
            rows: mark.rows,
            buffered: 0,
            written: bytes,
            cut: Some(|file, len| {
                use std::io::Seek as _;
                file.set_len(len)?;
                file.seek(std::io::SeekFrom::Start(len)).map(drop)
            }),
            buf: String::with_capacity(SPILL_BYTES + 1024),
        })
    }
}

impl<W: Write> CsvWriter<W> {
    /// Wraps any writer; `path` is only used to name the output in error messages.
    ///
    /// # Errors
    /// As [`create`](CsvWriter::create).
    pub fn from_writer<S: AsRef<str>>(
        writer: W,
        path: impl Into<PathBuf>,
        header: &[S],
    ) -> Result<Self> {
        check_names(header.iter().map(AsRef::as_ref))?;
        let mut w = Self {
            inner: Some(writer),
            path: path.into(),
            width: header.len(),
            rows: 0,
            buffered: 0,
            written: 0,
            cut: None,
            buf: String::with_capacity(SPILL_BYTES + 1024),
        };
        for (i, name) in header.iter().enumerate() {
            if i > 0 {
                w.buf.push(',');
            }
            w.buf.push_str(name.as_ref());
        }
        w.buf.push('\n');
        w.flush()?;
        Ok(w)
    }

    /// Appends one row; `row.len()` must equal the number of header columns.
    ///
    /// # Errors
    /// [`Error::RowLength`], [`Error::Finished`], or an I/O error naming the file when a
    /// buffer spill fails.
    pub fn write_row(&mut self, row: &[f64]) -> Result<()> {
        if self.inner.is_none() {
            return Err(Error::Finished {
                path: self.path.clone(),
            });
        }
        if row.len() != self.width {
            return Err(Error::RowLength {
                path: self.path.clone(),
                row: self.rows,
                expected: self.width,
                found: row.len(),
            });
        }
        for (i, &x) in row.iter().enumerate() {
            if i > 0 {
                self.buf.push(',');
            }
            format_f64(x, &mut self.buf);
        }
        self.buf.push('\n');
        self.rows += 1;
        self.buffered += 1;
        if self.buf.len() >= SPILL_BYTES {
            self.spill()?;
        }
        Ok(())
    }

    /// Hands all buffered rows to the underlying writer and flushes it.
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

    /// Flushes and stops: the file holds the header and every row written so far.
    /// Later writes fail with [`Error::Finished`]; finishing again does nothing.
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

    /// Finishes and returns the underlying writer (e.g. the `Vec<u8>` written to).
    ///
    /// # Errors
    /// [`Error::Finished`] if already finished, or an I/O error naming the file.
    pub fn into_inner(mut self) -> Result<W> {
        self.flush()?;
        self.inner.take().ok_or_else(|| Error::Finished {
            path: self.path.clone(),
        })
    }

    /// Number of data rows accepted so far (header excluded), less those a failed write lost:
    /// after a failure, and after [`finish`](Self::finish), the rows in the file.
    pub fn rows_written(&self) -> u64 {
        self.rows
    }

    /// The path given at creation, used in error messages.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes the buffer to the underlying writer without flushing it. If the writer fails
    /// part-way (a full disk, a file-size limit), the rows it took whole stay and are counted,
    /// the rest of the buffer is dropped (retrying a partly written buffer would duplicate
    /// rows), and a row cut in two is cut off the file, which so ends on a row boundary.
    fn spill(&mut self) -> Result<()> {
        if self.buf.is_empty() {
            return Ok(());
        }
        let Some(w) = self.inner.as_mut() else {
            return Err(Error::Finished {
                path: self.path.clone(),
            });
        };
        let bytes = self.buf.as_bytes();
        let (done, failure) = write_some(w, bytes);
        // The first spill carries the header line (a failed one fails `create`).
        let header = self.written == 0;
        let whole = bytes[..done]
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let lines = bytes[..whole].iter().filter(|&&b| b == b'\n').count() as u64;
        let rows = lines.saturating_sub(u64::from(header && whole > 0));
        self.written += whole as u64;
        self.rows -= self.buffered - rows;
        self.buffered = 0;
        self.buf.clear();
        let Some(e) = failure else {
            return Ok(());
        };
        if done > whole
            && let Some(cut) = self.cut
            && let Err(c) = cut(w, self.written)
        {
            let cause = std::io::Error::new(c.kind(), format!("{e}; the cut row stays: {c}"));
            return Err(Error::io("write to", &self.path, cause));
        }
        Err(Error::io("write to", &self.path, e))
    }
}

/// Writes `bytes` as `write_all` does, but says how many reached the writer before a failure.
fn write_some<W: Write>(w: &mut W, bytes: &[u8]) -> (usize, Option<std::io::Error>) {
    let mut done = 0;
    while done < bytes.len() {
        match w.write(&bytes[done..]) {
            Ok(0) => return (done, Some(std::io::ErrorKind::WriteZero.into())),
            Ok(k) => done += k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return (done, Some(e)),
        }
    }
    (done, None)
}

impl<W: Write> Drop for CsvWriter<W> {
    fn drop(&mut self) {
        if self.inner.is_some() {
            // Best effort: a caller who wants the error calls `finish` first.
            let _ = self.finish();
        }
    }
}

impl<W: Write> RowSink for CsvWriter<W> {
    fn write_row(&mut self, row: &[f64]) -> Result<()> {
        CsvWriter::write_row(self, row)
    }
    fn flush(&mut self) -> Result<()> {
        CsvWriter::flush(self)
    }
    fn finish(&mut self) -> Result<()> {
        CsvWriter::finish(self)
    }
    fn rows_written(&self) -> u64 {
        CsvWriter::rows_written(self)
    }
    fn mark(&mut self) -> Result<SinkMark> {
        CsvWriter::flush(self)?;
        Ok(SinkMark {
            rows: self.rows,
            bytes: vec![self.written],
        })
    }
}

/// Opens `path` for reading and writing, checking that it holds at least `bytes` (what a
/// checkpoint recorded of it).
///
/// # Errors
/// [`Error::Resume`] if it is shorter; an I/O error naming `path`.
pub fn open_at_least(path: &Path, bytes: u64) -> Result<std::fs::File> {
    let file = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(path)
        .map_err(|e| Error::io("open", path, e))?;
    let length = file
        .metadata()
        .map_err(|e| Error::io("read the length of", path, e))?
        .len();
    if length < bytes {
        return Err(Error::resume(
            path,
            format!("{length} bytes, but the checkpoint was taken after {bytes}"),
        ));
    }
    Ok(file)
}

/// Cuts `file` (at `path`) to `bytes` and puts its cursor there, to append after a checkpoint.
///
/// # Errors
/// An I/O error naming `path`.
pub fn cut_at(file: &mut std::fs::File, path: &Path, bytes: u64) -> Result<()> {
    use std::io::Seek as _;
    file.set_len(bytes).map_err(|e| Error::io("cut", path, e))?;
    file.seek(std::io::SeekFrom::Start(bytes))
        .map_err(|e| Error::io("seek in", path, e))?;
    Ok(())
}

/// Writes a whole table to `path` as CSV (header = the table's column names).
///
/// # Errors
/// An I/O error naming `path`.
pub fn write_csv(path: impl AsRef<Path>, table: &Table) -> Result<()> {
    let names: Vec<&str> = table.names().collect();
    let mut w = CsvWriter::create(path, &names)?;
    let mut row = vec![0.0; table.n_columns()];
    for i in 0..table.n_rows() {
        for (slot, col) in row.iter_mut().zip(table.columns()) {
            *slot = col.values[i];
        }
        w.write_row(&row)?;
    }
    w.finish()
}
