//! The summary table of a sweep: one row per member — its global index, the swept values, the
//! final time, the steps taken, what the run preserved (energy error and drift, or the energy
//! balance of a forced or time-dependent system), each momentum map's initial value and
//! drift, the final state, the status and the error message.
//!
//! The columns are fixed by the base problem ([`SweepColumns`]): `member,<swept>…,t_final,`
//! `steps,steps_requested,` then either `energy_max_rel_error,energy_final_rel_error,`
//! `energy_rel_drift` (energy conserved), `balance_total_work,balance_max_defect,`
//! `balance_total_defect` (forces act or `L` depends on `t`: an energy error would mislead), or
//! nothing (a file's own `L_d`: no continuous `L`, no energy), then `J_<name>,J_<name>_drift` per symmetry, `q_<name>…`, `p_<name>…` (the final state),
//! and `status,error` (CSV) or a numeric `status` (`.npy`, [`RunStatus::code`]).

use std::fmt::Write as _;

use super::balance::BalanceSummary;
use super::diagnostics::MapStats;
use super::solve::RunRecord;
use super::summary::RunStatus;
use crate::model::MomentumMap as _;
use crate::problem::{RunSpec, SweepSpec};

/// The columns of a sweep's table, fixed by the base problem.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepColumns {
    /// The swept values' names (`l`, `q[0]`), one per axis.
    pub swept: Vec<String>,
    /// Coordinate names.
    pub coordinates: Vec<String>,
    /// Symmetry names.
    pub symmetries: Vec<String>,
    /// What the rows say was preserved: the energy, its balance, or nothing.
    pub preserved: Preserved,
}

/// What a sweep's rows report besides the momentum maps and the final state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preserved {
    /// Energy is conserved: its error (the energy-error columns).
    Energy,
    /// Forces act or `L` depends on `t`: the discrete energy balance (the balance columns).
    Balance,
    /// A file's own `L_d`: there is no energy (no such columns).
    Nothing,
}

impl Preserved {
    /// What `base`'s members preserve.
    pub fn of(base: &RunSpec) -> Self {
        if !base.system.has_energy() {
            Self::Nothing
        } else if base.system.energy_not_conserved().is_none() {
            Self::Energy
        } else {
            Self::Balance
        }
    }

    /// The columns of the table that say it.
    fn columns(self) -> &'static [&'static str] {
        match self {
            Self::Energy => &ENERGY_COLUMNS,
            Self::Balance => &BALANCE_COLUMNS,
            Self::Nothing => &[],
        }
    }
}

impl SweepColumns {
    /// The columns of `base`'s sweep.
    pub fn of(base: &RunSpec, sweep: &SweepSpec) -> Self {
        Self {
            swept: sweep.labels(),
            coordinates: base.system.coordinates.clone(),
            symmetries: base
                .system
                .symmetries
                .iter()
                .map(|s| s.name().to_string())
                .collect(),
            preserved: Preserved::of(base),
        }
    }

    /// The names of the numeric columns, in order (everything but `status` and `error`).
    pub fn numeric_names(&self) -> Vec<String> {
        let mut names = vec!["member".to_owned()];
        names.extend(self.swept.iter().cloned());
        names.extend(["t_final", "steps", "steps_requested"].map(str::to_owned));
        names.extend(self.preserved.columns().iter().map(|c| (*c).to_owned()));
        for s in &self.symmetries {
            names.push(format!("J_{s}"));
            names.push(format!("J_{s}_drift"));
        }
        names.extend(self.coordinates.iter().map(|c| format!("q_{c}")));
        names.extend(self.coordinates.iter().map(|c| format!("p_{c}")));
        names
    }
}

/// What a conservative member's row says it preserved.
const ENERGY_COLUMNS: [&str; 3] = [
    "energy_max_rel_error",
    "energy_final_rel_error",
    "energy_rel_drift",
];
/// What a forced or time-dependent member's row says instead.
const BALANCE_COLUMNS: [&str; 3] = [
    "balance_total_work",
    "balance_max_defect",
    "balance_total_defect",
];

/// One member's line of the table.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    /// Global member index (its position in the sweep).
    pub member: usize,
    /// The swept values, one per axis.
    pub values: Vec<f64>,
    /// Time of the last good state (NaN if the member could not start).
    pub t_final: f64,
    /// Steps completed.
    pub steps: usize,
    /// Steps requested.
    pub steps_requested: usize,
    /// `max |E − E₀| / |E₀|` over the sampled rows (NaN if none, or energy not conserved).
    pub energy_max_rel_error: f64,
    /// `(E_N − E₀)/|E₀|` at the last sampled row (NaN likewise).
    pub energy_final_rel_error: f64,
    /// Least-squares slope of the relative energy error per unit time (NaN likewise).
    pub energy_rel_drift: f64,
    /// The discrete energy balance of a forced member (`None`: not computed).
    pub balance: Option<BalanceSummary>,
    /// Each momentum map's initial value and drift, in the file's order.
    pub maps: Vec<MapStats>,
    /// Final positions (empty if the member could not start).
    pub q: Vec<f64>,
    /// Final momenta (empty likewise).
    pub p: Vec<f64>,
    /// Why the member did not complete (`None`: completed, or interrupted while running).
    pub error: Option<String>,
    /// How the member ended.
    pub status: RunStatus,
}

