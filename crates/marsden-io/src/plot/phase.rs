//! Phase portrait: `p_i` against `q_i`, one panel per coordinate (the first few).

use std::path::Path;

use super::angle::split_at_wraps;
use super::axis::{Scale, extent, padded};
use super::downsample::{finite_segments, grid_thin};
use super::options::{PhaseCurve, PlotOptions, PlotReport};
use super::prepare::{check_lengths, note_segments};
use super::render::{Line, Panel, draw_figure};
use crate::error::Result;

/// Draws a phase portrait of the first `opts.max_phase_panels` coordinates to a PNG at `path`.
///
/// Curves of at most `opts.max_points` points are drawn as lines; longer ones as dots, thinned
/// to about one per pixel (a long run's orbit reads as its trace, and drawing stays bounded).
/// Non-finite points are skipped (noted); empty input draws a panel saying so. Coordinates in
/// `opts.angles` are expected wrapped to (−π, π] already; their curves break where they wrap.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a curve's `q` and `p` differ in length or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_phase_portrait(
    path: impl AsRef<Path>,
    curves: &[PhaseCurve<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for c in curves {
        check_lengths(
            path,
            (&format!("q_{}", c.name), c.q),
            (&format!("p_{}", c.name), c.p),
        )?;
    }
    let shown = &curves[..curves.len().min(opts.max_phase_panels.max(1))];
    let grid = match shown.len() {
        0 | 1 => (1, 1),
        2 => (1, 2),
        n => (n.div_ceil(2), 2),
    };
    let cell_px = (
        (opts.width as usize / grid.1).max(1),
        (opts.height as usize / grid.0).max(1),
    );
    let mut panels: Vec<Panel> = shown
        .iter()
        .map(|c| phase_panel(c, opts.max_points, cell_px, opts.is_angle(c.name)))
        .collect();
    match panels.first_mut() {
        None => {
            let mut p = Panel::new("", "q", "p");
            p.notes.push("no coordinates to plot".to_owned());
            panels.push(p);
        }
        Some(first) if curves.len() > shown.len() => first.notes.push(format!(
            "showing the first {} of {} coordinates",
            shown.len(),
            curves.len()
        )),
        Some(_) => {}
    }
    draw_figure(path, opts, "Phase portrait".to_owned(), grid, panels)
}

fn phase_panel(
    c: &PhaseCurve<'_>,
    max_points: usize,
    cell_px: (usize, usize),
    angle: bool,
) -> Panel {
    let q_label = if angle {
        format!("q_{} (mod 2π)", c.name)
    } else {
        format!("q_{}", c.name)
    };
    let mut panel = Panel::new(c.name, q_label, format!("p_{}", c.name));
    let n = c.q.len();
    if n <= max_points {
        let data = finite_segments(c.q, c.p);
        note_segments(None, &data, n, &mut panel.notes);
        let data = split_at_wraps(data, angle, false);
        panel.lines.push(Line { label: None, data });
        return panel;
    }
    let finite = || {
        c.q.iter()
            .zip(c.p)
            .map(|(&q, &p)| (q, p))
            .filter(|(q, p)| q.is_finite() && p.is_finite())
    };
    let non_finite = n - finite().count();
    if let (Some(xr), Some(yr)) = (
        extent(finite().map(|p| p.0), Scale::Linear),
        extent(finite().map(|p| p.1), Scale::Linear),
    ) {
        let cloud = grid_thin(
            finite(),
            padded(xr.0, xr.1, Scale::Linear),
            padded(yr.0, yr.1, Scale::Linear),
            cell_px,
        );
        panel.clouds.push(cloud);
        panel.notes.push(format!("{n} points, drawn as dots"));
    }
    if non_finite > 0 && non_finite < n {
        panel
            .notes
            .push(format!("{non_finite} non-finite point(s) not drawn"));
    }
    panel
}
