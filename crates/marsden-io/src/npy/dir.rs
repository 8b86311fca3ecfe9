//! A directory of `.npy` files, one per [`Group`](crate::Group) of a [`Layout`].

use std::fs::File;
use std::path::{Path, PathBuf};

use super::reader::read_npy;
use super::writer::{NpyShape, NpyWriter};
use crate::error::{Error, Result};
use crate::layout::{GroupKind, Layout};
use crate::sink::RowSink;
use crate::table::{Column, Table};

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

    /// Rows written so far.
    pub fn rows_written(&self) -> u64 {
        self.rows
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
    let dir = dir.as_ref();
    let mut columns = Vec::with_capacity(layout.width());
    let mut rows: Option<(u64, PathBuf)> = None;
    for g in layout.groups() {
        let path = file_of(dir, &g.name);
        let a = read_npy(&path)?;
        let width = g.width() as u64;
        let n = match (g.kind, a.shape.as_slice()) {
            (GroupKind::Scalar, &[n]) => n,
            (GroupKind::Vector, &[n, m]) if m == width => n,
            (_, shape) => {
                return Err(Error::Npy {
                    path,
                    message: format!(
                        "shape {shape:?} does not fit group `{}` of {width} column(s)",
                        g.name
                    ),
                });
            }
        };
        match &rows {
            Some((first, first_path)) if *first != n => {
                return Err(Error::Npy {
                    path,
                    message: format!("{n} rows but {} has {first}", first_path.display()),
                });
            }
            Some(_) => {}
            None => rows = Some((n, path.clone())),
        }
        let w = g.width();
        for (j, name) in g.columns.iter().enumerate() {
            let values = a.data.iter().skip(j).step_by(w.max(1)).copied().collect();
            columns.push(Column::new(name.clone(), values));
        }
    }
    Table::new(columns)
}