impl SweepRow {
    /// The row of member `member` with swept `values` from its run of `steps_requested` steps
    /// (or the reason it could not run); energy errors are NaN when `energy_conserved` is
    /// false.
    pub fn new(
        member: usize,
        values: Vec<f64>,
        steps_requested: usize,
        energy_conserved: bool,
        result: Result<RunRecord, String>,
    ) -> Self {
        match result {
            Ok(record) => {
                let energy = record.diagnostics.energy.report();
                let seen = energy.samples > 0 && energy_conserved;
                let or_nan = |x: f64| if seen { x } else { f64::NAN };
                Self {
                    member,
                    values,
                    t_final: record.final_state.t,
                    steps: record.steps,
                    steps_requested,
                    energy_max_rel_error: or_nan(energy.max_rel_error),
                    energy_final_rel_error: or_nan(energy.final_rel_error),
                    energy_rel_drift: or_nan(energy.rel_drift_per_unit_time),
                    balance: record.balance,
                    status: RunStatus::of(&record),
                    maps: record.diagnostics.maps,
                    q: record.final_state.q,
                    p: record.final_state.p,
                    error: record.error,
                }
            }
            Err(message) => Self {
                member,
                values,
                t_final: f64::NAN,
                steps: 0,
                steps_requested,
                energy_max_rel_error: f64::NAN,
                energy_final_rel_error: f64::NAN,
                energy_rel_drift: f64::NAN,
                balance: None,
                maps: Vec::new(),
                q: Vec::new(),
                p: Vec::new(),
                error: Some(message),
                status: RunStatus::Failed,
            },
        }
    }

    /// The row of a member that was not run because the sweep was stopped.
    pub fn not_run(member: usize, values: Vec<f64>, steps_requested: usize, message: &str) -> Self {
        Self {
            status: RunStatus::Interrupted,
            ..Self::new(
                member,
                values,
                steps_requested,
                true,
                Err(message.to_owned()),
            )
        }
    }

    /// The numeric columns of [`SweepColumns::numeric_names`], NaN where a value is missing.
    pub fn numeric(&self, columns: &SweepColumns) -> Vec<f64> {
        let mut row = vec![self.member as f64];
        row.extend(&self.values);
        row.extend([self.t_final, self.steps as f64, self.steps_requested as f64]);
        match columns.preserved {
            Preserved::Energy => row.extend([
                self.energy_max_rel_error,
                self.energy_final_rel_error,
                self.energy_rel_drift,
            ]),
            Preserved::Balance => {
                let b = self.balance.as_ref();
                let or_nan = |f: fn(&BalanceSummary) -> f64| b.map_or(f64::NAN, f);
                row.extend([
                    or_nan(|b| b.total_work),
                    or_nan(|b| b.max_defect),
                    or_nan(|b| b.total_defect),
                ]);
            }
            Preserved::Nothing => {}
        }
        for i in 0..columns.symmetries.len() {
            match self.maps.get(i).filter(|m| m.samples > 0) {
                Some(m) => row.extend([m.initial, m.max_abs_drift]),
                None => row.extend([f64::NAN, f64::NAN]),
            }
        }
        let n = columns.coordinates.len();
        for v in [&self.q, &self.p] {
            match v.len() == n {
                true => row.extend(v.iter()),
                false => row.extend(std::iter::repeat_n(f64::NAN, n)),
            }
        }
        row
    }

    /// What the row says was preserved, for the console: the worst energy error and the
    /// drift, or the worst balance defect and the work (`None`: no energy).
    pub fn preserved(&self, preserved: Preserved) -> Option<(f64, f64)> {
        match (preserved, &self.balance) {
            (Preserved::Energy, _) => Some((self.energy_max_rel_error, self.energy_rel_drift)),
            (Preserved::Balance, Some(b)) => Some((b.max_defect, b.total_work)),
            (Preserved::Balance, None) => Some((f64::NAN, f64::NAN)),
            (Preserved::Nothing, _) => None,
        }
    }
}

