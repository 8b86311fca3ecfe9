//! Named series against a common abscissa, one or more panels: the controls of an optimal
//! control run against time, the convergence history of its solver against the iteration.

use std::path::Path;

use super::axis::Scale;
use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, time_line};
use super::render::{Panel, draw_figure};
use crate::error::Result;

/// At most this many series get a line in a panel (the first ones).
const MAX_LINES: usize = 8;

/// One panel of [`plot_lines`]: series against `x`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinePanel<'a> {
    /// Panel title.
    pub title: &'a str,
    /// Label of the horizontal axis.
    pub x_label: &'a str,
    /// Label of the vertical axis.
    pub y_label: &'a str,
    /// The abscissa, shared by the series.
    pub x: &'a [f64],
    /// The series, each as long as `x`.
    pub series: &'a [Series<'a>],
    /// A base-10 logarithmic vertical axis (values ≤ 0 are gaps, noted).
    pub log: bool,
}

/// Draws the `panels` stacked vertically under `title` to a PNG at `path`, one line per series
/// with a legend.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a series' length differs from its `x` or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_lines(
    path: impl AsRef<Path>,
    title: &str,
    panels: &[LinePanel<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    let mut drawn = Vec::with_capacity(panels.len());
    for p in panels {
        for s in p.series {
            check_lengths(path, ("x", p.x), (s.name, s.values))?;
        }
        drawn.push(panel(p, opts));
    }
    let rows = drawn.len().max(1);
    draw_figure(path, opts, title.to_owned(), (rows, 1), drawn)
}

fn panel(p: &LinePanel<'_>, opts: &PlotOptions) -> Panel {
    let mut panel = Panel::new(p.title, p.x_label, p.y_label);
    let mut notes = Vec::new();
    if p.log {
        panel.y_scale = Scale::Log;
    }
    for s in p.series.iter().take(MAX_LINES) {
        let values: Vec<f64> = match p.log {
            true => {
                let hidden = s.values.iter().filter(|&&v| v <= 0.0).count();
                if hidden > 0 {
                    notes.push(format!(
                        "{}: {hidden} value(s) ≤ 0 not shown on the log axis",
                        s.name
                    ));
                }
                s.values
                    .iter()
                    .map(|&v| if v > 0.0 { v } else { f64::NAN })
                    .collect()
            }
            false => s.values.to_vec(),
        };
        let mut ignored = Vec::new();
        let sink = if p.log { &mut ignored } else { &mut notes };
        let line = time_line(
            Some(s.name),
            Some(s.name.to_owned()),
            p.x,
            &values,
            opts.max_points,
            sink,
        );
        panel.lines.push(line);
    }
    if p.series.len() > MAX_LINES {
        notes.push(format!(
            "showing the first {MAX_LINES} of {}",
            p.series.len()
        ));
    }
    if p.series.is_empty() {
        notes.push("nothing to plot".to_owned());
    }
    panel.notes = notes;
    panel
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_linear_and_log_panels() {
        let dir = tempfile::tempdir().unwrap();
        let x = [0.0, 1.0, 2.0, 3.0];
        let u = [1.0, -1.0, 0.5, 0.0];
        let kkt = [1.0, 1e-3, 1e-9, 0.0];
        let su = [Series {
            name: "u",
            values: &u,
        }];
        let sk = [Series {
            name: "kkt",
            values: &kkt,
        }];
        let panels = [
            LinePanel {
                title: "controls",
                x_label: "t",
                y_label: "u",
                x: &x,
                series: &su,
                log: false,
            },
            LinePanel {
                title: "history",
                x_label: "iteration",
                y_label: "",
                x: &x,
                series: &sk,
                log: true,
            },
        ];
        let path = dir.path().join("lines.png");
        let report = plot_lines(&path, "test", &panels, &PlotOptions::default()).unwrap();
        assert!(std::fs::metadata(&path).unwrap().len() > 1000);
        assert!(
            report
                .notes
                .iter()
                .any(|n| n.contains("kkt: 1 value(s) ≤ 0")),
            "{:?}",
            report.notes
        );
        let short = [Series {
            name: "u",
            values: &u[..2],
        }];
        let bad = [LinePanel {
            series: &short,
            ..panels[0]
        }];
        assert!(plot_lines(&path, "test", &bad, &PlotOptions::default()).is_err());
    }
}
