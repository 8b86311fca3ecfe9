//! The files of a run: the trajectory's columns (a contract: extend, don't rename) and the writer
//! for the chosen format.
//!
//! `t, q_<name>…, p_<name>…, energy`, then `J_<symmetry>` per symmetry, then
//! `constraint_residual` and the multipliers `lambda_<i>` (the constraint forces `−Dφ(q)ᵀλ`,
//! implied by each stored state, `marsden::holonomic::multipliers_at`) when there are
//! constraints, then the observables, and last, with constraints, the hidden constraint's
//! residual `constraint_velocity_residual` (`max_i |(Dφ(q)·v)_i|`). The same [`Layout`] names
//! the CSV header and the `.npy` files (`t.npy`, `q.npy`, `p.npy`, `energy.npy`, `J.npy`,
//! `constraint_residual.npy`, `lambda.npy`, `observables.npy`,
//! `constraint_velocity_residual.npy`).

use std::path::Path;

use marsden_io::{CsvWriter, Group, Layout, NpyDirWriter, RowSink};

use crate::problem::{Format, RunSpec, SystemSpec};

/// The trajectory file of `format = "csv"`.
pub const TRAJECTORY_CSV: &str = "trajectory.csv";
/// The summary of every run.
pub const SUMMARY_JSON: &str = "summary.json";
/// Name of the constraint-residual column.
pub const CONSTRAINT_RESIDUAL: &str = "constraint_residual";
/// Name of the hidden constraint's residual column `|Dφ(q)·v|`, the last column of a
/// constrained run (after the observables).
pub const CONSTRAINT_VELOCITY_RESIDUAL: &str = "constraint_velocity_residual";
/// Name of the multipliers' group (`lambda_0`, `lambda_1`, …; `lambda.npy`).
pub const LAMBDA: &str = "lambda";
/// A rigid body's attitude group (`R.npy`).
pub const ATTITUDE: &str = "R";
/// Its columns: the entries of `R` (body → space), row-major.
pub const ATTITUDE_COLUMNS: [&str; 9] = [
    "R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33",
];
/// A rigid body's body-momentum group (`Pi.npy`).
pub const BODY_MOMENTUM: &str = "Pi";
/// Its columns.
pub const BODY_MOMENTUM_COLUMNS: [&str; 3] = ["Pi1", "Pi2", "Pi3"];
/// Name of the observables' group (`observables.npy`); the columns are the observables' names.
pub const OBSERVABLES: &str = "observables";

/// The column layout of a system's trajectory (without observables: [`layout_of`]).
///
/// # Errors
/// If two columns would have the same name.
pub fn layout(system: &SystemSpec) -> marsden_io::Result<Layout> {
    let mut groups = match system.multibody() {
        Some(bodies) => multibody_groups(bodies),
        None => system_groups(system),
    };
    groups.extend(velocity_residual(system));
    Layout::new(groups)
}

/// The group of the hidden constraint's residual, last, when `system` has constraints (or
/// joints).
fn velocity_residual(system: &SystemSpec) -> Option<Group> {
    let constrained = !system.constraint.components().is_empty() || system.multibody().is_some();
    constrained.then(|| Group::scalar(CONSTRAINT_VELOCITY_RESIDUAL))
}

/// The groups of a system's trajectory before the observables.
fn system_groups(system: &SystemSpec) -> Vec<Group> {
    let q = system.coordinates.iter().map(|c| format!("q_{c}"));
    let p = system.coordinates.iter().map(|c| format!("p_{c}"));
    let j = system
        .momentum_names()
        .into_iter()
        .map(|s| format!("J_{s}"));
    let mut groups = vec![Group::scalar("t")];
    // A rigid body: its attitude and body momentum first, then its centre of mass's q and p.
    if system.rigid().is_some() {
        groups.push(Group::vector(ATTITUDE, ATTITUDE_COLUMNS));
        groups.push(Group::vector(BODY_MOMENTUM, BODY_MOMENTUM_COLUMNS));
    }
    groups.push(Group::vector("q", q));
    groups.push(Group::vector("p", p));
    // A file's own `L_d` has no energy column: there is no continuous L to define one.
    if system.has_energy() {
        groups.push(Group::scalar("energy"));
    }
    groups.push(Group::vector("J", j));
    let d = system.constraint.components().len();
    if d > 0 {
        groups.push(Group::scalar(CONSTRAINT_RESIDUAL));
        groups.push(Group::vector(
            LAMBDA,
            (0..d).map(|i| format!("{LAMBDA}_{i}")),
        ));
    }
    groups
}

