//! Momentum-map drift against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, first_finite, max_abs, sci, time_line};
use super::render::{Figure, Panel, render};
use crate::error::Result;

/// Draws each momentum map's drift `J(t) − J(t₀)` against `t`, one line per map with a
/// legend giving its maximum `|ΔJ|`, to a PNG at `path`.
///
/// The drift is absolute (momentum maps are often exactly zero, so a relative drift is
/// undefined). Linear axis with scientific tick labels; long series reduced to min/max per
/// bucket. No maps at all draws an empty chart saying so.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a map's length differs from `t`'s or the
/// image size is out of range; I/O errors name `path`.
pub fn plot_momentum_drift(
    path: impl AsRef<Path>,
    t: &[f64],
    maps: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for m in maps {
        check_lengths(path, ("t", t), (m.name, m.values))?;
    }
    let mut panel = Panel::new("", "t", "J(t) − J(t₀)");
    let mut notes = Vec::new();
    let mut overall: Option<f64> = None;
    for m in maps {
        let drift: Vec<f64> = match first_finite(m.values) {
            Some((_, j0)) => m.values.iter().map(|j| j - j0).collect(),
            None => m.values.to_vec(),
        };
        let max = max_abs(&drift);
        overall = match (overall, max) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        let label = format!("{} (max |ΔJ| = {})", m.name, sci(max));
        panel.lines.push(time_line(
            Some(m.name),
            Some(label),
            t,
            &drift,
            opts.max_points,
            &mut notes,
        ));
    }
    if maps.is_empty() {
        notes.push("no momentum maps declared".to_owned());
    }
    panel.notes = notes;
    let mut fig = Figure {
        title: format!("Momentum map drift (max |ΔJ| = {})", sci(overall)),
        grid: (1, 1),
        panels: vec![panel],
    };
    let notes = render(path, opts, &mut fig)?;
    Ok(PlotReport {
        path: path.to_path_buf(),
        notes,
    })
}
