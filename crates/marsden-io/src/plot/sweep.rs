//! A sweep at a glance: each per-member quantity (energy error, drift, final state, …) against
//! the swept value.

use std::path::Path;

use super::axis::{Scale, extent};
use super::downsample::{Segments, finite_segments};
use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::check_lengths;
use super::render::{Line, Panel, draw_figure};
use crate::error::Result;

/// At most this many quantities get a panel (the first ones).
const MAX_PANELS: usize = 6;

/// Draws each of `quantities` against the swept value `x`, one panel each, to a PNG at `path`.
///
/// Points are joined when the swept values increase (a one-parameter sweep) and drawn as dots
/// otherwise (a grid). A positive quantity spanning two decades or more gets a log axis (energy
/// errors across step sizes); a failed member's missing value leaves a gap.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a quantity's length differs from `x`'s or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_sweep(
    path: impl AsRef<Path>,
    x: Series<'_>,
    quantities: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for q in quantities {
        check_lengths(path, (x.name, x.values), (q.name, q.values))?;
    }
    let increasing = x.values.windows(2).all(|w| w[0] < w[1]);
    let shown = &quantities[..quantities.len().min(MAX_PANELS)];
    let mut panels: Vec<Panel> = shown.iter().map(|q| panel(x, *q, increasing)).collect();
    if panels.is_empty() {
        let mut empty = Panel::new("", x.name, "");
        empty
            .notes
            .push("no numeric quantity per member".to_owned());
        panels.push(empty);
    } else if quantities.len() > shown.len() {
        panels[0].notes.push(format!(
            "showing the first {} of {} quantities",
            shown.len(),
            quantities.len()
        ));
    }
    let grid = match panels.len() {
        1 => (1, 1),
        2 => (1, 2),
        n => (n.div_ceil(2), 2),
    };
    let title = format!("Sweep over {} ({} members)", x.name, x.values.len());
    draw_figure(path, opts, title, grid, panels)
}

fn panel(x: Series<'_>, q: Series<'_>, increasing: bool) -> Panel {
    let mut panel = Panel::new(q.name, x.name, q.name);
    let finite = || q.values.iter().copied().filter(|v| v.is_finite());
    let positive = extent(finite(), Scale::Log);
    if !finite().any(|v| v <= 0.0) && positive.is_some_and(|(lo, hi)| hi >= 100.0 * lo) {
        panel.y_scale = Scale::Log;
    }
    let data = if increasing {
        finite_segments(x.values, q.values)
    } else {
        let all = finite_segments(x.values, q.values);
        Segments {
            segments: all.points().map(|p| vec![p]).collect(),
            ..all
        }
    };
    let missing = data.non_finite;
    if missing > 0 {
        panel.notes.push(format!(
            "{missing} member(s) without a value (failed or not run)"
        ));
    }
    panel.lines.push(Line { label: None, data });
    panel
}