/// The suffixes of a body's columns in a multibody trajectory, per group.
pub const BODY_CENTRE: [&str; 3] = ["x", "y", "z"];
/// The suffixes of a body's momentum columns.
pub const BODY_LINEAR_MOMENTUM: [&str; 3] = ["p_x", "p_y", "p_z"];

/// The groups of jointed bodies before the observables: `t`, then per body (in the file's
/// order) its attitude `<b>_R11 … <b>_R33` (group `R`), body momentum `<b>_Pi1 …` (`Pi`), centre
/// `<b>_x …` (`q`) and momentum `<b>_p_x …` (`p`); `energy`, the joints' residual
/// `constraint_residual` and the multipliers `lambda_<joint>_<i>` (the velocity residual of
/// the joints follows, last, as for every constrained system).
fn multibody_groups(bodies: &crate::problem::multibody::MultibodySpec) -> Vec<Group> {
    vec![
        Group::scalar("t"),
        Group::vector(ATTITUDE, bodies.attitude_columns(&ATTITUDE_COLUMNS)),
        Group::vector(
            BODY_MOMENTUM,
            bodies.attitude_columns(&BODY_MOMENTUM_COLUMNS),
        ),
        Group::vector("q", bodies.body_columns(&BODY_CENTRE)),
        Group::vector("p", bodies.body_columns(&BODY_LINEAR_MOMENTUM)),
        Group::scalar("energy"),
        Group::scalar(CONSTRAINT_RESIDUAL),
        Group::vector(LAMBDA, bodies.lambda_columns()),
    ]
}

/// The layout of a multibody run's columns (as `summary.json` lists them), its bodies and
/// particles named by its `coordinates` (`<name>_x, <name>_y, <name>_z` each): the bodies are
/// those with an `<name>_R11` column.
///
/// # Errors
/// If the names do not form a valid layout.
pub fn multibody_layout_from_columns(
    names: &[String],
    coordinates: &[String],
) -> marsden_io::Result<Layout> {
    let members: Vec<&str> = (coordinates.iter())
        .filter_map(|c| c.strip_suffix("_x"))
        .collect();
    let bodies: Vec<&str> = (members.iter().copied())
        .filter(|b| names.iter().any(|n| *n == format!("{b}_R11")))
        .collect();
    let columns = |of: &[&str], suffixes: &[&str]| -> Vec<String> {
        (of.iter())
            .flat_map(|b| suffixes.iter().map(move |s| format!("{b}_{s}")))
            .collect()
    };
    let lambda: Vec<String> = (names.iter())
        .filter(|n| n.starts_with("lambda_"))
        .cloned()
        .collect();
    let groups = vec![
        Group::scalar("t"),
        Group::vector(ATTITUDE, columns(&bodies, &ATTITUDE_COLUMNS)),
        Group::vector(BODY_MOMENTUM, columns(&bodies, &BODY_MOMENTUM_COLUMNS)),
        Group::vector("q", columns(&members, &BODY_CENTRE)),
        Group::vector("p", columns(&members, &BODY_LINEAR_MOMENTUM)),
        Group::scalar("energy"),
        Group::scalar(CONSTRAINT_RESIDUAL),
        Group::vector(LAMBDA, lambda),
        Group::scalar(CONSTRAINT_VELOCITY_RESIDUAL),
    ];
    Layout::new(groups)
}

