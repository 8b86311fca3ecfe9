//! The picture of a multibody run, beside the energy error, the joints' residual and the
//! multipliers every constrained run draws: the paths of the bodies' centres of mass, projected
//! on the coordinate plane in which they move most (the x–z plane of a planar pendulum).

use std::path::Path;

use marsden_io::plot::{Orbit, Plane, plot_configuration};
use marsden_io::{PlotOptions, Table};

/// File name of the plot.
pub const BODIES_PNG: &str = "bodies.png";

/// At most this many bodies are drawn (the first ones), so the legend and the sketch stay small.
const MOST: usize = 12;

const AXES: [&str; 3] = ["x", "y", "z"];

/// The bodies and particles of a multibody trajectory's columns: the prefixes `b` of its
/// `<b>_p_x` columns that have a `<b>_x` column too (a body has `<b>_R11` besides).
fn bodies<'n>(names: impl Iterator<Item = &'n str> + Clone) -> Vec<&'n str> {
    let all = names.clone();
    names
        .filter_map(|n| n.strip_suffix("_p_x"))
        .filter(|b| !b.is_empty() && all.clone().any(|n| n.strip_suffix("_x") == Some(*b)))
        .take(MOST)
        .collect()
}

/// The centre columns the plot reads, `<body>_x`, `<body>_y`, `<body>_z` (the sketch of the
/// trajectory must keep them); empty for other systems.
pub fn columns(names: &[String]) -> Vec<String> {
    (bodies(names.iter().map(String::as_str)).iter())
        .flat_map(|b| AXES.map(|a| format!("{b}_{a}")))
        .collect()
}

/// Draws the plot into `dir` if the table has bodies' centres; returns the file.
///
/// # Errors
/// The plot that could not be drawn.
pub fn draw(table: &Table, dir: &Path, opts: &PlotOptions) -> marsden_io::Result<Vec<String>> {
    let names: Vec<&str> = table.names().collect();
    let bodies = bodies(names.iter().copied());
    let mut centres = Vec::new();
    for b in &bodies {
        let axis = |a: &str| table.values(&format!("{b}_{a}"));
        if let (Some(x), Some(y), Some(z)) = (axis("x"), axis("y"), axis("z")) {
            centres.push((*b, [x, y, z]));
        }
    }
    if centres.is_empty() {
        return Ok(Vec::new());
    }
    let (a, b) = widest_plane(&centres);
    let orbits: Vec<Orbit<'_>> = (centres.iter())
        .map(|(name, c)| Orbit {
            name,
            x: c[a],
            y: c[b],
        })
        .collect();
    let plane = Plane {
        x_label: AXES[a].to_owned(),
        y_label: AXES[b].to_owned(),
        equal_axes: true,
        wrapped: (false, false),
        title: Some(format!(
            "Centres of mass of the bodies, in the {}–{} plane",
            AXES[a], AXES[b]
        )),
    };
    plot_configuration(dir.join(BODIES_PNG), &plane, &orbits, opts)?;
    Ok(vec![BODIES_PNG.to_owned()])
}

/// The two axes along which the centres spread most (their ranges summed over the bodies, finite
/// samples only), in the order x, y, z.
fn widest_plane(centres: &[(&str, [&[f64]; 3])]) -> (usize, usize) {
    let range = |axis: usize| -> f64 {
        (centres.iter())
            .map(|(_, c)| {
                let finite = c[axis].iter().filter(|v| v.is_finite());
                let (lo, hi) = finite.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(*v), hi.max(*v))
                });
                if hi >= lo { hi - lo } else { 0.0 }
            })
            .sum()
    };
    let spread = [range(0), range(1), range(2)];
    let narrowest = (0..3).fold(0, |n, i| if spread[i] < spread[n] { i } else { n });
    match narrowest {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_planar_chain_is_drawn_in_its_plane() {
        let (x, y, z) = ([0.0, 0.5, 1.0], [0.0, 0.0, 0.0], [-1.0, -0.8, -0.2]);
        assert_eq!(widest_plane(&[("a", [&x, &y, &z])]), (0, 2));
        assert_eq!(widest_plane(&[("a", [&y, &x, &z])]), (1, 2));
    }

    #[test]
    fn the_bodies_and_particles_are_the_prefixes_of_centre_and_momentum_columns() {
        let names: Vec<String> = [
            "t",
            "a_R11",
            "link_2_R11",
            "a_x",
            "link_2_x",
            "bob_x",
            "a_p_x",
            "link_2_p_x",
            "bob_p_x",
            "q_x",
            "p_x",
            "R11",
        ]
        .map(str::to_owned)
        .to_vec();
        assert_eq!(
            columns(&names),
            [
                "a_x", "a_y", "a_z", "link_2_x", "link_2_y", "link_2_z", "bob_x", "bob_y", "bob_z"
            ]
        );
    }
}
