//! The sensitivity file of a run, `sensitivity.npy` (shape `[samples, 2n, columns]`) or
//! `sensitivity.csv` (`t`, then the entries row by row, named `q_x/q0_x`), written a stored
//! step at a time ([`SensitivityWriter`]), continued after a checkpoint
//! ([`SensitivityWriter::reopen`]), and the sink that writes the tangent run's Jacobians into it
//! and keeps them in memory when asked ([`JacobianFile`]).

use std::path::Path;

use marsden_io::{CsvWriter, NpyShape, NpyWriter, RowSink as _};
use marsden_problem::problem::Format;

use crate::checkpoint::Mark;
use crate::sensitivity::{JacobianSink, Sensitivities, SensitivitySummary};

/// `sensitivity.npy`.
pub const SENSITIVITY_NPY: &str = "sensitivity.npy";
/// `sensitivity.csv`.
pub const SENSITIVITY_CSV: &str = "sensitivity.csv";

/// Writes the stored Jacobians into `dir` in `format`; returns the file's name.
///
/// # Errors
/// An I/O error, as text.
pub fn write(dir: &Path, format: Format, found: &Sensitivities) -> Result<String, String> {
    let mut writer = SensitivityWriter::create(dir, format, &found.summary)?;
    for (t, jac) in &found.samples {
        writer.write(*t, jac)?;
    }
    writer.finish()
}

/// The sensitivity file of a run, written a stored step at a time: `sensitivity.npy` of shape
/// `[samples, 2n, columns]`, or `sensitivity.csv` (`t`, then the entries row by row).
pub enum SensitivityWriter {
    /// `sensitivity.npy`.
    Npy(NpyWriter<std::fs::File>),
    /// `sensitivity.csv`, and a row buffer.
    Csv(CsvWriter<std::fs::File>, Vec<f64>),
}

impl SensitivityWriter {
    /// Creates the file for Jacobians of the summary's rows and columns.
    ///
    /// # Errors
    /// An I/O error, as text.
    pub fn create(
        dir: &Path,
        format: Format,
        summary: &SensitivitySummary,
    ) -> Result<Self, String> {
        let (rows, columns) = (summary.rows.len(), summary.columns.len());
        match format {
            Format::Npy => {
                let shape = NpyShape::Stack { rows, columns };
                let w = NpyWriter::create(dir.join(SENSITIVITY_NPY), shape).map_err(text)?;
                Ok(Self::Npy(w))
            }
            Format::Csv => {
                let header = csv_header(summary);
                let w = CsvWriter::create(dir.join(SENSITIVITY_CSV), &header).map_err(text)?;
                Ok(Self::Csv(w, Vec::with_capacity(rows * columns + 1)))
            }
        }
    }

    /// Opens the file of a tangent run checkpointed at `mark`, to go on after it: the
    /// Jacobians written after the checkpoint (by a run killed then) are cut off.
    ///
    /// # Errors
    /// The file is shorter than the mark, or its CSV header is not this run's; an I/O error.
    pub fn reopen(
        dir: &Path,
        format: Format,
        summary: &SensitivitySummary,
        mark: &Mark,
    ) -> Result<Self, String> {
        let (rows, columns) = (summary.rows.len(), summary.columns.len());
        match format {
            Format::Npy => {
                let shape = NpyShape::Stack { rows, columns };
                let path = dir.join(SENSITIVITY_NPY);
                let w = NpyWriter::reopen(path, shape, mark.rows).map_err(text)?;
                Ok(Self::Npy(w))
            }
            Format::Csv => {
                let header = csv_header(summary);
                let path = dir.join(SENSITIVITY_CSV);
                let w = CsvWriter::reopen(path, &header, &mark.into()).map_err(text)?;
                Ok(Self::Csv(w, Vec::with_capacity(rows * columns + 1)))
            }
        }
    }

    /// Flushes, and says where the file stands.
    ///
    /// # Errors
    /// An I/O error, as text.
    pub fn mark(&mut self) -> Result<Mark, String> {
        match self {
            Self::Npy(w) => {
                w.flush().map_err(text)?;
                Ok(Mark {
                    rows: w.rows_written(),
                    bytes: Vec::new(),
                })
            }
            Self::Csv(w, _) => w.mark().map(Mark::from).map_err(text),
        }
    }

    /// Appends the Jacobian of the stored step at `t`.
    ///
    /// # Errors
    /// An I/O error, as text.
    pub fn write(&mut self, t: f64, jacobian: &[f64]) -> Result<(), String> {
        match self {
            Self::Npy(w) => w.write_row(jacobian).map_err(text),
            Self::Csv(w, row) => {
                row.clear();
                row.push(t);
                row.extend_from_slice(jacobian);
                w.write_row(row).map_err(text)
            }
        }
    }

    /// Closes the file; returns its name.
    ///
    /// # Errors
    /// An I/O error, as text.
    pub fn finish(self) -> Result<String, String> {
        match self {
            Self::Npy(mut w) => {
                w.finish().map_err(text)?;
                Ok(SENSITIVITY_NPY.to_owned())
            }
            Self::Csv(mut w, _) => {
                w.finish().map_err(text)?;
                Ok(SENSITIVITY_CSV.to_owned())
            }
        }
    }
}

/// `t`, then `q_x/q0_x` … row by row.
fn csv_header(summary: &SensitivitySummary) -> Vec<String> {
    let mut header = vec!["t".to_owned()];
    for r in &summary.rows {
        header.extend(summary.columns.iter().map(|c| format!("{r}/{c}")));
    }
    header
}

fn text(e: marsden_io::Error) -> String {
    e.to_string()
}

/// The tangent run's Jacobians into the sensitivity file (when there is one) and into memory
/// (when kept): a [`JacobianSink`] whose first write error is kept and stops the writing.
pub struct JacobianFile {
    /// The file (`None`: not written).
    pub writer: Option<SensitivityWriter>,
    /// The Jacobians kept in memory (`None`: not kept).
    pub kept: Option<Vec<(f64, Vec<f64>)>>,
    /// The first write error.
    pub error: Option<String>,
}

impl JacobianSink for JacobianFile {
    fn take(&mut self, t: f64, jacobian: &[f64]) {
        if let Some(kept) = self.kept.as_mut() {
            kept.push((t, jacobian.to_vec()));
        }
        if let (Some(w), None) = (self.writer.as_mut(), &self.error)
            && let Err(e) = w.write(t, jacobian)
        {
            self.error = Some(e);
        }
    }

    fn mark(&mut self) -> Result<Option<Mark>, String> {
        if let Some(e) = &self.error {
            return Err(e.clone());
        }
        self.writer
            .as_mut()
            .map(SensitivityWriter::mark)
            .transpose()
    }
}
