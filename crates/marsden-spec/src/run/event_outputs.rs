//! Where the events of a run go: `events.csv` (rows `event, t, q_…, p_…`, `event` the index
//! of the event in the file's `[[events]]`, streamed as the run locates them) or, with
//! `[output] format = "npy"`, `events.npy` (the same rows as a `records × (2 + 2n)` array,
//! its column names in `summary.json`'s `output.event_columns`), the in-memory records
//! ([`EventSamples`]) and, after the run, the Poincaré section of the records (`section.png`)
//! and the observables against time (`observables.png`).

use std::path::Path;

use marsden_io::{CsvWriter, Group, Layout, NpyDirWriter, PlotOptions, RowSink, Series, Table};

use crate::problem::{Format, RunSpec};
pub use marsden_engine::events::{EVENTS_CSV, event_columns};

/// The Poincaré section plot of the recorded events.
pub const SECTION_PNG: &str = "section.png";
/// The observables against time.
pub const OBSERVABLES_PNG: &str = "observables.png";

/// The event records of a run kept in memory, one column per quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventSamples {
    /// The events' names, in the file's order (`event` indexes them).
    pub names: Vec<String>,
    /// Which event each record is of.
    pub event: Vec<usize>,
    /// Times of the crossings.
    pub t: Vec<f64>,
    /// Positions there, per coordinate.
    pub q: Vec<Vec<f64>>,
    /// Momenta there, per coordinate.
    pub p: Vec<Vec<f64>>,
}

impl EventSamples {
    /// Empty records of the events of `spec`.
    pub fn of(spec: &RunSpec) -> Self {
        let n = spec.system.dof();
        Self {
            names: spec.events.events.iter().map(|e| e.name.clone()).collect(),
            event: Vec::new(),
            t: Vec::new(),
            q: vec![Vec::new(); n],
            p: vec![Vec::new(); n],
        }
    }

    /// Number of records.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}

impl RowSink for EventSamples {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        let mut values = row.iter().copied();
        let mut next = || values.next().unwrap_or(f64::NAN);
        // The index was written from a `usize`: exact.
        self.event.push(next() as usize);
        self.t.push(next());
        for column in self.q.iter_mut().chain(&mut self.p) {
            column.push(next());
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

/// The event records to the file and to memory.
pub struct EventTee<'a> {
    /// `events.csv` or `events.npy`.
    pub files: &'a mut dyn RowSink,
    /// The in-memory records.
    pub memory: &'a mut EventSamples,
}

impl RowSink for EventTee<'_> {
    fn write_row(&mut self, row: &[f64]) -> marsden_io::Result<()> {
        self.files.write_row(row)?;
        self.memory.write_row(row)
    }
    fn flush(&mut self) -> marsden_io::Result<()> {
        self.files.flush()
    }
    fn finish(&mut self) -> marsden_io::Result<()> {
        self.files.finish()
    }
    fn rows_written(&self) -> u64 {
        self.files.rows_written()
    }
    /// The files' mark: what a checkpoint cuts them back to (the memory is not resumed).
    fn mark(&mut self) -> marsden_io::Result<marsden_io::SinkMark> {
        self.files.mark()
    }
}

/// `events.npy`, the records with `[output] format = "npy"`.
pub const EVENTS_NPY: &str = "events.npy";

/// The file of the event records in `format`.
pub fn file_name(format: Format) -> &'static str {
    match format {
        Format::Csv => EVENTS_CSV,
        Format::Npy => EVENTS_NPY,
    }
}

/// The `.npy` layout of the records: one matrix group, `events`.
fn npy_layout(spec: &RunSpec) -> marsden_io::Result<Layout> {
    let columns = event_columns(&spec.system.coordinates);
    Layout::new(vec![Group::vector("events", columns)])
}

/// Opens the events' file in `dir` for the events of `spec` (`None` without events), in the
/// output's format; reopened at `resume_at` for a resumed run.
///
/// # Errors
/// An I/O error naming the file.
pub fn open(
    dir: &Path,
    spec: &RunSpec,
    resume_at: Option<&marsden_io::SinkMark>,
) -> marsden_io::Result<Option<Box<dyn RowSink>>> {
    if spec.events.events.is_empty() {
        return Ok(None);
    }
    let columns = event_columns(&spec.system.coordinates);
    let sink: Box<dyn RowSink> = match (spec.output.format, resume_at) {
        (Format::Csv, None) => Box::new(CsvWriter::create(dir.join(EVENTS_CSV), &columns)?),
        (Format::Csv, Some(mark)) => {
            Box::new(CsvWriter::reopen(dir.join(EVENTS_CSV), &columns, mark)?)
        }
        (Format::Npy, None) => Box::new(NpyDirWriter::create(dir, &npy_layout(spec)?)?),
        (Format::Npy, Some(mark)) => Box::new(NpyDirWriter::reopen(dir, &npy_layout(spec)?, mark)?),
    };
    Ok(Some(sink))
}

