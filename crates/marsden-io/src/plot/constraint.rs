//! Constraint residuals against time: the position constraint `|φ(q)|` and, when the run
//! recorded it, the hidden constraint `|Dφ(q)·v|` that RATTLE also keeps at the Newton
//! tolerance (HLW06 §VII.1, in the references of the `marsden` crate).

use std::path::Path;

use super::axis::{Scale, extent};
use super::options::{PlotOptions, PlotReport};
use super::prepare::{check_lengths, max_abs, sci, time_line};
use super::render::{Line, Panel, draw_figure};
use crate::error::Result;

/// Legend of the position residual when both curves are drawn.
pub const POSITION_LABEL: &str = "|φ(q)|";
/// Legend of the velocity (hidden constraint) residual.
pub const VELOCITY_LABEL: &str = "|Dφ(q)·v|";

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
    let panel = residual_panel(t, &[(None, residual)], opts.max_points);
    let title = format!("Constraint residual (max |r| = {})", sci(max_abs(residual)));
    draw_figure(path, opts, title, (1, 1), vec![panel])
}

/// Draws the position residual `|φ(q)|` and the velocity residual `|Dφ(q)·v|` against `t`, two
/// curves on one axis (logarithmic under the rule of [`plot_constraint_residual`], applied to
/// both together), each labelled with its maximum.
///
/// # Errors
/// As [`plot_constraint_residual`], for either series.
pub fn plot_constraint_residuals(
    path: impl AsRef<Path>,
    t: &[f64],
    position: &[f64],
    velocity: &[f64],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    check_lengths(path, ("t", t), ("constraint_residual", position))?;
    check_lengths(path, ("t", t), ("constraint_velocity_residual", velocity))?;
    let series = [
        (Some(POSITION_LABEL), position),
        (Some(VELOCITY_LABEL), velocity),
    ];
    let panel = residual_panel(t, &series, opts.max_points);
    let title = format!(
        "Constraint residuals (max |φ| = {}, max |Dφ·v| = {})",
        sci(max_abs(position)),
        sci(max_abs(velocity))
    );
    draw_figure(path, opts, title, (1, 1), vec![panel])
}

/// One panel of residual curves (`(legend, values)`, no legend for a lone curve) on a shared
/// axis: logarithmic when no finite value is negative and the positive ones span two decades.
pub(crate) fn residual_panel(
    t: &[f64],
    series: &[(Option<&str>, &[f64])],
    max_points: usize,
) -> Panel {
    let finite = || {
        (series.iter())
            .flat_map(|(_, values)| values.iter())
            .filter(|r| r.is_finite())
    };
    let positive = extent(finite().copied(), Scale::Log);
    let log = !finite().any(|&r| r < 0.0) && positive.is_some_and(|(lo, hi)| hi >= 100.0 * lo);
    let mut notes = Vec::new();
    let mut panel = Panel::new("", "t", "constraint residual");
    if log {
        panel.y_scale = Scale::Log;
    }
    for &(name, values) in series {
        let label = name.map(|n| format!("{n} (max {})", sci(max_abs(values))));
        let line = match log {
            true => log_line(name, label, t, values, max_points, &mut notes),
            false => time_line(name, label, t, values, max_points, &mut notes),
        };
        panel.lines.push(line);
    }
    panel.notes = notes;
    panel
}

/// A residual curve on a log axis: exact zeros become gaps, noted apart from non-finite values.
fn log_line(
    name: Option<&str>,
    label: Option<String>,
    t: &[f64],
    values: &[f64],
    max_points: usize,
    notes: &mut Vec<String>,
) -> Line {
    let who = name.map_or(String::new(), |n| format!("{n}: "));
    let zeros = values.iter().filter(|&&r| r == 0.0).count();
    if zeros > 0 {
        notes.push(format!(
            "{who}{zeros} exact zero(s) not shown on the log axis"
        ));
    }
    // Zeros become gaps; the non-finite count then includes them, so fix it up.
    let shown: Vec<f64> = values
        .iter()
        .map(|&r| if r == 0.0 { f64::NAN } else { r })
        .collect();
    let mut line = time_line(name, label, t, &shown, max_points, &mut Vec::new());
    line.data.non_finite -= zeros.min(line.data.non_finite);
    super::prepare::note_segments(name, &line.data, t.len(), notes);
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both residuals of a constrained run are drawn: two labelled curves on one log axis
    /// (RATTLE's residuals are round-off, spanning decades), each with its maximum.
    #[test]
    fn the_velocity_residual_is_a_second_labelled_curve() {
        let t = [0.0, 1.0, 2.0, 3.0];
        let position = [1e-16, 4e-16, 2e-15, 1e-16];
        let velocity = [0.0, 3e-14, 1e-13, 2e-14];
        let series = [
            (Some(POSITION_LABEL), &position[..]),
            (Some(VELOCITY_LABEL), &velocity[..]),
        ];
        let panel = residual_panel(&t, &series, 1000);
        assert_eq!(panel.lines.len(), 2);
        assert_eq!(panel.y_scale, Scale::Log);
        let labels: Vec<&str> = panel
            .lines
            .iter()
            .filter_map(|l| l.label.as_deref())
            .collect();
        assert_eq!(
            labels,
            ["|φ(q)| (max 2.00e-15)", "|Dφ(q)·v| (max 1.00e-13)"]
        );
        assert_eq!(
            panel.notes,
            ["|Dφ(q)·v|: 1 exact zero(s) not shown on the log axis"]
        );
    }

    /// A lone residual keeps its unlabelled curve.
    #[test]
    fn a_lone_residual_has_no_legend() {
        let t = [0.0, 1.0];
        let panel = residual_panel(&t, &[(None, &[1e-16, 1e-12][..])], 1000);
        assert_eq!(panel.lines.len(), 1);
        assert!(panel.lines[0].label.is_none());
    }
}
