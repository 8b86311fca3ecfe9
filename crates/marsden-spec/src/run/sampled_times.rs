//! Where the samples at `[output] times` go: `samples.csv` (rows `t, q_…, p_…,
//! observables…`, streamed as the run reaches each time) or, with `[output] format = "npy"`,
//! `samples.npy` (the same rows as a `times × (1 + 2n + observables)` array, its column names
//! in `summary.json`'s `output.sample_columns`), and the in-memory samples ([`SampledStates`]).

use std::path::Path;

use marsden_io::{CsvWriter, Group, Layout, NpyDirWriter, RowSink};

use crate::problem::{Format, RunSpec};
pub use marsden_engine::samples::{SAMPLES_CSV, sample_columns};

/// `samples.npy`, the samples with `[output] format = "npy"`.
pub const SAMPLES_NPY: &str = "samples.npy";

/// The samples of a run kept in memory, one column per quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampledStates {
    /// The requested times reached.
    pub t: Vec<f64>,
    /// Positions there, per coordinate.
    pub q: Vec<Vec<f64>>,
    /// Momenta there, per coordinate.
    pub p: Vec<Vec<f64>>,
    /// The observables there, per observable (the file's order).
    pub observables: Vec<Vec<f64>>,
    /// The observables' names, in the same order.
    pub observable_names: Vec<String>,
}

impl SampledStates {
    /// Empty samples of the system of `spec`.
    pub fn of(spec: &RunSpec) -> Self {
        let n = spec.system.dof();
        Self {
            t: Vec::new(),
            q: vec![Vec::new(); n],
            p: vec![Vec::new(); n],
            observables: vec![Vec::new(); spec.events.observables.len()],
            observable_names: spec.events.observables.names.clone(),
        }
    }
}

impl RowSink for SampledStates {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        let mut values = row.iter().copied();
        self.t.push(values.next().unwrap_or(f64::NAN));
        for column in self
            .q
            .iter_mut()
            .chain(&mut self.p)
            .chain(&mut self.observables)
        {
            column.push(values.next().unwrap_or(f64::NAN));
        }
        Ok(())
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        Ok(())
    }
    fn rows_written(&self) -> u64 {
        self.t.len() as u64
    }
}

/// The samples' destinations: the file, memory, or both.
pub struct SampleOutputs {
    /// `samples.csv` or `samples.npy` (`None`: no files written).
    pub file: Option<Box<dyn RowSink>>,
    /// The in-memory samples (`None`: not kept).
    pub memory: Option<SampledStates>,
}

impl SampleOutputs {
    /// The destinations of the samples of `spec` (`None` without `[output] times`): the file in
    /// `dir` when given (reopened at `resume_at` for a resumed run), memory when `keep`.
    ///
    /// # Errors
    /// An I/O error naming the file.
    pub fn open(
        spec: &RunSpec,
        dir: Option<&Path>,
        keep: bool,
        resume_at: Option<&marsden_io::SinkMark>,
    ) -> marsden_io::Result<Option<Self>> {
        if spec.output.times.is_empty() {
            return Ok(None);
        }
        let file = match dir {
            Some(dir) => Some(open_file(dir, spec, resume_at)?),
            None => None,
        };
        Ok(Some(Self {
            file,
            memory: keep.then(|| SampledStates::of(spec)),
        }))
    }
}

impl RowSink for SampleOutputs {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        if let Some(file) = &mut self.file {
            file.write_row(row)?;
        }
        match &mut self.memory {
            Some(memory) => memory.write_row(row),
            None => Ok(()),
        }
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.flush())
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        self.file.as_mut().map_or(Ok(()), |f| f.finish())
    }
    fn rows_written(&self) -> u64 {
        match (&self.file, &self.memory) {
            (Some(file), _) => file.rows_written(),
            (None, Some(memory)) => memory.rows_written(),
            (None, None) => 0,
        }
    }
    /// The file's mark: what a checkpoint cuts it back to (the memory is not resumed).
    fn mark(&mut self) -> marsden_io::Result<marsden_io::SinkMark> {
        match &mut self.file {
            Some(file) => file.mark(),
            None => Ok(marsden_io::SinkMark {
                rows: self.rows_written(),
                bytes: Vec::new(),
            }),
        }
    }
}

/// The file of the samples in `format`.
pub fn file_name(format: Format) -> &'static str {
    match format {
        Format::Csv => SAMPLES_CSV,
        Format::Npy => SAMPLES_NPY,
    }
}

/// The columns of the samples of `spec`.
pub fn columns(spec: &RunSpec) -> Vec<String> {
    sample_columns(&spec.system.coordinates, &spec.events.observables.names)
}

/// The `.npy` layout of the samples: one matrix group, `samples`.
fn npy_layout(spec: &RunSpec) -> marsden_io::Result<Layout> {
    Layout::new(vec![Group::vector("samples", columns(spec))])
}

/// Opens the samples' file in `dir`, in the output's format; reopened at `resume_at`.
fn open_file(
    dir: &Path,
    spec: &RunSpec,
    resume_at: Option<&marsden_io::SinkMark>,
) -> marsden_io::Result<Box<dyn RowSink>> {
    let columns = columns(spec);
    let sink: Box<dyn RowSink> = match (spec.output.format, resume_at) {
        (Format::Csv, None) => Box::new(CsvWriter::create(dir.join(SAMPLES_CSV), &columns)?),
        (Format::Csv, Some(mark)) => {
            Box::new(CsvWriter::reopen(dir.join(SAMPLES_CSV), &columns, mark)?)
        }
        (Format::Npy, None) => Box::new(NpyDirWriter::create(dir, &npy_layout(spec)?)?),
        (Format::Npy, Some(mark)) => Box::new(NpyDirWriter::reopen(dir, &npy_layout(spec)?, mark)?),
    };
    Ok(sink)
}
