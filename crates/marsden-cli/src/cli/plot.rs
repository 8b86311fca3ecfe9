//! `marsden plot DIR`: re-draws the plots of a finished (or failed) run.

use std::path::Path;

use marsden_spec::plots;

use crate::error::{CliError, Status};

/// Reads the run in `dir` and draws every plot its columns allow.
pub fn plot(dir: &Path) -> Result<Status, CliError> {
    for r in &plots::redraw(dir)? {
        println!("wrote {}", r.path.display());
        for note in &r.notes {
            println!("  note: {note}");
        }
    }
    Ok(Status::Completed)
}
