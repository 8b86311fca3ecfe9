//! Writes a sweep's table as its rows arrive, so a sweep of millions of members holds only
//! the rows of the members in flight: `sweep.csv` (or, with `[output] format = "npy"`,
//! `sweep.npy`, a `members × columns` array whose column names are in `summary.json`), and at
//! the end a small `summary.json` (`summary.shard-i-of-n.json` for a shard) with the counts,
//! the worst energy error or balance defect and the first failures' messages.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use marsden_engine::checkpoint::Mark;
use marsden_io::{NpyShape, NpyWriter};
use serde::{Deserialize, Serialize};
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

/// What the writer has counted of the rows so far (what `summary.json` reports), kept in a
/// sweep's checkpoint.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SweepCounts {
    /// Rows written.
    pub rows: usize,
    /// Members that failed.
    pub failed: usize,
    /// Members interrupted.
    pub interrupted: usize,
    /// The worst energy error or balance defect.
    pub worst: Option<f64>,
    /// The first failures' messages, by member.
    pub failures: Vec<(usize, String)>,
}

/// Streams the rows of a sweep (a shard's or the whole sweep's) into `dir`.
pub struct SweepWriter {
    dir: PathBuf,
    shard: Shard,
    columns: SweepColumns,
    table: Table,
    table_name: String,
    counts: SweepCounts,
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
        let table_name = table_name(shard, format);
        let path = dir.join(&table_name);
        let table = match format {
            Format::Csv => {
                let file = File::create(&path).map_err(|e| cannot("create", &path, &e))?;
                let mut w = BufWriter::new(file);
                w.write_all(sweep_table::csv_header(&columns).as_bytes())
                    .map_err(|e| cannot("write", &path, &e))?;
                Table::Csv(w)
            }
            Format::Npy => Table::Npy(
                NpyWriter::create(&path, npy_shape(&columns)).map_err(|e| e.to_string())?,
            ),
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            shard,
            columns,
            table,
            table_name,
            counts: SweepCounts::default(),
        })
    }

    /// Opens the table a killed sweep left in `dir` (as [`SweepWriter::create`] made it) to go
    /// on after its checkpoint: cuts off the rows written after `mark` and takes up the
    /// `counts` of that moment.
    ///
    /// # Errors
    /// The table is missing or shorter than the mark, or cannot be opened, as text naming it.
    pub fn reopen(
        dir: &Path,
        shard: Shard,
        columns: SweepColumns,
        format: Format,
        mark: &Mark,
        counts: SweepCounts,
    ) -> Result<Self, String> {
        let table_name = table_name(shard, format);
        let path = dir.join(&table_name);
        let table = match format {
            Format::Csv => {
                let [bytes] = mark.bytes.as_slice() else {
                    return Err(format!(
                        "the checkpoint records {} lengths for the one table {}",
                        mark.bytes.len(),
                        path.display()
                    ));
                };
                let mut file =
                    marsden_io::open_at_least(&path, *bytes).map_err(|e| e.to_string())?;
                marsden_io::cut_at(&mut file, &path, *bytes).map_err(|e| e.to_string())?;
                Table::Csv(BufWriter::new(file))
            }
            Format::Npy => Table::Npy(
                NpyWriter::reopen(&path, npy_shape(&columns), mark.rows)
                    .map_err(|e| e.to_string())?,
            ),
        };
        Ok(Self {
            dir: dir.to_path_buf(),
            shard,
            columns,
            table,
            table_name,
            counts,
        })
    }

    /// Flushes the table and says where it stands, with the counts so far (for a checkpoint).
    ///
    /// # Errors
    /// The table cannot be flushed, as text naming it.
    pub fn mark(&mut self) -> Result<(Mark, SweepCounts), String> {
        let path = self.dir.join(&self.table_name);
        let bytes = match &mut self.table {
            Table::Csv(w) => {
                w.flush().map_err(|e| cannot("write", &path, &e))?;
                let meta = w.get_ref().metadata();
                vec![
                    meta.map_err(|e| cannot("read the length of", &path, &e))?
                        .len(),
                ]
            }
            Table::Npy(w) => {
                w.flush().map_err(|e| e.to_string())?;
                Vec::new()
            }
        };
        let mark = Mark {
            rows: self.counts.rows as u64,
            bytes,
        };
        Ok((mark, self.counts.clone()))
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
        let c = &mut self.counts;
        c.rows += 1;
        match row.status {
            RunStatus::Completed | RunStatus::Stopped => {}
            RunStatus::Failed => c.failed += 1,
            RunStatus::Interrupted => c.interrupted += 1,
        }
        if let (Some(e), true) = (&row.error, c.failures.len() < FAILURES_KEPT) {
            c.failures.push((row.member, e.clone()));
        }
        let preserved = row
            .preserved(self.columns.preserved)
            .map_or(f64::NAN, |p| p.0);
        if preserved.is_finite() {
            c.worst = Some(c.worst.map_or(preserved, |w| w.max(preserved)));
        }
        Ok(())
    }

    /// Members counted so far: (run, failed, interrupted).
    pub fn counts(&self) -> (usize, usize, usize) {
        (
            self.counts.rows,
            self.counts.failed,
            self.counts.interrupted,
        )
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
        let c = &self.counts;
        let status = match (c.failed, c.interrupted) {
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
            Preserved::Energy => json!({ "energy": { "max_rel_error": c.worst } }),
            Preserved::Balance => json!({ "energy_balance": { "max_defect": c.worst } }),
            Preserved::Nothing => json!({ "energy_not_available": ENERGY_NOT_AVAILABLE }),
        };
        let failures: Vec<serde_json::Value> = c
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
            "members_run": c.rows,
            "failed": c.failed,
            "interrupted": c.interrupted,
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

/// `sweep.csv` or `sweep.npy`, with the shard's suffix.
fn table_name(shard: Shard, format: Format) -> String {
    format!("sweep{}.{}", shard.suffix(), format.name())
}

/// The `.npy` table's shape: the numeric columns and the status code.
fn npy_shape(columns: &SweepColumns) -> NpyShape {
    NpyShape::Matrix {
        columns: columns.numeric_names().len() + 1,
    }
}

fn cannot(what: &str, path: &Path, e: &std::io::Error) -> String {
    format!("cannot {what} {}: {e}", path.display())
}
