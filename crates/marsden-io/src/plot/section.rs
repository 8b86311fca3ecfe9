//! A Poincaré section: the points where a run crossed a surface, one dot each, and the
//! observables of a run against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, series_panel};
use super::render::{Panel, draw_figure};
use crate::error::Result;

/// At most this many observables get a panel (the first ones).
const MAX_OBSERVABLE_PANELS: usize = 6;

/// Draws the points `(x_i, y_i)` of a Poincaré section as small dots to a PNG at `path`.
///
/// Every finite point is drawn (a dot of one pixel's radius, so thousands of points stay
/// legible as a pattern); non-finite points are skipped and noted; no points at all draws a
/// panel saying so.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if `x` and `y` differ in length or the image
/// size is out of range; I/O errors name `path`.
pub fn plot_section(
    path: impl AsRef<Path>,
    x: Series<'_>,
    y: Series<'_>,
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    check_lengths(path, (x.name, x.values), (y.name, y.values))?;
    let mut panel = Panel::new("", x.name, y.name);
    let cloud: Vec<(f64, f64)> = (x.values.iter().zip(y.values))
        .map(|(&x, &y)| (x, y))
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    let skipped = x.values.len() - cloud.len();
    if cloud.is_empty() {
        panel.notes.push("no crossings recorded".to_owned());
    } else {
        panel.clouds.push(cloud);
    }
    if skipped > 0 && skipped < x.values.len() {
        panel
            .notes
            .push(format!("{skipped} non-finite point(s) not drawn"));
    }
    let title = format!("Poincaré section ({} points)", x.values.len());
    draw_figure(path, opts, title, (1, 1), vec![panel])
}

/// Draws each observable against `t`, one panel each (the first six), to a PNG at `path`.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a series' length differs from `t`'s or the
/// image size is out of range; I/O errors name `path`.
pub fn plot_observables(
    path: impl AsRef<Path>,
    t: &[f64],
    observables: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for s in observables {
        check_lengths(path, ("t", t), (s.name, s.values))?;
    }
    let shown = &observables[..observables.len().min(MAX_OBSERVABLE_PANELS)];
    let mut panels: Vec<Panel> = shown
        .iter()
        .map(|s| {
            let name = |s: &Series<'_>| s.name.to_owned();
            series_panel(s.name, t, std::slice::from_ref(s), opts.max_points, name)
        })
        .collect();
    match panels.first_mut() {
        None => {
            let mut p = Panel::new("", "t", "");
            p.notes.push("no observables declared".to_owned());
            panels.push(p);
        }
        Some(first) if observables.len() > shown.len() => first.notes.push(format!(
            "showing the first {} of {} observables",
            shown.len(),
            observables.len()
        )),
        Some(_) => {}
    }
    let rows = panels.len();
    draw_figure(path, opts, "Observables".to_owned(), (rows, 1), panels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_thousands_of_points_and_notes_the_non_finite() {
        let dir = tempfile::tempdir().unwrap();
        let n = 3000;
        let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.01).sin()).collect();
        let mut y: Vec<f64> = (0..n).map(|i| (i as f64 * 0.013).cos()).collect();
        y[7] = f64::NAN;
        let path = dir.path().join("section.png");
        let xs = Series {
            name: "y",
            values: &x,
        };
        let ys = Series {
            name: "p_y",
            values: &y,
        };
        let report = plot_section(&path, xs, ys, &PlotOptions::default()).unwrap();
        assert!(path.metadata().unwrap().len() > 1000);
        assert_eq!(report.notes, ["1 non-finite point(s) not drawn"]);
        let short = Series {
            name: "p_y",
            values: &y[..10],
        };
        assert!(plot_section(&path, xs, short, &PlotOptions::default()).is_err());
    }

    #[test]
    fn draws_one_panel_per_observable() {
        let dir = tempfile::tempdir().unwrap();
        let t: Vec<f64> = (0..100).map(f64::from).collect();
        let a: Vec<f64> = t.iter().map(|t| t * t).collect();
        let path = dir.path().join("observables.png");
        let series = [
            Series {
                name: "a",
                values: &a,
            },
            Series {
                name: "b",
                values: &t,
            },
        ];
        plot_observables(&path, &t, &series, &PlotOptions::default()).unwrap();
        assert!(path.metadata().unwrap().len() > 1000);
    }
}
