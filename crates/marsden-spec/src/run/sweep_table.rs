//! The summary table of a sweep: one row per member — its global index, the swept value, the
//! final time, the steps taken, the energy error and drift, the status and the error message —
//! rendered for stdout and written as CSV (`sweep.csv`, or `sweep.shard-i-of-n.csv` for a
//! shard) next to a small `summary.json` (`summary.shard-i-of-n.json`).
//!
//! CSV columns: `member,<swept>,t_final,steps,steps_requested,energy_max_rel_error,`
//! `energy_final_rel_error,energy_rel_drift,status,error` (the error quoted, empty when the
//! member completed). Numbers are written with Rust's shortest round-trip formatting.

use std::fmt::Write as _;
use std::path::Path;

use serde_json::json;

use super::shard::Shard;
use super::solve::RunRecord;
use super::summary::RunStatus;

/// One member's line of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    /// Global member index (the position of its value in the sweep).
    pub member: usize,
    /// The swept value.
    pub value: f64,
    /// Time of the last good state (NaN if the member could not start).
    pub t_final: f64,
    /// Steps completed.
    pub steps: usize,
    /// Steps requested.
    pub steps_requested: usize,
    /// `max |E − E₀| / |E₀|` over the sampled rows (NaN if none).
    pub energy_max_rel_error: f64,
    /// `(E_N − E₀)/|E₀|` at the last sampled row.
    pub energy_final_rel_error: f64,
    /// Least-squares slope of the relative energy error per unit time.
    pub energy_rel_drift: f64,
    /// Why the member did not complete (`None`: completed, or interrupted while running).
    pub error: Option<String>,
    /// How the member ended.
    pub status: RunStatus,
}

impl SweepRow {
    /// The row of member `member` with `value` from its run (or the reason it could not run).
    pub fn new(
        member: usize,
        value: f64,
        steps_requested: usize,
        result: Result<RunRecord, String>,
    ) -> Self {
        match result {
            Ok(record) => {
                let energy = record.diagnostics.energy.report();
                let seen = energy.samples > 0;
                let or_nan = |x: f64| if seen { x } else { f64::NAN };
                Self {
                    member,
                    value,
                    t_final: record.final_state.t,
                    steps: record.steps,
                    steps_requested,
                    energy_max_rel_error: or_nan(energy.max_rel_error),
                    energy_final_rel_error: or_nan(energy.final_rel_error),
                    energy_rel_drift: or_nan(energy.rel_drift_per_unit_time),
                    status: RunStatus::of(&record),
                    error: record.error,
                }
            }
            Err(message) => Self {
                member,
                value,
                t_final: f64::NAN,
                steps: 0,
                steps_requested,
                energy_max_rel_error: f64::NAN,
                energy_final_rel_error: f64::NAN,
                energy_rel_drift: f64::NAN,
                error: Some(message),
                status: RunStatus::Failed,
            },
        }
    }

    /// The row of a member that was not run because the sweep was stopped.
    pub fn not_run(member: usize, value: f64, steps_requested: usize, message: &str) -> Self {
        Self {
            status: RunStatus::Interrupted,
            ..Self::new(member, value, steps_requested, Err(message.to_owned()))
        }
    }
}

/// The table for stdout: a header and one aligned line per row (failed rows end with their
/// message).
pub fn render(label: &str, rows: &[SweepRow]) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:>6}  {:>12}  {:>12}  {:>9}  {:>12}  {:>12}  status",
        "member", label, "t_final", "steps", "max|dE/E|", "drift/t"
    );
    for r in rows {
        let _ = write!(
            out,
            "{:>6}  {:>12.6e}  {:>12.6e}  {:>9}  {:>12.3e}  {:>12.3e}  {}",
            r.member,
            r.value,
            r.t_final,
            r.steps,
            r.energy_max_rel_error,
            r.energy_rel_drift,
            r.status.name()
        );
        match &r.error {
            Some(e) => {
                let _ = writeln!(out, ": {}", e.lines().next().unwrap_or_default());
            }
            None => out.push('\n'),
        }
    }
    out
}

/// The CSV text of the table.
pub fn csv(label: &str, rows: &[SweepRow]) -> String {
    let mut out = format!(
        "member,{},t_final,steps,steps_requested,energy_max_rel_error,energy_final_rel_error,\
         energy_rel_drift,status,error\n",
        quote(label)
    );
    for r in rows {
        let error = r.error.as_deref().map(quote).unwrap_or_default();
        let _ = writeln!(
            out,
            "{},{:?},{:?},{},{},{:?},{:?},{:?},{},{}",
            r.member,
            r.value,
            r.t_final,
            r.steps,
            r.steps_requested,
            r.energy_max_rel_error,
            r.energy_final_rel_error,
            r.energy_rel_drift,
            r.status.name(),
            error
        );
    }
    out
}

/// A CSV field in quotes when it needs them (comma, quote or line break inside).
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

/// Writes the CSV and the summary of `rows` (a shard's or the whole sweep's) into `dir`;
/// returns the file names.
///
/// # Errors
/// The file that could not be written, with the reason.
pub fn write(
    dir: &Path,
    shard: Shard,
    label: &str,
    rows: &[SweepRow],
    total: usize,
) -> Result<Vec<String>, String> {
    let suffix = shard.suffix();
    let csv_name = format!("sweep{suffix}.csv");
    let json_name = format!("summary{suffix}.json");
    let save = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
    };
    save(&csv_name, csv(label, rows))?;
    let text = serde_json::to_string_pretty(&summary(shard, label, rows, total))
        .map_err(|e| e.to_string())?;
    save(&json_name, text + "\n")?;
    Ok(vec![csv_name, json_name])
}

/// `summary.json` of a sweep: counts, the worst energy error, the CSV's name.
fn summary(shard: Shard, label: &str, rows: &[SweepRow], total: usize) -> serde_json::Value {
    let failed = rows
        .iter()
        .filter(|r| r.status == RunStatus::Failed)
        .count();
    let interrupted = rows.iter().any(|r| r.status == RunStatus::Interrupted);
    let worst = rows
        .iter()
        .map(|r| r.energy_max_rel_error)
        .filter(|x| x.is_finite())
        .fold(None, |m: Option<f64>, x| Some(m.map_or(x, |m| m.max(x))));
    let steps = rows.first().map_or(0, |r| r.steps_requested);
    json!({
        "kind": "sweep",
        "status": match (failed, interrupted) {
            (0, false) => "completed",
            (0, true) => "interrupted",
            _ => "failed",
        },
        "swept": label,
        "members": total,
        "shard": { "index": shard.index, "count": shard.count },
        "members_run": rows.len(),
        "failed": failed,
        "steps": steps,
        "energy": { "max_rel_error": worst },
        "table": format!("sweep{}.csv", shard.suffix()),
    })
}
