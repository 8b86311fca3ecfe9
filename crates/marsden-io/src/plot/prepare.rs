//! Turning caller data into panel lines: length checks, reference values, notes.

use std::path::Path;

use super::downsample::{Segments, min_max};
use super::options::Series;
use super::render::{Line, Panel};
use crate::error::{Error, Result};

/// Fails with [`Error::PlotInput`] unless `a` and `b` have the same length.
pub(crate) fn check_lengths(path: &Path, a: (&str, &[f64]), b: (&str, &[f64])) -> Result<()> {
    if a.1.len() == b.1.len() {
        return Ok(());
    }
    Err(Error::PlotInput {
        path: path.to_path_buf(),
        message: format!(
            "`{}` has {} values but `{}` has {}",
            a.0,
            a.1.len(),
            b.0,
            b.1.len()
        ),
    })
}

/// The first finite value and its index.
pub(crate) fn first_finite(values: &[f64]) -> Option<(usize, f64)> {
    values
        .iter()
        .copied()
        .enumerate()
        .find(|(_, v)| v.is_finite())
}

/// The largest finite `|v|`, if any.
pub(crate) fn max_abs(values: &[f64]) -> Option<f64> {
    values
        .iter()
        .filter(|v| v.is_finite())
        .map(|v| v.abs())
        .fold(None, |m, v| Some(m.map_or(v, |m: f64| m.max(v))))
}

/// `3.14e-9`, `0`, or `n/a` when there is no value.
pub(crate) fn sci(v: Option<f64>) -> String {
    match v {
        None => "n/a".to_owned(),
        Some(0.0) => "0".to_owned(),
        Some(v) => format!("{v:.2e}"),
    }
}

/// A time-series line (reduced to `max_points`) plus notes on what was dropped or reduced;
/// `name` prefixes notes about this series only.
pub(crate) fn time_line(
    name: Option<&str>,
    label: Option<String>,
    t: &[f64],
    values: &[f64],
    max_points: usize,
    notes: &mut Vec<String>,
) -> Line {
    let data = min_max(t, values, max_points);
    note_segments(name, &data, t.len(), notes);
    Line { label, data }
}

/// Adds notes about non-finite values (prefixed by `name`) and bucketing (once per panel).
pub(crate) fn note_segments(
    name: Option<&str>,
    data: &Segments,
    n: usize,
    notes: &mut Vec<String>,
) {
    let who = name.map_or(String::new(), |n| format!("{n}: "));
    if data.non_finite > 0 && data.non_finite < n {
        notes.push(format!(
            "{who}{} non-finite value(s) not drawn (gaps)",
            data.non_finite
        ));
    }
    let bucket_note = format!(
        "{n} points per series, shown as min/max of {} buckets",
        data.buckets
    );
    if data.buckets > 0 && !notes.contains(&bucket_note) {
        notes.push(bucket_note);
    }
}

/// A panel of named series against `t`, one line each; `label` gives each legend entry.
pub(crate) fn series_panel(
    y_label: &str,
    t: &[f64],
    series: &[Series<'_>],
    max_points: usize,
    label: impl Fn(&Series<'_>) -> String,
) -> Panel {
    let mut panel = Panel::new("", "t", y_label);
    let mut notes = Vec::new();
    for s in series {
        let line = time_line(
            Some(s.name),
            Some(label(s)),
            t,
            s.values,
            max_points,
            &mut notes,
        );
        panel.lines.push(line);
    }
    panel.notes = notes;
    panel
}