/// The event records in `dir` read back, as a table with the columns `event, t, q_…, p_…`.
///
/// # Errors
/// The file cannot be read, as text.
pub fn read(dir: &Path, spec: &RunSpec) -> Result<Table, String> {
    let columns = event_columns(&spec.system.coordinates);
    read_records(dir, spec.output.format, columns)
}

/// The event records in `dir` in `format` with `columns` (`summary.json`'s
/// `output.event_columns`), as a table.
///
/// # Errors
/// The file cannot be read, as text.
pub fn read_records(dir: &Path, format: Format, columns: Vec<String>) -> Result<Table, String> {
    let table = match format {
        Format::Csv => marsden_io::read_csv(dir.join(EVENTS_CSV)),
        Format::Npy => Layout::new(vec![Group::vector("events", columns)])
            .and_then(|layout| marsden_io::read_npy_dir(dir, &layout)),
    };
    table.map_err(|e| e.to_string())
}

/// The section plot's two axes as columns of the event records and their labels:
/// `[[column, label], [column, label]]` (`summary.json`'s `output.section`; empty without
/// events).
pub fn section_axes(spec: &RunSpec) -> Vec<[String; 2]> {
    let Some(section) = spec
        .events
        .section
        .as_ref()
        .filter(|_| !spec.events.events.is_empty())
    else {
        return Vec::new();
    };
    let c = &spec.system.coordinates;
    [&section.x, &section.y]
        .iter()
        .map(|(axis, label)| [axis.column(c).unwrap_or_default(), label.clone()])
        .collect()
}

/// Draws `section.png` from the event records in `dir`, in the axes of `[output] section`.
///
/// # Errors
/// The records cannot be read back or the plot cannot be written, as text.
pub fn draw_section(dir: &Path, spec: &RunSpec) -> Result<String, String> {
    let axes = section_axes(spec);
    let [x, y] = axes.as_slice() else {
        return Err("the system has no coordinates".to_owned());
    };
    let table = read(dir, spec)?;
    draw_section_of(dir, &table, x, y)
}

/// Draws `section.png` in `dir` from the records `table`, with the `[column, label]` axes `x`
/// and `y`.
///
/// # Errors
/// A column the records lack, or a plot that cannot be written, as text.
pub fn draw_section_of(
    dir: &Path,
    table: &Table,
    x: &[String; 2],
    y: &[String; 2],
) -> Result<String, String> {
    let x = series_of(table, &x[0], &x[1])?;
    let y = series_of(table, &y[0], &y[1])?;
    let path = dir.join(SECTION_PNG);
    marsden_io::plot::plot_section(&path, x, y, &PlotOptions::default())
        .map_err(|e| e.to_string())?;
    Ok(SECTION_PNG.to_owned())
}

/// The column `name` of `table` as a series labelled `label`.
fn series_of<'t>(table: &'t Table, name: &str, label: &'t str) -> Result<Series<'t>, String> {
    let column = (table.columns().iter())
        .find(|c| c.name == name)
        .ok_or_else(|| format!("the event records have no column {name}"))?;
    Ok(Series {
        name: label,
        values: &column.values,
    })
}

/// Draws `observables.png` from the trajectory's sketch `table` (the columns `names`: the
/// observables of the file, `summary.json`'s `output.observables`) with the plot options
/// `opts`; nothing without them.
///
/// # Errors
/// The plot cannot be written.
pub fn draw_observables(
    dir: &Path,
    names: &[String],
    table: &Table,
    opts: &PlotOptions,
) -> marsden_io::Result<Option<String>> {
    let find = |name: &str| table.columns().iter().find(|c| c.name == name);
    let (Some(t), false) = (find("t"), names.is_empty()) else {
        return Ok(None);
    };
    let series: Vec<Series<'_>> = (names.iter())
        .filter_map(|name| find(name))
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect();
    marsden_io::plot::plot_observables(dir.join(OBSERVABLES_PNG), &t.values, &series, opts)?;
    Ok(Some(OBSERVABLES_PNG.to_owned()))
}
