//! The plots of a run: drawn after `marsden run` from the files just written ([`draw`]), or
//! again later from a run's directory ([`redraw`], `marsden plot`).

use std::path::Path;

use marsden_io::{Layout, PlotOptions, PlotReport, Table, plot_run, read_csv, read_npy_dir};

use super::output::{self, SUMMARY_JSON, TRAJECTORY_CSV, layout_from_columns};
use crate::error::{Diagnostic, Error};
use crate::problem::{Format, RunSpec};

/// Reads the trajectory of `spec` back and draws every plot; returns the PNG file names.
///
/// # Errors
/// The trajectory cannot be read or a plot cannot be written.
pub fn draw(spec: &RunSpec, layout: &Layout) -> marsden_io::Result<Vec<String>> {
    let dir = &spec.output.dir;
    let table = match spec.output.format {
        Format::Csv => read_csv(dir.join(output::TRAJECTORY_CSV))?,
        Format::Npy => read_npy_dir(dir, layout)?,
    };
    let reports = plot_run(&table, dir, &PlotOptions::default())?;
    Ok(reports
        .iter()
        .filter_map(|r| r.path.file_name())
        .map(|f| f.to_string_lossy().into_owned())
        .collect())
}

/// Reads the run in `dir` (a finished or failed one) and draws every plot its columns allow.
///
/// # Errors
/// Bad input if `dir` holds no readable run; failed if a plot cannot be drawn.
pub fn redraw(dir: &Path) -> Result<Vec<PlotReport>, Error> {
    let table = read_run(dir)?;
    plot_run(&table, dir, &PlotOptions::default())
        .map_err(|e| Error::failed(Diagnostic::new(format!("cannot draw the plots: {e}"))))
}

/// The trajectory of a run directory: `trajectory.csv`, or the `.npy` files named by
/// `summary.json`.
fn read_run(dir: &Path) -> Result<Table, Error> {
    let bad = |message: String| Error::bad_input(Diagnostic::new(message));
    let csv = dir.join(TRAJECTORY_CSV);
    if csv.exists() {
        return read_csv(&csv).map_err(|e| bad(e.to_string()));
    }
    let summary = dir.join(SUMMARY_JSON);
    let text = std::fs::read_to_string(&summary).map_err(|e| {
        bad(format!(
            "{} has neither {TRAJECTORY_CSV} nor a readable {SUMMARY_JSON} ({e}): is it the output directory of a run?",
            dir.display()
        ))
    })?;
    let json: serde_json::Value = serde_json::from_str(&text)
        .map_err(|e| bad(format!("{} is not valid JSON: {e}", summary.display())))?;
    let columns: Vec<String> = json["output"]["columns"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|c| c.as_str().map(str::to_owned))
                .collect()
        })
        .unwrap_or_default();
    let layout = layout_from_columns(&columns)
        .map_err(|e| bad(format!("{}: output.columns: {e}", summary.display())))?;
    read_npy_dir(dir, &layout).map_err(|e| bad(e.to_string()))
}
