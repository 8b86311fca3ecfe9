//! A directory of `.npy` files, one per [`Group`](crate::Group) of a [`Layout`].

use std::fs::File;
use std::path::{Path, PathBuf};

use super::reader::NpyValues;
use super::writer::{NpyShape, NpyWriter};
use crate::error::{Error, Result};
use crate::layout::{Group, GroupKind, Layout};
use crate::sink::{RowSink, SinkMark};
use crate::table::{Collector, Table};
use crate::thin::{Thinned, Thinner};

fn shape_of(kind: GroupKind, width: usize) -> NpyShape {
    match kind {
        GroupKind::Scalar => NpyShape::Vector,
        GroupKind::Vector => NpyShape::Matrix { columns: width },
    }
}

fn file_of(dir: &Path, group: &str) -> PathBuf {
    dir.join(format!("{group}.npy"))
}

/// Streams flat rows (ordered as [`Layout::column_names`]) into `<dir>/<group>.npy` files:
/// `t.npy` 1-D, `q.npy` 2-D `rows × n`, and so on.
#[derive(Debug)]
pub struct NpyDirWriter {
    dir: PathBuf,
    writers: Vec<NpyWriter<File>>,
    width: usize,
    rows: u64,
}

impl NpyDirWriter {
    /// Creates `dir` if needed and one `.npy` file per group (existing ones are truncated).
    ///
    /// # Errors
    /// An I/O error naming the directory or file.
    pub fn create(dir: impl AsRef<Path>, layout: &Layout) -> Result<Self> {
        let dir = dir.as_ref();
        std::fs::create_dir_all(dir).map_err(|e| Error::io("create directory", dir, e))?;
        let writers = layout
            .groups()
            .iter()
            .map(|g| NpyWriter::create(file_of(dir, &g.name), shape_of(g.kind, g.width())))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            writers,
            width: layout.width(),
            rows: 0,
        })
    }

    /// Opens the files a run wrote up to `mark` ([`RowSink::mark`]) to go on writing after it
    /// ([`NpyWriter::reopen`]: data past the mark is cut off).
    ///
    /// # Errors
    /// [`Error::Resume`] if a file holds fewer rows than the mark; an I/O error naming the file.
    pub fn reopen(dir: impl AsRef<Path>, layout: &Layout, mark: &SinkMark) -> Result<Self> {
        let dir = dir.as_ref();
        let writers = layout
            .groups()
            .iter()
            .map(|g| {
                NpyWriter::reopen(
                    file_of(dir, &g.name),
                    shape_of(g.kind, g.width()),
                    mark.rows,
                )
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            writers,
            width: layout.width(),
            rows: mark.rows,
        })
    }

    /// Appends one flat row, split among the group files.
    ///
    /// # Errors
    /// [`Error::RowLength`], [`Error::Finished`], or an I/O error naming the file.
    pub fn write_row(&mut self, row: &[f64]) -> Result<()> {
        if row.len() != self.width {
            return Err(Error::RowLength {
                path: self.dir.clone(),
                row: self.rows,
                expected: self.width,
                found: row.len(),
            });
        }
        let mut rest = row;
        for w in &mut self.writers {
            let (mine, tail) = rest.split_at(w.shape().row_width());
            w.write_row(mine)?;
            rest = tail;
        }
        self.rows += 1;
        Ok(())
    }

    /// Flushes every file (each then holds exactly the rows written so far).
    ///
    /// # Errors
    /// The first I/O error, naming its file.
    pub fn flush(&mut self) -> Result<()> {
        self.writers.iter_mut().try_for_each(NpyWriter::flush)
    }

    /// Finishes every file, even after a failure; returns the first error.
    ///
    /// # Errors
    /// The first I/O error, naming its file.
    pub fn finish(&mut self) -> Result<()> {
        let mut first = Ok(());
        for w in &mut self.writers {
            let r = w.finish();
            if first.is_ok() {
                first = r;
            }
        }
        first
    }

    /// Rows written so far; after a failed write, the rows every file holds whole.
    pub fn rows_written(&self) -> u64 {
        self.writers
            .iter()
            .map(NpyWriter::rows_written)
            .fold(self.rows, u64::min)
    }

    /// The output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

impl RowSink for NpyDirWriter {
    fn write_row(&mut self, row: &[f64]) -> Result<()> {
        NpyDirWriter::write_row(self, row)
    }
    fn flush(&mut self) -> Result<()> {
        NpyDirWriter::flush(self)
    }
    fn finish(&mut self) -> Result<()> {
        NpyDirWriter::finish(self)
    }
    fn rows_written(&self) -> u64 {
        NpyDirWriter::rows_written(self)
    }
    fn mark(&mut self) -> Result<SinkMark> {
        NpyDirWriter::flush(self)?;
        let rows = NpyDirWriter::rows_written(self);
        let header = super::header::HEADER_BYTES as u64;
        let bytes = (self.writers.iter())
            .map(|w| header + rows * 8 * w.shape().row_width() as u64)
            .collect();
        Ok(SinkMark { rows, bytes })
    }
}

