//! Coordinates and momenta against time: `q_i(t)` above, `p_i(t)` below.

use std::path::Path;

use super::angle::split_at_wraps;
use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, time_line};
use super::render::{Panel, draw_figure};
use crate::error::Result;

/// At most this many coordinates get a line in each panel (the first ones).
const MAX_LINES: usize = 8;

/// Draws `q_i(t)` (top panel) and `p_i(t)` (bottom panel) of the first coordinates, one
/// line per coordinate with a legend, to a PNG at `path`.
///
/// Series whose name is in `opts.angles` (as `q_<angle>`) are expected wrapped to (−π, π]
/// already and are drawn with a break where they wrap. Long series are reduced to min/max per
/// bucket, so the band a fast oscillation fills stays visible.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a series' length differs from `t`'s or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_time_series(
    path: impl AsRef<Path>,
    t: &[f64],
    q: &[Series<'_>],
    p: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for s in q.iter().chain(p) {
        check_lengths(path, ("t", t), (s.name, s.values))?;
    }
    let panels = vec![
        panel("Positions", "q", t, q, opts),
        panel("Momenta", "p", t, p, opts),
    ];
    draw_figure(
        path,
        opts,
        "Coordinates and momenta against time".to_owned(),
        (2, 1),
        panels,
    )
}

fn panel(
    title: &str,
    y_label: &str,
    t: &[f64],
    series: &[Series<'_>],
    opts: &PlotOptions,
) -> Panel {
    let mut panel = Panel::new(title, "t", y_label);
    let mut notes = Vec::new();
    for s in series.iter().take(MAX_LINES) {
        let angle = opts.is_angle(s.name);
        let label = if angle {
            format!("{} (mod 2π)", s.name)
        } else {
            s.name.to_owned()
        };
        let mut line = time_line(
            Some(s.name),
            Some(label),
            t,
            s.values,
            opts.max_points,
            &mut notes,
        );
        line.data = split_at_wraps(line.data, false, angle);
        panel.lines.push(line);
    }
    if series.len() > MAX_LINES {
        notes.push(format!("showing the first {MAX_LINES} of {}", series.len()));
    }
    if series.is_empty() {
        notes.push("no coordinates to plot".to_owned());
    }
    panel.notes = notes;
    panel
}
