//! Which plane the configuration plot shows, read off the coordinate names.

use super::axis::{Scale, extent};
use super::columns::Columns;
use super::configuration::Plane;
use super::options::PlotOptions;

/// The columns of one orbit in the configuration plot.
pub(crate) struct OrbitColumns {
    /// Legend entry (`body 2`), empty for a single point.
    pub legend: String,
    /// Horizontal coordinate's column, e.g. `q_x2`.
    pub x: String,
    /// Vertical coordinate's column.
    pub y: String,
}

/// The plane of the configuration plot and its orbits `(legend, x column, y column)`, when the
/// coordinate names say where the points are:
///
/// * N-body (`x1 y1 z1 x2 …`): one orbit per body, in the plane of the two axes along which the
///   bodies spread most (so a planar problem is seen face on);
/// * coordinates `x` and `y` (Kepler, a Cartesian pendulum): the path in the x–y plane;
/// * exactly two other coordinates: the path in their plane (angles wrapped, axes not equal).
pub(crate) fn plane_of(
    columns: &Columns<'_>,
    coordinates: &[&str],
    opts: &PlotOptions,
) -> Option<(Plane, Vec<OrbitColumns>)> {
    let has = |name: &str| coordinates.contains(&name);
    let bodies: Vec<String> = coordinates
        .iter()
        .filter_map(|c| c.strip_prefix('x'))
        .filter(|k| !k.is_empty() && k.chars().all(|ch| ch.is_ascii_digit()))
        .filter(|k| has(&format!("y{k}")))
        .map(str::to_owned)
        .collect();
    let plane = |x: &str, y: &str, equal: bool| Plane {
        x_label: x.to_owned(),
        y_label: y.to_owned(),
        equal_axes: equal,
        wrapped: (opts.is_angle(x), opts.is_angle(y)),
        title: None,
    };
    if !bodies.is_empty() {
        let spread = |axis: char| -> f64 {
            bodies
                .iter()
                .map(|k| range_of(columns.get(&format!("q_{axis}{k}"))))
                .sum()
        };
        let mut axes: Vec<char> = ['x', 'y', 'z']
            .into_iter()
            .filter(|a| bodies.iter().all(|k| has(&format!("{a}{k}"))))
            .collect();
        axes.sort_by(|a, b| spread(*b).total_cmp(&spread(*a)));
        let (a, b) = (axes[0].min(axes[1]), axes[0].max(axes[1]));
        let orbits = bodies
            .iter()
            .map(|k| OrbitColumns {
                legend: format!("body {k}"),
                x: format!("q_{a}{k}"),
                y: format!("q_{b}{k}"),
            })
            .collect();
        return Some((plane(&a.to_string(), &b.to_string(), true), orbits));
    }
    let pair = if has("x") && has("y") {
        Some(("x", "y"))
    } else if let [a, b] = coordinates {
        Some((*a, *b))
    } else {
        None
    }?;
    let equal = !opts.is_angle(pair.0) && !opts.is_angle(pair.1);
    let orbit = OrbitColumns {
        legend: String::new(),
        x: format!("q_{}", pair.0),
        y: format!("q_{}", pair.1),
    };
    Some((plane(pair.0, pair.1, equal), vec![orbit]))
}

/// The spread `max − min` of the finite values (0 if none).
fn range_of(values: &[f64]) -> f64 {
    extent(values.iter().copied(), Scale::Linear).map_or(0.0, |(lo, hi)| hi - lo)
}