/// Writes a whole table as one `.npy` per group of `layout` into `dir`.
///
/// # Errors
/// [`Error::MissingColumn`] if the table lacks a layout column, or an I/O error naming the file.
pub fn write_npy_dir(dir: impl AsRef<Path>, layout: &Layout, table: &Table) -> Result<()> {
    let groups = layout.select(table)?;
    let dir = dir.as_ref();
    std::fs::create_dir_all(dir).map_err(|e| Error::io("create directory", dir, e))?;
    for (g, cols) in layout.groups().iter().zip(&groups) {
        let mut w = NpyWriter::create(file_of(dir, &g.name), shape_of(g.kind, g.width()))?;
        let mut row = vec![0.0; cols.len()];
        for i in 0..table.n_rows() {
            for (slot, c) in row.iter_mut().zip(cols) {
                *slot = c.values[i];
            }
            w.write_row(&row)?;
        }
        w.finish()?;
    }
    Ok(())
}

/// Reads `<dir>/<group>.npy` for every group of `layout` back into one table whose columns are
/// the layout's column names.
///
/// # Errors
/// An I/O error naming the file, or [`Error::Npy`] if a file's shape does not fit the layout
/// or the files disagree on the number of rows.
pub fn read_npy_dir(dir: impl AsRef<Path>, layout: &Layout) -> Result<Table> {
    let collector = Collector::new(owned_names(layout));
    stream_npy_dir(dir.as_ref(), layout, collector, false)?
        .0
        .into_table()
}

/// Reads a run's `.npy` files into a bounded [`Thinned`] sketch for plots (see [`Thinner`]),
/// keeping the extremes of the `monitored` columns; memory does not grow with the rows.
/// Files of a run cut short (killed) may end at different rows: the rows all files hold are
/// read and [`Thinned::cut`] says so.
///
/// # Errors
/// As [`read_npy_dir`], except for files that disagree on the number of rows.
pub fn read_npy_dir_thinned(
    dir: impl AsRef<Path>,
    layout: &Layout,
    monitored: &[&str],
    budget: usize,
) -> Result<Thinned> {
    let thinner = Thinner::new(owned_names(layout), monitored, budget);
    let (thinner, cut) = stream_npy_dir(dir.as_ref(), layout, thinner, true)?;
    let mut sketch = thinner.finish_table()?;
    sketch.cut = cut;
    Ok(sketch)
}

/// Streams the rows of the group files of `layout` in `dir` into `sink`, all files in step.
/// Files that disagree on the number of rows are an error, or with `shortest` the rows they
/// all hold are read and the second value says how many were left out.
fn stream_npy_dir<S: RowSink>(
    dir: &Path,
    layout: &Layout,
    mut sink: S,
    shortest: bool,
) -> Result<(S, Option<String>)> {
    let mut files = Vec::with_capacity(layout.groups().len());
    let mut counts: Vec<(u64, PathBuf)> = Vec::with_capacity(layout.groups().len());
    for g in layout.groups() {
        let path = file_of(dir, &g.name);
        let file = NpyValues::open(&path)?;
        let n = rows_of(&path, g, &file.shape)?;
        if let Some((first, first_path)) = counts.first()
            && *first != n
            && !shortest
        {
            return Err(Error::Npy {
                path,
                message: format!("{n} rows but {} has {first}", first_path.display()),
            });
        }
        counts.push((n, path));
        files.push(file);
    }
    let rows = counts.iter().map(|c| c.0).min().unwrap_or(0);
    let most = counts.iter().map(|c| c.0).max().unwrap_or(0);
    let cut = (most > rows).then(|| {
        format!(
            "the files end at different rows (a run cut short): the {rows} rows all hold are \
             drawn, {} left out",
            most - rows
        )
    });
    let mut row = Vec::with_capacity(layout.width());
    for _ in 0..rows {
        row.clear();
        for (g, file) in layout.groups().iter().zip(&mut files) {
            for _ in 0..g.width() {
                row.push(file.next_value()?);
            }
        }
        sink.write_row(&row)?;
    }
    Ok((sink, cut))
}

/// Number of rows of a group file of shape `shape`, checked against the group's kind and width.
fn rows_of(path: &Path, g: &Group, shape: &[u64]) -> Result<u64> {
    let width = g.width() as u64;
    match (g.kind, shape) {
        (GroupKind::Scalar, &[n]) => Ok(n),
        (GroupKind::Vector, &[n, m]) if m == width => Ok(n),
        (_, shape) => Err(Error::Npy {
            path: path.to_path_buf(),
            message: format!(
                "shape {shape:?} does not fit group `{}` of {width} column(s)",
                g.name
            ),
        }),
    }
}

fn owned_names(layout: &Layout) -> Vec<String> {
    layout
        .column_names()
        .into_iter()
        .map(str::to_owned)
        .collect()
}
