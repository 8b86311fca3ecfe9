//! Writes a sweep's table as its rows arrive, so a sweep of millions of members holds only
//! the rows of the members in flight: `sweep.csv` (or, with `[output] format = "npy"`,
//! `sweep.npy`, a `members × columns` array whose column names are in `summary.json`), and at
//! the end a small `summary.json` (`summary.shard-i-of-n.json` for a shard) with the counts,
//! the worst energy error or balance defect and the first failures' messages.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use marsden_io::{NpyShape, NpyWriter};
use serde_json::json;

use super::shard::Shard;
use super::summary::RunStatus;
use super::sweep_table::{self, Preserved, SweepColumns, SweepRow};
use crate::problem::spec::ENERGY_NOT_AVAILABLE;
use crate::problem::{Format, RunSpec};

/// The failures' messages kept for `summary.json` (the table has them all).
pub const FAILURES_KEPT: usize = 100;

/// The open table file.
enum Table {
    Csv(BufWriter<File>),
    Npy(NpyWriter<File>),
}

/// Streams the rows of a sweep (a shard's or the whole sweep's) into `dir`.
pub struct SweepWriter {
    dir: PathBuf,
    shard: Shard,
    columns: SweepColumns,
    table: Table,
    table_name: String,
    rows: usize,
    failed: usize,
    interrupted: usize,
    worst: Option<f64>,
    failures: Vec<(usize, String)>,
}

impl SweepWriter {
    /// Creates the table file in `dir` (which must exist).
    ///
    /// # Errors
    /// The file cannot be created, as text naming it.
    pub fn create(
        dir: &Path,
        shard: Shard,
        columns: SweepColumns,
        format: Format,
    ) -> Result<Self, String> {
        let suffix = shard.suffix();
        let (table_name, table) = match format {
            Format::Csv => {
                let name = format!("sweep{suffix}.csv");
                let path = dir.join(&name);
                let file = File::create(&path).map_err(|e| cannot("create", &path, &e))?;
                let mut w = BufWriter::new(file);
                w.write_all(sweep_table::csv_header(&columns).as_bytes())
                    .map_err(|e| cannot("write", &path, &e))?;
                (name, Table::Csv(w))
            }
            Format::Npy => {
                let name = format!("sweep{suffix}.npy");
                let width = columns.numeric_names().len() + 1;
                let shape = NpyShape::Matrix { columns: width };
                let writer =
                    NpyWriter::create(dir.join(&name), shape).map_err(|e| e.to_string())?;
                (name, Table::Npy(writer))
            }
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            shard,
            columns,
            table,
            table_name,
            rows: 0,
            failed: 0,
            interrupted: 0,
            worst: None,
            failures: Vec::new(),
        })
    }

    /// Appends a row and counts it.
    ///
    /// # Errors
    /// The table cannot be written, as text naming it.
    pub fn push(&mut self, row: &SweepRow) -> Result<(), String> {
        match &mut self.table {
            Table::Csv(w) => w
                .write_all(sweep_table::csv_line(&self.columns, row).as_bytes())
                .map_err(|e| cannot("write", &self.dir.join(&self.table_name), &e))?,
            Table::Npy(w) => {
                let mut numeric = row.numeric(&self.columns);
                numeric.push(f64::from(row.status.code()));
                w.write_row(&numeric).map_err(|e| e.to_string())?;
            }
        }
        self.rows += 1;
        match row.status {
            RunStatus::Completed | RunStatus::Stopped => {}
            RunStatus::Failed => self.failed += 1,
            RunStatus::Interrupted => self.interrupted += 1,
        }
        if let (Some(e), true) = (&row.error, self.failures.len() < FAILURES_KEPT) {
            self.failures.push((row.member, e.clone()));
        }
        let preserved = row
            .preserved(self.columns.preserved)
            .map_or(f64::NAN, |p| p.0);
        if preserved.is_finite() {
            self.worst = Some(self.worst.map_or(preserved, |w| w.max(preserved)));
        }
        Ok(())
    }

    /// Members counted so far: (run, failed, interrupted).
    pub fn counts(&self) -> (usize, usize, usize) {
        (self.rows, self.failed, self.interrupted)
    }

    /// Closes the table and writes `summary.json`; returns the file names written.
    ///
    /// # Errors
    /// A file cannot be written, as text naming it.
    pub fn finish(mut self, total: usize, base: &RunSpec) -> Result<Vec<String>, String> {
        match &mut self.table {
            Table::Csv(w) => w
                .flush()
                .map_err(|e| cannot("write", &self.dir.join(&self.table_name), &e))?,
            Table::Npy(w) => w.finish().map_err(|e| e.to_string())?,
        }
        let json_name = format!("summary{}.json", self.shard.suffix());
        let text =
            serde_json::to_string_pretty(&self.summary(total, base)).map_err(|e| e.to_string())?;
        let path = self.dir.join(&json_name);
        std::fs::write(&path, text + "\n").map_err(|e| cannot("write", &path, &e))?;
        Ok(vec![self.table_name.clone(), json_name])
    }

    /// `summary.json` of a sweep: counts, the worst energy error (or balance defect), the
    /// table's name and columns, the first failures, and what every member shares: the
    /// method, `h` and the swept values of the first and last members.
    fn summary(&self, total: usize, base: &RunSpec) -> serde_json::Value {
        let steps = base.integrator.grid.steps;
        let status = match (self.failed, self.interrupted) {
            (0, 0) => "completed",
            (0, _) => "interrupted",
            _ => "failed",
        };
        let mut columns = self.columns.numeric_names();
        columns.push("status".to_owned());
        if matches!(self.table, Table::Csv(_)) {
            columns.push("error".to_owned());
        }
        let preserved = match self.columns.preserved {
            Preserved::Energy => json!({ "energy": { "max_rel_error": self.worst } }),
            Preserved::Balance => json!({ "energy_balance": { "max_defect": self.worst } }),
            Preserved::Nothing => json!({ "energy_not_available": ENERGY_NOT_AVAILABLE }),
        };
        let failures: Vec<serde_json::Value> = self
            .failures
            .iter()
            .map(|(member, error)| json!({ "member": member, "error": error }))
            .collect();
        let mut summary = json!({
            "kind": "sweep",
            "status": status,
            "swept": self.columns.swept.join(" × "),
            "swept_columns": self.columns.swept,
            "members": total,
            "shard": { "index": self.shard.index, "count": self.shard.count },
            "members_run": self.rows,
            "failed": self.failed,
            "interrupted": self.interrupted,
            "steps": steps,
            "method": base.method_name(),
            "order": base.method_order(),
            "h": base.integrator.grid.h,
            "t0": base.integrator.grid.t0,
            "values": base.sweep.as_ref().map(|s| {
                json!({
                    "first": s.values_of(0),
                    "last": s.values_of(s.count().saturating_sub(1)),
                })
            }),
            "table": self.table_name,
            "columns": columns,
            "first_failures": failures,
        });
        if let (Some(s), Some(p)) = (summary.as_object_mut(), preserved.as_object()) {
            s.extend(p.clone());
        }
        summary
    }
}

fn cannot(what: &str, path: &Path, e: &std::io::Error) -> String {
    format!("cannot {what} {}: {e}", path.display())
}
