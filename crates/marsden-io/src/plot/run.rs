//! All plots of a run, from a table following the `trajectory.csv` naming convention.

use std::path::Path;

use super::constraint::plot_constraint_residual;
use super::energy::plot_energy_error;
use super::momentum::plot_momentum_drift;
use super::multipliers::plot_multipliers;
use super::options::{PhaseCurve, PlotOptions, PlotReport, Series};
use super::phase::plot_phase_portrait;
use crate::error::{Error, Result};
use crate::table::Table;

/// File name of the phase portrait written by [`plot_run`].
pub const PHASE_PORTRAIT_PNG: &str = "phase_portrait.png";
/// File name of the energy-error plot written by [`plot_run`].
pub const ENERGY_ERROR_PNG: &str = "energy_error.png";
/// File name of the momentum-drift plot written by [`plot_run`].
pub const MOMENTUM_DRIFT_PNG: &str = "momentum_drift.png";
/// File name of the constraint-residual plot written by [`plot_run`].
pub const CONSTRAINT_RESIDUAL_PNG: &str = "constraint_residual.png";
/// File name of the multiplier plot written by [`plot_run`].
pub const MULTIPLIERS_PNG: &str = "multipliers.png";

/// Draws every plot the table's columns allow into `dir`, by the `trajectory.csv`
/// convention: `t`; `q_<name>` paired with `p_<name>` (phase portrait); `energy`;
/// `J_<symmetry>` (momentum drift); `constraint_residual`; `lambda_<i>` (multipliers). A plot whose columns are absent is
/// skipped; the reports say which files were written (for `marsden plot DIR`).
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
    let mut reports = Vec::new();

    let curves: Vec<PhaseCurve<'_>> = table
        .columns_with_prefix("q_")
        .filter_map(|q| {
            let name = &q.name[2..];
            let p = table.values(&format!("p_{name}"))?;
            Some(PhaseCurve {
                name,
                q: &q.values,
                p,
            })
        })
        .collect();
    if !curves.is_empty() {
        reports.push(plot_phase_portrait(
            dir.join(PHASE_PORTRAIT_PNG),
            &curves,
            opts,
        )?);
    }
    if let Some(energy) = table.values("energy") {
        reports.push(plot_energy_error(
            dir.join(ENERGY_ERROR_PNG),
            t,
            energy,
            opts,
        )?);
    }
    let maps: Vec<Series<'_>> = table
        .columns_with_prefix("J_")
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect();
    if !maps.is_empty() {
        reports.push(plot_momentum_drift(
            dir.join(MOMENTUM_DRIFT_PNG),
            t,
            &maps,
            opts,
        )?);
    }
    if let Some(r) = table.values("constraint_residual") {
        reports.push(plot_constraint_residual(
            dir.join(CONSTRAINT_RESIDUAL_PNG),
            t,
            r,
            opts,
        )?);
    }
    let multipliers: Vec<Series<'_>> = table
        .columns_with_prefix("lambda_")
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect();
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