/// The table for stdout: a header and one aligned line per row (failed rows end with their
/// message).
pub fn render(columns: &SweepColumns, rows: &[SweepRow]) -> String {
    let mut out = String::new();
    let _ = write!(out, "{:>6}", "member");
    for label in &columns.swept {
        let _ = write!(out, "  {label:>12}");
    }
    let _ = write!(out, "  {:>12}  {:>9}", "t_final", "steps");
    let _ = match columns.preserved {
        Preserved::Energy => write!(out, "  {:>12}  {:>12}", "max|dE/E|", "drift/t"),
        Preserved::Balance => write!(out, "  {:>12}  {:>12}", "max defect", "work"),
        Preserved::Nothing => Ok(()),
    };
    let _ = writeln!(out, "  status");
    for r in rows {
        let _ = write!(out, "{:>6}", r.member);
        for v in &r.values {
            let _ = write!(out, "  {v:>12.6e}");
        }
        let _ = write!(out, "  {:>12.6e}  {:>9}", r.t_final, r.steps);
        if let Some((first, second)) = r.preserved(columns.preserved) {
            let _ = write!(out, "  {first:>12.3e}  {second:>12.3e}");
        }
        let _ = write!(out, "  {}", r.status.name());
        match &r.error {
            Some(e) => {
                let _ = writeln!(out, ": {}", e.lines().next().unwrap_or_default());
            }
            None => out.push('\n'),
        }
    }
    out
}

/// The CSV header line (with its line break).
pub fn csv_header(columns: &SweepColumns) -> String {
    let names: Vec<String> = columns.numeric_names().iter().map(|n| quote(n)).collect();
    format!("{},status,error\n", names.join(","))
}

/// One CSV line (with its line break): the numbers in Rust's shortest round-trip form, the
/// status, the error quoted (empty when the member completed).
pub fn csv_line(columns: &SweepColumns, row: &SweepRow) -> String {
    let mut out = String::new();
    for (i, x) in row.numeric(columns).iter().enumerate() {
        let _ = match i {
            0 => write!(out, "{}", row.member),
            _ if is_count(columns, i) => write!(out, ",{x}"),
            _ => write!(out, ",{x:?}"),
        };
    }
    let error = row.error.as_deref().map(quote).unwrap_or_default();
    let _ = writeln!(out, ",{},{error}", row.status.name());
    out
}

/// Whether numeric column `i` is a count (`steps`, `steps_requested`), written as an integer.
fn is_count(columns: &SweepColumns, i: usize) -> bool {
    let steps = 1 + columns.swept.len() + 1;
    i == steps || i == steps + 1
}

/// A CSV field in quotes when it needs them (comma, quote or line break inside).
fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn columns(preserved: Preserved) -> SweepColumns {
        SweepColumns {
            swept: vec!["l".into(), "q[0]".into()],
            coordinates: vec!["x".into()],
            symmetries: vec!["rot".into()],
            preserved,
        }
    }

    #[test]
    fn a_failed_row_has_every_column_and_its_message() {
        let cols = columns(Preserved::Energy);
        let row = SweepRow::new(3, vec![0.5, 0.1], 10, true, Err("bad, \"x\"".into()));
        let numeric = row.numeric(&cols);
        assert_eq!(numeric.len(), cols.numeric_names().len());
        assert_eq!(numeric[..3], [3.0, 0.5, 0.1]);
        assert!(numeric[6..].iter().all(|x| x.is_nan()));
        let line = csv_line(&cols, &row);
        assert!(line.starts_with("3,0.5,0.1,NaN,0,10,NaN"), "{line}");
        assert!(line.ends_with(",failed,\"bad, \"\"x\"\"\"\n"), "{line}");
        assert_eq!(
            csv_header(&cols),
            "member,l,q[0],t_final,steps,steps_requested,energy_max_rel_error,\
             energy_final_rel_error,energy_rel_drift,J_rot,J_rot_drift,q_x,p_x,status,error\n"
        );
    }

    #[test]
    fn a_forced_sweep_reports_the_balance_not_an_energy_error() {
        let names = columns(Preserved::Balance).numeric_names();
        assert!(names.contains(&"balance_max_defect".to_owned()));
        assert!(!names.iter().any(|n| n.starts_with("energy")));
    }

    #[test]
    fn a_sweep_of_a_discrete_lagrangian_has_neither_energy_nor_balance_columns() {
        let cols = columns(Preserved::Nothing);
        let names = cols.numeric_names();
        assert!(
            !names
                .iter()
                .any(|n| n.starts_with("energy") || n.starts_with("balance")),
            "{names:?}"
        );
        let row = SweepRow::new(0, vec![0.5, 0.1], 10, false, Err("x".into()));
        assert_eq!(row.numeric(&cols).len(), names.len());
        assert!(!render(&cols, &[row]).contains("max"));
    }
}