/// The column layout of the trajectory of `spec`: its system's ([`layout`]), then its
/// observables (the group [`OBSERVABLES`], one column per name).
///
/// # Errors
/// As [`layout`].
pub fn layout_of(spec: &RunSpec) -> marsden_io::Result<Layout> {
    let observables = &spec.events.observables.names;
    let mut groups = match spec.system.multibody() {
        Some(bodies) => multibody_groups(bodies),
        None => system_groups(&spec.system),
    };
    if !observables.is_empty() {
        groups.push(Group::vector(OBSERVABLES, observables.iter().cloned()));
    }
    groups.extend(velocity_residual(&spec.system));
    Layout::new(groups)
}

/// The layout of a finished run from its column names (as `summary.json` lists them):
/// grouped by the prefixes `q_`, `p_`, `J_`; `t`, `energy`, `constraint_residual` and
/// `constraint_velocity_residual` alone (a multibody run's: [`multibody_layout_from_columns`]).
///
/// # Errors
/// If the names do not form a valid layout.
pub fn layout_from_columns(names: &[String]) -> marsden_io::Result<Layout> {
    let with = |prefix: &str| -> Vec<String> {
        names
            .iter()
            .filter(|n| n.starts_with(prefix))
            .cloned()
            .collect()
    };
    let mut groups = vec![
        Group::vector("q", with("q_")),
        Group::vector("p", with("p_")),
        Group::vector("J", with("J_")),
    ];
    let lambda = with("lambda_");
    if !lambda.is_empty() {
        groups.push(Group::vector(LAMBDA, lambda));
    }
    if ATTITUDE_COLUMNS
        .iter()
        .all(|c| names.iter().any(|n| n == c))
    {
        groups.push(Group::vector(ATTITUDE, ATTITUDE_COLUMNS));
        groups.push(Group::vector(BODY_MOMENTUM, BODY_MOMENTUM_COLUMNS));
    }
    const SCALARS: [&str; 4] = [
        "t",
        "energy",
        CONSTRAINT_RESIDUAL,
        CONSTRAINT_VELOCITY_RESIDUAL,
    ];
    for scalar in SCALARS {
        if names.iter().any(|n| n == scalar) {
            groups.push(Group::scalar(scalar));
        }
    }
    // Every other name is an observable's (their names avoid the prefixes and the scalars).
    let grouped = |n: &String| {
        SCALARS.contains(&n.as_str())
            || ["q_", "p_", "J_", "lambda_"]
                .iter()
                .any(|p| n.starts_with(p))
    };
    let observables: Vec<String> = names.iter().filter(|n| !grouped(n)).cloned().collect();
    if !observables.is_empty() {
        groups.push(Group::vector(OBSERVABLES, observables));
    }
    Layout::new(groups)
}

/// Files a previous run may have left in an output directory (and nothing else).
const RUN_FILES: [&str; 32] = [
    TRAJECTORY_CSV,
    super::sampled_times::SAMPLES_CSV,
    super::sampled_times::SAMPLES_NPY,
    marsden_engine::checkpoint::CHECKPOINT_FILE,
    marsden_engine::checkpoint::tangent::SENSITIVITY_CHECKPOINT_FILE,
    marsden_engine::events::EVENTS_CSV,
    super::event_outputs::EVENTS_NPY,
    "observables.npy",
    super::event_outputs::SECTION_PNG,
    super::event_outputs::OBSERVABLES_PNG,
    SUMMARY_JSON,
    "t.npy",
    "R.npy",
    "Pi.npy",
    super::rigid_plots::ATTITUDE_PNG,
    super::rigid_plots::BODY_MOMENTUM_PNG,
    super::multibody_plots::BODIES_PNG,
    "q.npy",
    "p.npy",
    "energy.npy",
    "J.npy",
    "constraint_residual.npy",
    "constraint_velocity_residual.npy",
    "lambda.npy",
    marsden_io::plot::PHASE_PORTRAIT_PNG,
    marsden_io::plot::ENERGY_ERROR_PNG,
    marsden_io::plot::MOMENTUM_DRIFT_PNG,
    marsden_io::plot::CONSTRAINT_RESIDUAL_PNG,
    marsden_io::plot::MULTIPLIERS_PNG,
    super::balance::ENERGY_BALANCE_PNG,
    super::sensitivity::SENSITIVITY_NPY,
    super::sensitivity::SENSITIVITY_CSV,
];

