//! Momentum-map drift against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, first_finite, max_abs, sci, series_panel};
use super::render::draw_figure;
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
    let drifts: Vec<Vec<f64>> = maps
        .iter()
        .map(|m| match first_finite(m.values) {
            Some((_, j0)) => m.values.iter().map(|j| j - j0).collect(),
            None => m.values.to_vec(),
        })
        .collect();
    let drift_series: Vec<Series<'_>> = maps
        .iter()
        .zip(&drifts)
        .map(|(m, d)| Series {
            name: m.name,
            values: d,
        })
        .collect();
    let label = |d: &Series<'_>| format!("{} (max |ΔJ| = {})", d.name, sci(max_abs(d.values)));
    let mut panel = series_panel("J(t) − J(t₀)", t, &drift_series, opts.max_points, label);
    if maps.is_empty() {
        panel.notes.push("no momentum maps declared".to_owned());
    }
    let overall = drifts.iter().filter_map(|d| max_abs(d)).reduce(f64::max);
    let title = format!("Momentum map drift (max |ΔJ| = {})", sci(overall));
    draw_figure(path, opts, title, (1, 1), vec![panel])
}
