//! The plots of a run: drawn after `marsden run` from the files just written ([`draw`]), or
//! again later from a run's directory ([`redraw`], `marsden plot`).

use std::path::Path;

use marsden_io::plot::plot_sweep;
use marsden_io::thin::DEFAULT_BUDGET;
use marsden_io::{
    Layout, PlotOptions, PlotReport, Series, Thinned, plot_run, read_csv_numeric, read_csv_thinned,
    read_npy_dir_thinned,
};

use super::output::{self, SUMMARY_JSON, TRAJECTORY_CSV, layout_from_columns};
use crate::error::{Diagnostic, Error};
use crate::problem::{Format, RunSpec};

/// Reads the trajectory of `spec` back as a bounded sketch and draws every plot; returns the
/// PNG file names. Memory does not grow with the number of rows (see [`marsden_io::Thinner`]).
///
/// # Errors
/// The trajectory cannot be read or a plot cannot be written.
pub fn draw(spec: &RunSpec, layout: &Layout) -> marsden_io::Result<Vec<String>> {
    let dir = &spec.output.dir;
    let names: Vec<String> = layout
        .column_names()
        .into_iter()
        .map(str::to_owned)
        .collect();
    let monitored = monitored(&names);
    let sketch = match spec.output.format {
        Format::Csv => {
            read_csv_thinned(dir.join(output::TRAJECTORY_CSV), &monitored, DEFAULT_BUDGET)?
        }
        Format::Npy => read_npy_dir_thinned(dir, layout, &monitored, DEFAULT_BUDGET)?,
    };
    let conserved = spec.system.energy_not_conserved().is_none();
    let opts = options(&sketch, spec.output.angles.clone(), conserved);
    let reports = plot_run(&sketch.table, dir, &opts)?;
    let mut files: Vec<String> = reports
        .iter()
        .filter_map(|r| r.path.file_name())
        .map(|f| f.to_string_lossy().into_owned())
        .collect();
    files.extend(super::rigid_plots::draw(&sketch.table, dir, &opts)?);
    files.extend(super::multibody_plots::draw(&sketch.table, dir, &opts)?);
    files.extend(super::event_outputs::draw_observables(
        dir,
        &spec.events.observables.names,
        &sketch.table,
        &opts,
    )?);
    Ok(files)
}

/// Reads the run in `dir` (a finished or failed one) and draws every plot its columns allow;
/// a sweep's directory (`sweep.csv`) gets its sweep plot.
///
/// # Errors
/// Bad input if `dir` holds no readable run; failed if a plot cannot be drawn.
pub fn redraw(dir: &Path) -> Result<Vec<PlotReport>, Error> {
    let sweep_table = dir.join(SWEEP_CSV).exists() || dir.join(SWEEP_NPY).exists();
    if !dir.join(TRAJECTORY_CSV).exists() && sweep_table {
        return draw_sweep(dir).map(|r| vec![r]);
    }
    let (sketch, angles, conserved) = read_run(dir)?;
    let opts = options(&sketch, angles, conserved);
    let failed = |e: &dyn std::fmt::Display| {
        Error::failed(Diagnostic::new(format!("cannot draw the plots: {e}")))
    };
    let mut reports = plot_run(&sketch.table, dir, &opts).map_err(|e| failed(&e))?;
    let summary = read_summary(dir);
    let mut more = super::rigid_plots::draw(&sketch.table, dir, &opts).map_err(|e| failed(&e))?;
    more.extend(super::multibody_plots::draw(&sketch.table, dir, &opts).map_err(|e| failed(&e))?);
    let observables = strings(&summary["output"]["observables"]);
    let drawn = super::event_outputs::draw_observables(dir, &observables, &sketch.table, &opts);
    more.extend(drawn.map_err(|e| failed(&e))?);
    more.extend(redraw_section(dir, &summary)?);
    reports.extend(more.into_iter().map(|name| PlotReport {
        path: dir.join(name),
        notes: Vec::new(),
    }));
    if summary["energy_balance"].is_object()
        && let Some(last) = reports.last_mut()
    {
        last.notes.push(format!(
            "{} is not redrawn: the balance of every step is not stored in the run's files \
             (run the problem again to draw it)",
            super::balance::ENERGY_BALANCE_PNG
        ));
    }
    Ok(reports)
}

/// `summary.json` of the run in `dir` (`Null` if it cannot be read: the plots that need it
/// are then not redrawn).
fn read_summary(dir: &Path) -> serde_json::Value {
    std::fs::read_to_string(dir.join(SUMMARY_JSON))
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok())
        .unwrap_or(serde_json::Value::Null)
}

/// The strings of a JSON array (none for anything else).
fn strings(value: &serde_json::Value) -> Vec<String> {
    (value.as_array().into_iter().flatten())
        .filter_map(|c| c.as_str().map(str::to_owned))
        .collect()
}

