//! `marsden plot DIR`: re-draws the plots of a finished (or failed) run.

use std::path::Path;

use marsden_io::{PlotOptions, Table, plot_run, read_csv, read_npy_dir};

use crate::error::{CliError, Diagnostic, Status};
use crate::run::output::{SUMMARY_JSON, TRAJECTORY_CSV, layout_from_columns};

/// Reads the run in `dir` and draws every plot its columns allow.
pub fn plot(dir: &Path) -> Result<Status, CliError> {
    let table = read_run(dir)?;
    let reports = plot_run(&table, dir, &PlotOptions::default())
        .map_err(|e| CliError::failed(Diagnostic::new(format!("cannot draw the plots: {e}"))))?;
    for r in &reports {
        println!("wrote {}", r.path.display());
        for note in &r.notes {
            println!("  note: {note}");
        }
    }
    Ok(Status::Completed)
}

/// The trajectory of a run directory: `trajectory.csv`, or the `.npy` files named by
/// `summary.json`.
fn read_run(dir: &Path) -> Result<Table, CliError> {
    let bad = |message: String| CliError::bad_input(Diagnostic::new(message));
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
