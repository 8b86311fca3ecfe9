//! Constraint residual against time.

use std::path::Path;

use super::axis::{Scale, extent};
use super::options::{PlotOptions, PlotReport};
use super::prepare::{check_lengths, max_abs, sci, time_line};
use super::render::{Panel, draw_figure};
use crate::error::Result;

/// Draws the constraint residual against `t` to a PNG at `path`.
///
/// When no finite value is negative and the positive ones span at least two decades (a norm
/// varying over orders of magnitude) the axis is **logarithmic**; exact zeros cannot be shown
/// there and are noted. Otherwise (signed residuals, a narrow range, all zero) the axis is
/// linear with scientific labels.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if `t` and `residual` differ in length or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_constraint_residual(
    path: impl AsRef<Path>,
    t: &[f64],
    residual: &[f64],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    check_lengths(path, ("t", t), ("constraint_residual", residual))?;
    let finite = || residual.iter().filter(|r| r.is_finite());
    let positive = extent(finite().copied(), Scale::Log);
    let log = !finite().any(|&r| r < 0.0) && positive.is_some_and(|(lo, hi)| hi >= 100.0 * lo);
    let mut notes = Vec::new();
    let mut panel = Panel::new("", "t", "constraint residual");
    let line = if log {
        panel.y_scale = Scale::Log;
        let zeros = finite().filter(|&&r| r == 0.0).count();
        if zeros > 0 {
            notes.push(format!("{zeros} exact zero(s) not shown on the log axis"));
        }
        // Zeros become gaps; the non-finite count then includes them, so fix it up.
        let shown: Vec<f64> = residual
            .iter()
            .map(|&r| if r == 0.0 { f64::NAN } else { r })
            .collect();
        let mut line = time_line(None, None, t, &shown, opts.max_points, &mut Vec::new());
        line.data.non_finite -= zeros.min(line.data.non_finite);
        super::prepare::note_segments(None, &line.data, t.len(), &mut notes);
        line
    } else {
        time_line(None, None, t, residual, opts.max_points, &mut notes)
    };
    panel.lines.push(line);
    panel.notes = notes;
    let title = format!("Constraint residual (max |r| = {})", sci(max_abs(residual)));
    draw_figure(path, opts, title, (1, 1), vec![panel])
}