/// `section.png` again from the event records, when `summary` names the section's axes.
///
/// # Errors
/// Records that cannot be read, or a plot that cannot be written.
fn redraw_section(dir: &Path, summary: &serde_json::Value) -> Result<Option<String>, Error> {
    let output = &summary["output"];
    let axes: Vec<Vec<String>> = (output["section"].as_array().into_iter().flatten())
        .map(strings)
        .collect();
    let [x, y] = axes.as_slice() else {
        return Ok(None);
    };
    let (Ok(x), Ok(y)) = (
        <[String; 2]>::try_from(x.clone()),
        <[String; 2]>::try_from(y.clone()),
    ) else {
        return Ok(None);
    };
    let format = match output["format"].as_str() {
        Some("npy") => Format::Npy,
        _ => Format::Csv,
    };
    let records =
        super::event_outputs::read_records(dir, format, strings(&output["event_columns"]))
            .map_err(|e| {
                Error::bad_input(Diagnostic::new(format!("cannot read the events: {e}")))
            })?;
    super::event_outputs::draw_section_of(dir, &records, &x, &y)
        .map(Some)
        .map_err(|e| Error::failed(Diagnostic::new(format!("cannot draw the section: {e}"))))
}

/// File name of a sweep's table.
const SWEEP_CSV: &str = "sweep.csv";
/// File name of a sweep's table written with `format = "npy"`.
const SWEEP_NPY: &str = "sweep.npy";
/// File name of a sweep's plot.
pub const SWEEP_PNG: &str = "sweep.png";
/// Columns of a sweep's table that are bookkeeping, not results.
const BOOKKEEPING: [&str; 4] = ["member", "steps", "steps_requested", "status"];

/// Draws `sweep.png` from the sweep table in `dir` (`sweep.csv`, or `sweep.npy` with the
/// column names of `summary.json`): each per-member result against the first swept value, and
/// for a grid one curve per combination of the other swept values.
///
/// # Errors
/// Bad input if the table cannot be read or has no swept column; failed if the plot cannot
/// be drawn.
pub fn draw_sweep(dir: &Path) -> Result<PlotReport, Error> {
    let bad = |message: String| Error::bad_input(Diagnostic::new(message));
    let summary: Option<serde_json::Value> = std::fs::read_to_string(dir.join(SUMMARY_JSON))
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok());
    let names = |key: &str| -> Vec<String> {
        summary
            .as_ref()
            .and_then(|j| j[key].as_array().cloned())
            .unwrap_or_default()
            .iter()
            .filter_map(|c| c.as_str().map(str::to_owned))
            .collect()
    };
    let table = if dir.join(SWEEP_CSV).exists() {
        let path = dir.join(SWEEP_CSV);
        read_csv_numeric(&path).map_err(|e| bad(e.to_string()))?
    } else {
        sweep_npy(dir, names("columns")).map_err(bad)?
    };
    let swept = names("swept_columns");
    let is_swept = |name: &str| swept.iter().any(|s| s == name);
    let mut columns = table.columns().iter().filter(|c| c.name != "member");
    let Some(x) = columns.next() else {
        return Err(bad(format!(
            "the sweep table in {} has no swept column",
            dir.display()
        )));
    };
    // Every member ending at the same time is bookkeeping too (no member failed early).
    let same_end =
        |c: &marsden_io::Column| c.name == "t_final" && c.values.windows(2).all(|w| w[0] == w[1]);
    let quantities: Vec<Series<'_>> = columns
        .filter(|c| !BOOKKEEPING.contains(&c.name.as_str()) && !is_swept(&c.name) && !same_end(c))
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect();
    let x = Series {
        name: &x.name,
        values: &x.values,
    };
    // A grid: the other swept axes pick the curves.
    let others: Vec<Series<'_>> = (table.columns().iter())
        .filter(|c| c.name != x.name && is_swept(&c.name))
        .map(|c| Series {
            name: &c.name,
            values: &c.values,
        })
        .collect();
    let (path, opts) = (dir.join(SWEEP_PNG), PlotOptions::default());
    match others.is_empty() {
        true => plot_sweep(path, x, &quantities, &opts),
        false => marsden_io::plot::plot_sweep_grid(path, x, &others, &quantities, &opts),
    }
    .map_err(|e| Error::failed(Diagnostic::new(format!("cannot draw the sweep plot: {e}"))))
}

/// `sweep.npy` as a table, its columns named by `names` (from `summary.json`).
fn sweep_npy(dir: &Path, names: Vec<String>) -> Result<marsden_io::Table, String> {
    let path = dir.join(SWEEP_NPY);
    let array = marsden_io::read_npy(&path).map_err(|e| e.to_string())?;
    let width = match array.shape[..] {
        [_, w] => w as usize,
        _ => {
            return Err(format!(
                "{} is not a table (shape {:?})",
                path.display(),
                array.shape
            ));
        }
    };
    if names.len() != width {
        return Err(format!(
            "{} has {width} columns but {SUMMARY_JSON} names {}",
            path.display(),
            names.len()
        ));
    }
    let rows = array.data.len() / width.max(1);
    let columns = names
        .into_iter()
        .enumerate()
        .map(|(j, name)| {
            let values = (0..rows).map(|i| array.data[i * width + j]).collect();
            marsden_io::Column::new(name, values)
        })
        .collect();
    marsden_io::Table::new(columns).map_err(|e| e.to_string())
}

