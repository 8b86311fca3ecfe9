//! The pictures of a rigid body's run, beside the energy error and the momentum drift that
//! every run draws: where the body's third axis points in space (the tip of `R e₃`, seen from
//! above: a heavy top's precession and nutation), and the body momentum `Π` on its sphere
//! `|Π| = const` (seen along `e₂`: the free body's closed orbits about its stable axes).

use std::path::Path;

use marsden_io::plot::{Orbit, Plane, plot_configuration};
use marsden_io::{PlotOptions, Table};

/// File name of the axis-tip plot.
pub const ATTITUDE_PNG: &str = "axis_tip.png";
/// File name of the body-momentum plot.
pub const BODY_MOMENTUM_PNG: &str = "body_momentum.png";

/// The columns the plots read (the sketch of the trajectory must keep them).
pub const COLUMNS: [&str; 5] = ["R13", "R23", "Pi1", "Pi2", "Pi3"];

/// Draws both plots into `dir` if the table has a rigid body's columns; returns the files.
///
/// # Errors
/// The plot that could not be drawn.
pub fn draw(table: &Table, dir: &Path, opts: &PlotOptions) -> marsden_io::Result<Vec<String>> {
    let column = |name: &str| table.values(name);
    let (Some(r13), Some(r23), Some(pi1), Some(pi3)) =
        (column("R13"), column("R23"), column("Pi1"), column("Pi3"))
    else {
        return Ok(Vec::new());
    };
    let tip = Plane {
        x_label: "(R e₃)ₓ = R13".to_owned(),
        y_label: "(R e₃)ᵧ = R23".to_owned(),
        equal_axes: true,
        wrapped: (false, false),
    };
    let orbit = |x, y| [Orbit { name: "", x, y }];
    plot_configuration(dir.join(ATTITUDE_PNG), &tip, &orbit(r13, r23), opts)?;
    let sphere = Plane {
        x_label: "Π₁".to_owned(),
        y_label: "Π₃".to_owned(),
        equal_axes: true,
        wrapped: (false, false),
    };
    plot_configuration(dir.join(BODY_MOMENTUM_PNG), &sphere, &orbit(pi1, pi3), opts)?;
    Ok(vec![ATTITUDE_PNG.to_owned(), BODY_MOMENTUM_PNG.to_owned()])
}
