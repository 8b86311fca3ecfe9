//! All plots of a run, from a table following the `trajectory.csv` naming convention.

use std::path::Path;

use super::columns::{Columns, is_constant};
use super::configuration::{Orbit, plot_configuration};
use super::constraint::{plot_constraint_residual, plot_constraint_residuals};
use super::energy::plot_energy_error;
use super::momentum::plot_momentum_drift;
use super::multipliers::plot_multipliers;
use super::options::{PhaseCurve, PlotOptions, PlotReport, Series};
use super::phase::plot_phase_portrait;
use super::plane::plane_of;
use super::time_series::plot_time_series;
use crate::error::{Error, Result};
use crate::table::Table;

/// File name of the phase portrait written by [`plot_run`].
pub const PHASE_PORTRAIT_PNG: &str = "phase_portrait.png";
/// File name of the time-series plot (`q(t)`, `p(t)`) written by [`plot_run`].
pub const TIME_SERIES_PNG: &str = "time_series.png";
/// File name of the configuration-space plot written by [`plot_run`].
pub const CONFIGURATION_PNG: &str = "configuration.png";
/// File name of the energy-error plot written by [`plot_run`].
pub const ENERGY_ERROR_PNG: &str = "energy_error.png";
/// File name of the momentum-drift plot written by [`plot_run`].
pub const MOMENTUM_DRIFT_PNG: &str = "momentum_drift.png";
/// File name of the constraint-residual plot written by [`plot_run`].
pub const CONSTRAINT_RESIDUAL_PNG: &str = "constraint_residual.png";
/// File name of the multiplier plot written by [`plot_run`].
pub const MULTIPLIERS_PNG: &str = "multipliers.png";

/// Draws every plot the table's columns allow into `dir`, by the `trajectory.csv`
/// convention: `t`; `q_<name>` paired with `p_<name>` (phase portrait, time series, and the
/// configuration space when the names say where the points are, see `plane_of`); `energy`
/// (its relative error, when `opts.energy_conserved`);
/// `J_<symmetry>` (momentum drift); `constraint_residual` (with `constraint_velocity_residual`,
/// the hidden constraint's `|Dφ(q)·v|`, as a second curve when present); `lambda_<i>`
/// (multipliers). A plot
/// whose columns are absent is skipped; the reports say which files were written (for
/// `marsden plot DIR`). Coordinates named in `opts.angles` are drawn wrapped to (−π, π].
///
/// # Errors
/// [`Error::PlotInput`] if there is no `t` column; otherwise the first plot error.
pub fn plot_run(
    table: &Table,
    dir: impl AsRef<Path>,
    opts: &PlotOptions,
) -> Result<Vec<PlotReport>> {
    let dir = dir.as_ref();
    let t = table.values("t").ok_or_else(|| Error::PlotInput {
        path: dir.to_path_buf(),
        message: "the table has no `t` column".to_owned(),
    })?;
    let columns = Columns::new(table, opts);
    let mut reports = Vec::new();
    let coordinates = columns.coordinates();
    if !coordinates.is_empty() {
        reports.push(phase_portrait(dir, &columns, &coordinates, opts)?);
        reports.push(time_series(dir, t, &columns, &coordinates, opts)?);
    }
    if let Some((plane, orbits)) = plane_of(&columns, &coordinates, opts) {
        let orbits: Vec<Orbit<'_>> = orbits
            .iter()
            .map(|o| Orbit {
                name: &o.legend,
                x: columns.get(&o.x),
                y: columns.get(&o.y),
            })
            .collect();
        reports.push(plot_configuration(
            dir.join(CONFIGURATION_PNG),
            &plane,
            &orbits,
            opts,
        )?);
    }
    if let Some(energy) = table.values("energy").filter(|_| opts.energy_conserved) {
        reports.push(plot_energy_error(
            dir.join(ENERGY_ERROR_PNG),
            t,
            energy,
            opts,
        )?);
    }
    let maps = series(table, "J_");
    if !maps.is_empty() {
        reports.push(plot_momentum_drift(
            dir.join(MOMENTUM_DRIFT_PNG),
            t,
            &maps,
            opts,
        )?);
    }
    if let Some(r) = table.values("constraint_residual") {
        let path = dir.join(CONSTRAINT_RESIDUAL_PNG);
        let report = match table.values("constraint_velocity_residual") {
            Some(v) => plot_constraint_residuals(path, t, r, v, opts)?,
            None => plot_constraint_residual(path, t, r, opts)?,
        };
        reports.push(report);
    }
    let multipliers = series(table, "lambda_");
    if !multipliers.is_empty() {
        reports.push(plot_multipliers(
            dir.join(MULTIPLIERS_PNG),
            t,
            &multipliers,
            opts,
        )?);
    }
    Ok(reports)
}

/// The columns whose names start with `prefix`, as named series.
fn series<'a>(table: &'a Table, prefix: &'a str) -> Vec<Series<'a>> {
    table
        .columns_with_prefix(prefix)
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect()
}

/// Phase portrait of the coordinates that move (constant ones are skipped, and said).
fn phase_portrait(
    dir: &Path,
    columns: &Columns<'_>,
    coordinates: &[&str],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let moving = |name: &&str| {
        let (q, p) = (
            columns.get(&format!("q_{name}")),
            columns.get(&format!("p_{name}")),
        );
        !(is_constant(q) && is_constant(p))
    };
    let (shown, still): (Vec<&str>, Vec<&str>) =
        coordinates.iter().copied().partition(|name| moving(name));
    let shown = if shown.is_empty() {
        coordinates.to_vec()
    } else {
        shown
    };
    let curves: Vec<PhaseCurve<'_>> = shown
        .iter()
        .map(|name| PhaseCurve {
            name,
            q: columns.get(&format!("q_{name}")),
            p: columns.get(&format!("p_{name}")),
        })
        .collect();
    let mut report = plot_phase_portrait(dir.join(PHASE_PORTRAIT_PNG), &curves, opts)?;
    if !still.is_empty() && shown.len() < coordinates.len() {
        report.notes.push(format!(
            "not shown, constant throughout: {}",
            still.join(", ")
        ));
    }
    Ok(report)
}

fn time_series(
    dir: &Path,
    t: &[f64],
    columns: &Columns<'_>,
    coordinates: &[&str],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let names = |prefix: &str| -> Vec<String> {
        coordinates.iter().map(|n| format!("{prefix}{n}")).collect()
    };
    let (q_names, p_names) = (names("q_"), names("p_"));
    let (q, p) = (named(&q_names, columns), named(&p_names, columns));
    plot_time_series(dir.join(TIME_SERIES_PNG), t, &q, &p, opts)
}

/// The columns called `names`, as series.
fn named<'a>(names: &'a [String], columns: &'a Columns<'_>) -> Vec<Series<'a>> {
    names
        .iter()
        .map(|n| Series {
            name: n,
            values: columns.get(n),
        })
        .collect()
}
