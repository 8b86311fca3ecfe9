//! Constraint multipliers against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, max_abs, sci, series_panel};
use super::render::draw_figure;
use crate::error::Result;

/// Draws each multiplier `λ_i(t)` (the constraint forces `−Dφ(q)ᵀλ`) against `t`, one line
/// per multiplier with a legend giving its largest `|λ_i|`, to a PNG at `path`. Linear axis;
/// long series reduced to min/max per bucket; non-finite values are gaps.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a series' length differs from `t`'s or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_multipliers(
    path: impl AsRef<Path>,
    t: &[f64],
    multipliers: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for m in multipliers {
        check_lengths(path, ("t", t), (m.name, m.values))?;
    }
    let label = |m: &Series<'_>| format!("{} (max |λ| = {})", m.name, sci(max_abs(m.values)));
    let panel = series_panel("λ(t)", t, multipliers, opts.max_points, label);
    let title = "Constraint multipliers".to_owned();
    draw_figure(path, opts, title, (1, 1), vec![panel])
}
