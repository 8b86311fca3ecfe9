//! `[system] control_table = "controls.csv"`: the controls of a `marsden run` read from a
//! table (columns `t` and one per declared control, as `marsden optimize` writes
//! `controls.csv`), `u_k` acting on `[t_k, t_{k+1})` ([`crate::model::ControlTable`]). The
//! path is relative to the problem file. Without it the controls of a run are zero.
//!
//! Checked here, each with the reason at the key: the file and its columns, its times against
//! the run's grid (`t_k = t0 + k h`, one row per step), and the rule, whose quadrature nodes
//! must lie inside the step for `u(t)` to tell the step from the time.

use std::ops::Range;
use std::path::PathBuf;

use marsden::discrete::rules::{BaseMethod, Method as CoreMethod};
use marsden::run::TimeGrid;
use toml::Spanned;

use super::check::Checker;
use super::method::Method;
use super::raw::{RawProblem, RawSystem};
use super::spec::{IntegratorSpec, SystemSpec};
use crate::error::Diagnostic;
use crate::model::ControlTable;

/// Relative tolerance of a table's time against the grid's (a round trip through CSV is exact).
const TIME_TOLERANCE: f64 = 1e-9;

/// Reads `[system] control_table` (if given), checks it against the run's grid and rule and
/// lets the forces read it.
///
/// # Errors
/// A diagnostic at `control_table` (or the method) saying what does not fit.
pub fn attach(
    ck: &Checker<'_>,
    raw: &RawProblem,
    system: &mut SystemSpec,
    integrator: &IntegratorSpec,
) -> Result<(), Diagnostic> {
    let Some(raw_system) = raw.system.as_ref().map(Spanned::get_ref) else {
        return Ok(());
    };
    let Some(file) = &raw_system.control_table else {
        return Ok(());
    };
    let at = Some(file.span());
    let names = control_names(ck, raw_system, at.clone())?;
    inside_the_step(ck, raw, &integrator.method)?;
    let path = match ck.source.path().parent() {
        Some(dir) => dir.join(file.get_ref()),
        None => PathBuf::from(file.get_ref()),
    };
    let table = marsden_io::read_csv(&path).map_err(|e| {
        ck.error(at.clone(), format!("cannot read the control table: {e}"))
            .help(
                "`marsden optimize` writes one as controls.csv; the path is relative to this file",
            )
    })?;
    let rows = read_rows(ck, at.clone(), &table, &names)?;
    let times = column(ck, at.clone(), &table, "t")?;
    on_the_grid(ck, at, times, &integrator.grid)?;
    let grid = integrator.grid;
    let controls = ControlTable {
        t0: grid.t0,
        h: grid.h,
        rows,
    };
    system.force = std::mem::take(&mut system.force).with_control_table(controls);
    Ok(())
}

/// Whether the file gives a control table (the controls are then inputs of the forces).
pub fn given(system: &RawSystem) -> bool {
    system.control_table.is_some()
}

fn control_names(
    ck: &Checker<'_>,
    system: &RawSystem,
    at: Option<Range<usize>>,
) -> Result<Vec<String>, Diagnostic> {
    match &system.controls {
        Some(list) if !list.get_ref().is_empty() => {
            Ok(list.get_ref().iter().map(|c| c.get_ref().clone()).collect())
        }
        _ => Err(ck
            .error(
                at,
                "`control_table` gives values of controls, but none are declared",
            )
            .help("declare them, e.g. controls = [\"u\"], and use them in `forces`")),
    }
}

/// The rule's force quadrature nodes must lie inside the step: midpoint, `alpha-<a>` and
/// `symmetrized-<a>` with `0 < a < 1`.
fn inside_the_step(ck: &Checker<'_>, raw: &RawProblem, method: &Method) -> Result<(), Diagnostic> {
    let inside = |a: f64| a > 0.0 && a < 1.0;
    let fits = match method {
        Method::Rule(CoreMethod::Single(base)) => match base {
            BaseMethod::Midpoint => true,
            BaseMethod::Alpha(a) | BaseMethod::Symmetrized(a) => inside(*a),
            _ => false,
        },
        _ => false,
    };
    if fits {
        return Ok(());
    }
    let span = (raw.integrator.as_ref())
        .and_then(|i| i.get_ref().method.as_ref())
        .map(|m| m.span());
    Err(ck
        .error(
            span,
            format!("the method `{method}` cannot read a control table"),
        )
        .note(
            "the controls are constant per step and read by time at the force's quadrature \
             nodes; this rule has a node at a step's end, where two steps meet",
        )
        .help("use `midpoint`, `alpha-<a>` or `symmetrized-<a>` with 0 < a < 1"))
}

fn column<'t>(
    ck: &Checker<'_>,
    at: Option<Range<usize>>,
    table: &'t marsden_io::Table,
    name: &str,
) -> Result<&'t [f64], Diagnostic> {
    table.values(name).ok_or_else(|| {
        let found: Vec<&str> = table.names().collect();
        ck.error(at, format!("the control table has no column `{name}`"))
            .note(format!("its columns: {}", found.join(", ")))
    })
}

/// `u_k` per step, the columns in declared order; every value finite.
fn read_rows(
    ck: &Checker<'_>,
    at: Option<Range<usize>>,
    table: &marsden_io::Table,
    names: &[String],
) -> Result<Vec<Vec<f64>>, Diagnostic> {
    let mut rows = vec![Vec::with_capacity(names.len()); table.n_rows()];
    for name in names {
        let values = column(ck, at.clone(), table, name)?;
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(ck.error(
                at,
                format!("the control table's `{name}` is {} at row {k}", values[k]),
            ));
        }
        for (row, &v) in rows.iter_mut().zip(values) {
            row.push(v);
        }
    }
    Ok(rows)
}

/// One row per step, at `t_k = t0 + k h`.
fn on_the_grid(
    ck: &Checker<'_>,
    at: Option<Range<usize>>,
    times: &[f64],
    grid: &TimeGrid,
) -> Result<(), Diagnostic> {
    let help = format!(
        "the run's grid: t0 = {}, h = {}, {} steps; the table needs t_k = t0 + k h, k = 0 … {}",
        grid.t0,
        grid.h,
        grid.steps,
        grid.steps.saturating_sub(1)
    );
    if times.len() != grid.steps {
        return Err(ck
            .error(
                at,
                format!(
                    "the control table has {} rows, the run has {} steps",
                    times.len(),
                    grid.steps
                ),
            )
            .help(help));
    }
    for (k, &t) in times.iter().enumerate() {
        let want = grid.t0 + k as f64 * grid.h;
        // Written so that a NaN time is refused too.
        let fits = (t - want).abs() <= TIME_TOLERANCE * want.abs().max(grid.h);
        if !fits {
            return Err(ck
                .error(
                    at,
                    format!("the control table's row {k} has t = {t}, the run's t_{k} = {want}"),
                )
                .help(help));
        }
    }
    Ok(())
}