/// The columns whose extremes the sketch keeps: the monitored quantities, where a spike is
/// news, and the first coordinates and momenta, whose envelope the time series shows.
fn monitored(names: &[String]) -> Vec<&str> {
    const COORDINATES: usize = 4;
    let watched = |n: &&str| {
        *n == "energy"
            || *n == "constraint_residual"
            || *n == "constraint_velocity_residual"
            || n.starts_with("J_")
            || n.starts_with("lambda_")
    };
    let prefixed = |prefix: &'static str| {
        names
            .iter()
            .map(String::as_str)
            .filter(move |n| n.starts_with(prefix))
            .take(COORDINATES)
    };
    let mut columns: Vec<&str> = names.iter().map(String::as_str).filter(watched).collect();
    columns.extend(prefixed("q_").chain(prefixed("p_")));
    let rigid = super::rigid_plots::COLUMNS;
    columns.extend(rigid.iter().filter(|c| names.iter().any(|n| n == *c)));
    let centres = super::multibody_plots::columns(names);
    columns.extend((names.iter().map(String::as_str)).filter(|n| centres.iter().any(|c| c == n)));
    columns
}

fn options(sketch: &Thinned, angles: Vec<String>, energy_conserved: bool) -> PlotOptions {
    PlotOptions {
        angles,
        note: sketch.note(),
        energy_conserved,
        ..PlotOptions::default()
    }
}

/// The trajectory of a run directory as a bounded sketch (`trajectory.csv`, or the `.npy`
/// files named by `summary.json`), the angles the summary declares, and whether it says the
/// energy is conserved (not when `energy_not_conserved` names a reason: a forced run's
/// `energy_balance.png`, drawn by the run from the work, is kept as it is).
fn read_run(dir: &Path) -> Result<(Thinned, Vec<String>, bool), Error> {
    let bad = |message: String| Error::bad_input(Diagnostic::new(message));
    let summary = dir.join(SUMMARY_JSON);
    let json: Option<serde_json::Value> = std::fs::read_to_string(&summary)
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok());
    let angles = json
        .as_ref()
        .map(|j| strings(&j["output"]["angles"]))
        .unwrap_or_default();
    let conserved = json
        .as_ref()
        .is_none_or(|j| j["energy_not_conserved"].is_null());
    let csv = dir.join(TRAJECTORY_CSV);
    if csv.exists() {
        let names = csv_header(&csv).map_err(|e| bad(e.to_string()))?;
        let sketch = read_csv_thinned(&csv, &monitored(&names), DEFAULT_BUDGET)
            .map_err(|e| bad(e.to_string()))?;
        return Ok((sketch, angles, conserved));
    }
    let json = match json {
        Some(json) => json,
        None => {
            let why = match std::fs::read_to_string(&summary) {
                Err(e) => format!("({e})"),
                Ok(_) => "(it is not valid JSON)".to_owned(),
            };
            return Err(bad(format!(
                "{} has neither {TRAJECTORY_CSV} nor a readable {SUMMARY_JSON} {why}: is it the output directory of a run?",
                dir.display()
            )));
        }
    };
    if json["output"]["format"].as_str() == Some("csv") {
        return Err(bad(format!(
            "{} has no {TRAJECTORY_CSV}, which its {SUMMARY_JSON} says the run wrote \
             (format \"csv\"): was it moved or deleted?",
            dir.display()
        )));
    }
    let columns = strings(&json["output"]["columns"]);
    let layout = match json["system"].as_str() {
        Some("multibody") => {
            output::multibody_layout_from_columns(&columns, &strings(&json["coordinates"]))
        }
        _ => layout_from_columns(&columns),
    };
    let layout = layout.map_err(|e| bad(format!("{}: output.columns: {e}", summary.display())))?;
    let sketch = read_npy_dir_thinned(dir, &layout, &monitored(&columns), DEFAULT_BUDGET)
        .map_err(|e| bad(e.to_string()))?;
    Ok((sketch, angles, conserved))
}

/// The column names on the first line of a CSV file.
fn csv_header(path: &Path) -> std::io::Result<Vec<String>> {
    use std::io::BufRead;
    use std::io::Read;
    let mut line = String::new();
    let file = std::fs::File::open(path).map_err(|e| {
        std::io::Error::new(e.kind(), format!("cannot open {}: {e}", path.display()))
    })?;
    let n = std::io::BufReader::new(file)
        .take(marsden_io::csv::MAX_LINE)
        .read_line(&mut line)
        .map_err(|e| {
            let why = match e.kind() {
                std::io::ErrorKind::InvalidData => {
                    "its first line is not UTF-8 text: not a trajectory".to_owned()
                }
                _ => format!("cannot read it: {e}"),
            };
            std::io::Error::new(e.kind(), format!("{}: {why}", path.display()))
        })?;
    if n as u64 == marsden_io::csv::MAX_LINE && !line.ends_with('\n') {
        return Err(std::io::Error::other(format!(
            "{}: its first line is longer than {} bytes: not a trajectory",
            path.display(),
            marsden_io::csv::MAX_LINE
        )));
    }
    Ok(line.trim_end().split(',').map(str::to_owned).collect())
}
