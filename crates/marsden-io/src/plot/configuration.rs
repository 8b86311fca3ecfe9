//! Configuration space: the path of the system's points in a plane (an orbit, a pendulum's
//! arc, the bodies of an N-body run), with equal axes so circles look round.

use std::path::Path;

use super::angle::split_at_wraps;
use super::axis::{Scale, extent, padded};
use super::downsample::{finite_segments, grid_thin};
use super::options::{PlotOptions, PlotReport};
use super::prepare::{check_lengths, note_segments};
use super::render::{Line, Panel, draw_figure};
use crate::error::Result;

/// One point's path in the plane: its legend name and its coordinates over time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit<'a> {
    /// Legend label (a body, or empty for a single point).
    pub name: &'a str,
    /// Horizontal coordinate over time.
    pub x: &'a [f64],
    /// Vertical coordinate over time, same length as `x`.
    pub y: &'a [f64],
}

/// What the configuration plot shows: axis names and whether lengths on both axes are alike.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Plane {
    /// Horizontal axis label, e.g. `x`.
    pub x_label: String,
    /// Vertical axis label, e.g. `y`.
    pub y_label: String,
    /// One unit is as long on both axes (true for positions; false when an axis is an angle).
    pub equal_axes: bool,
    /// The axes are angles wrapped to (−π, π]: lines break where they wrap.
    pub wrapped: (bool, bool),
    /// The figure's title (`None`: "Configuration space").
    pub title: Option<String>,
}

/// Draws every orbit in one panel to a PNG at `path`, one colour per orbit.
///
/// Paths of at most `opts.max_points` points are drawn as lines; longer ones as dots thinned to
/// about one per pixel. Each orbit's first point is marked, so the direction of motion can be
/// read off together with the time series.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if an orbit's `x` and `y` differ in length or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_configuration(
    path: impl AsRef<Path>,
    plane: &Plane,
    orbits: &[Orbit<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for o in orbits {
        check_lengths(path, (&plane.x_label, o.x), (&plane.y_label, o.y))?;
    }
    let mut panel = Panel::new("", plane.x_label.as_str(), plane.y_label.as_str());
    panel.equal_axes = plane.equal_axes;
    let cells = (opts.width as usize, opts.height as usize);
    let all = || {
        orbits.iter().flat_map(|o| {
            o.x.iter()
                .zip(o.y)
                .map(|(&x, &y)| (x, y))
                .filter(|(x, y)| x.is_finite() && y.is_finite())
        })
    };
    let ranges = (
        extent(all().map(|p| p.0), Scale::Linear).map(|(lo, hi)| padded(lo, hi, Scale::Linear)),
        extent(all().map(|p| p.1), Scale::Linear).map(|(lo, hi)| padded(lo, hi, Scale::Linear)),
    );
    for o in orbits {
        let n = o.x.len();
        let label = (!o.name.is_empty()).then(|| o.name.to_owned());
        if n <= opts.max_points {
            let data = finite_segments(o.x, o.y);
            note_segments(Some(o.name), &data, n, &mut panel.notes);
            let data = split_at_wraps(data, plane.wrapped.0, plane.wrapped.1);
            panel.lines.push(Line { label, data });
        } else if let (Some(xr), Some(yr)) = ranges {
            let points = o.x.iter().zip(o.y).map(|(&x, &y)| (x, y));
            panel.clouds.push(grid_thin(points, xr, yr, cells));
        }
        if let Some(start) =
            o.x.iter()
                .zip(o.y)
                .find(|(x, y)| x.is_finite() && y.is_finite())
        {
            panel.markers.push((*start.0, *start.1));
        }
    }
    if orbits.iter().any(|o| o.x.len() > opts.max_points) {
        panel
            .notes
            .push("long paths drawn as dots, about one per pixel".to_owned());
    }
    if orbits.is_empty() {
        panel.notes.push("no positions to plot".to_owned());
    }
    draw_figure(
        path,
        opts,
        format!(
            "{} (● start)",
            plane.title.as_deref().unwrap_or("Configuration space")
        ),
        (1, 1),
        vec![panel],
    )
}
