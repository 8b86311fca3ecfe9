//! The pictures of a rigid body's run, beside the energy error and the momentum drift that
//! every run draws: where the body's third axis points in space (the tip of `R e₃` seen from
//! above: a heavy top's precession and nutation), and the body momentum `Π` on its sphere
//! `|Π| = const`, seen along the body axis it winds about (the free body's closed orbits about
//! its stable axes, [MR99] §15.5).
//!
//! [MR99]: marsden#references

use std::path::Path;

use marsden_io::plot::{Orbit, Plane, plot_configuration};
use marsden_io::{PlotOptions, Table};

/// File name of the axis-tip plot.
pub const ATTITUDE_PNG: &str = "axis_tip.png";
/// File name of the body-momentum plot.
pub const BODY_MOMENTUM_PNG: &str = "body_momentum.png";

/// The columns the plots read (the sketch of the trajectory must keep them).
pub const COLUMNS: [&str; 5] = ["R13", "R23", "Pi1", "Pi2", "Pi3"];

/// Subscripts of the body axes, for the labels.
const SUBSCRIPT: [&str; 3] = ["₁", "₂", "₃"];

/// Draws both plots into `dir` if the table has a rigid body's columns; returns the files.
///
/// # Errors
/// The plot that could not be drawn.
pub fn draw(table: &Table, dir: &Path, opts: &PlotOptions) -> marsden_io::Result<Vec<String>> {
    let column = |name: &str| table.values(name);
    let (Some(r13), Some(r23), Some(pi1), Some(pi2), Some(pi3)) = (
        column("R13"),
        column("R23"),
        column("Pi1"),
        column("Pi2"),
        column("Pi3"),
    ) else {
        return Ok(Vec::new());
    };
    let plane = |x: String, y: String, title: &str| Plane {
        x_label: x,
        y_label: y,
        equal_axes: true,
        wrapped: (false, false),
        title: Some(title.to_owned()),
    };
    let orbit = |x, y| [Orbit { name: "", x, y }];
    let tip = plane(
        "(R e₃)ₓ = R13".to_owned(),
        "(R e₃)ᵧ = R23".to_owned(),
        "Tip of the body axis e₃ in space, from above",
    );
    plot_configuration(dir.join(ATTITUDE_PNG), &tip, &orbit(r13, r23), opts)?;
    let pi = [pi1, pi2, pi3];
    let axis = winding_axis(&pi);
    let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
    let title = format!(
        "Body momentum Π on its sphere, seen along e{}",
        SUBSCRIPT[axis]
    );
    let sphere = plane(
        format!("Π{}", SUBSCRIPT[a]),
        format!("Π{}", SUBSCRIPT[b]),
        &title,
    );
    plot_configuration(
        dir.join(BODY_MOMENTUM_PNG),
        &sphere,
        &orbit(pi[a], pi[b]),
        opts,
    )?;
    Ok(vec![ATTITUDE_PNG.to_owned(), BODY_MOMENTUM_PNG.to_owned()])
}

/// The body axis the orbit of `Π` winds about: the one whose component keeps its sign and is
/// largest on average (its mean absolute value, finite samples only).
fn winding_axis(pi: &[&[f64]; 3]) -> usize {
    let mean = |c: &[f64]| {
        let (sum, n) =
            (c.iter().filter(|v| v.is_finite())).fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
        if n == 0 { 0.0 } else { (sum / n as f64).abs() }
    };
    (0..3).fold(0, |best, i| {
        if mean(pi[i]) > mean(pi[best]) {
            i
        } else {
            best
        }
    })
}

#[cfg(test)]
mod tests {
    use super::winding_axis;

    #[test]
    fn the_winding_axis_is_the_component_that_keeps_its_sign() {
        // A loop about e₃: Π₁ and Π₂ change sign, Π₃ stays near 0.9.
        let (p1, p2, p3) = (
            [0.4, 0.0, -0.4, 0.0],
            [0.0, 0.3, 0.0, -0.3],
            [0.9, 0.95, 0.9, 0.95],
        );
        assert_eq!(winding_axis(&[&p1, &p2, &p3]), 2);
        assert_eq!(winding_axis(&[&p3, &p2, &p1]), 0);
    }
}