/// Removes the files of a previous run from `dir`, so that a directory never mixes two runs
/// (say, a momentum-drift plot of an older problem). Other files are left alone.
///
/// # Errors
/// The first file that exists but cannot be removed.
pub fn clear_previous(dir: &Path) -> std::io::Result<()> {
    for name in RUN_FILES {
        match std::fs::remove_file(dir.join(name)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e),
            _ => {}
        }
    }
    Ok(())
}

pub use marsden_io::write_atomically;

/// The lock file of an output directory.
pub const LOCK: &str = ".marsden.lock";

/// An exclusive lock on an output directory, held while a run writes into it (released when
/// dropped, which removes the lock file, or when the process ends, however it ends).
#[derive(Debug)]
pub struct DirLock {
    _file: std::fs::File,
    path: std::path::PathBuf,
}

impl Drop for DirLock {
    fn drop(&mut self) {
        // Removed while still held, so no other run can have locked this file meanwhile.
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Locks `dir` (which must exist) for one run.
///
/// # Errors
/// A message if another run holds the lock, or the lock file cannot be opened.
pub fn lock(dir: &Path) -> Result<DirLock, String> {
    lock_named(dir, LOCK)
}

/// Locks `dir` under the lock file `name` (a sweep's shard locks its own files only, so the
/// shards of one sweep may write into one directory at once).
///
/// # Errors
/// As [`lock`].
pub fn lock_named(dir: &Path, name: &str) -> Result<DirLock, String> {
    let path = dir.join(name);
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(|e| format!("cannot open the lock file {}: {e}", path.display()))?;
    match file.try_lock() {
        Ok(()) => Ok(DirLock { _file: file, path }),
        Err(std::fs::TryLockError::WouldBlock) => Err(format!(
            "another run is writing into {} (it holds {name})",
            dir.display()
        )),
        Err(std::fs::TryLockError::Error(e)) => Err(format!("cannot lock {}: {e}", path.display())),
    }
}

/// Opens the streaming writer of `format` in `dir` (which must exist).
///
/// # Errors
/// An I/O error naming the file.
pub fn open_sink(
    dir: &Path,
    format: Format,
    layout: &Layout,
) -> marsden_io::Result<Box<dyn RowSink>> {
    Ok(match format {
        Format::Csv => Box::new(CsvWriter::create(
            dir.join(TRAJECTORY_CSV),
            &layout.column_names(),
        )?),
        Format::Npy => Box::new(NpyDirWriter::create(dir, layout)?),
    })
}

/// The trajectory files of a run resumed from a checkpoint, reopened at its `mark` (rows
/// written after it are cut off).
///
/// # Errors
/// A file that does not match the mark, or an I/O error naming it.
pub fn reopen_sink(
    dir: &Path,
    format: Format,
    layout: &Layout,
    mark: &marsden_io::SinkMark,
) -> marsden_io::Result<Box<dyn RowSink>> {
    Ok(match format {
        Format::Csv => Box::new(CsvWriter::reopen(
            dir.join(TRAJECTORY_CSV),
            &layout.column_names(),
            mark,
        )?),
        Format::Npy => Box::new(NpyDirWriter::reopen(dir, layout, mark)?),
    })
}

/// The trajectory files of `format` for `layout`, for the report.
pub fn trajectory_files(format: Format, layout: &Layout) -> Vec<String> {
    match format {
        Format::Csv => vec![TRAJECTORY_CSV.to_owned()],
        Format::Npy => layout
            .groups()
            .iter()
            .map(|g| format!("{}.npy", g.name))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn column_names_regroup() {
        let names: Vec<String> = [
            "t",
            "q_x",
            "q_y",
            "p_x",
            "p_y",
            "energy",
            "J_Lz",
            "constraint_residual",
            "lambda_0",
            "constraint_velocity_residual",
        ]
        .map(String::from)
        .to_vec();
        let layout = layout_from_columns(&names).unwrap();
        let mut got: Vec<&str> = layout.column_names();
        got.sort_unstable();
        let mut want: Vec<&str> = names.iter().map(String::as_str).collect();
        want.sort_unstable();
        assert_eq!(got, want);
    }
}
