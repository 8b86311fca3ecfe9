//! A grid sweep at a glance: each per-member quantity against the first swept value, one curve
//! per combination of the other axes' values (a sweep over `l × q[0]` draws one curve of the
//! final energy error against `l` for each `q[0]`).

use std::path::Path;

use super::axis::{Scale, extent};
use super::downsample::finite_segments;
use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::check_lengths;
use super::render::{Line, Panel, draw_figure};
use crate::error::Result;

/// At most this many quantities get a panel (the first ones).
const MAX_PANELS: usize = 6;
/// At most this many curves per panel (the first combinations of the other axes).
pub const MAX_CURVES: usize = 8;

/// The members that share one combination of the other axes' values, ordered by `x`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Curve {
    /// `q[0] = 0.2` (or `q[0] = 0.2, c = 1` for more axes).
    pub label: String,
    /// Member indices, by increasing `x`.
    pub members: Vec<usize>,
}

/// Draws each of `quantities` against the first swept value `x`, one panel per quantity and
/// one curve per combination of the values of the `others` axes (at most [`MAX_CURVES`], the
/// rest said in a note), to a PNG at `path`. A positive quantity spanning two decades or more
/// gets a log axis; a failed member's missing value leaves a gap.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a column's length differs from `x`'s or the
/// image size is out of range; I/O errors name `path`.
pub fn plot_sweep_grid(
    path: impl AsRef<Path>,
    x: Series<'_>,
    others: &[Series<'_>],
    quantities: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for s in others.iter().chain(quantities) {
        check_lengths(path, (x.name, x.values), (s.name, s.values))?;
    }
    let curves = curves(x.values, others);
    let shown = &quantities[..quantities.len().min(MAX_PANELS)];
    let mut panels: Vec<Panel> = shown.iter().map(|q| panel(x, *q, &curves)).collect();
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
    if curves.len() > MAX_CURVES {
        panels[0].notes.push(format!(
            "showing the first {MAX_CURVES} of {} combinations of {}",
            curves.len(),
            names(others)
        ));
    }
    let grid = match panels.len() {
        1 => (1, 1),
        2 => (1, 2),
        n => (n.div_ceil(2), 2),
    };
    let title = format!(
        "Sweep over {} × {} ({} members)",
        x.name,
        names(others),
        x.values.len()
    );
    draw_figure(path, opts, title, grid, panels)
}

/// `q[0]` or `q[0] × c`.
fn names(others: &[Series<'_>]) -> String {
    let names: Vec<&str> = others.iter().map(|s| s.name).collect();
    names.join(" × ")
}

/// The members grouped by their values of `others` (groups in order of first appearance), each
/// group ordered by `x`.
pub(crate) fn curves(x: &[f64], others: &[Series<'_>]) -> Vec<Curve> {
    let key = |i: usize| -> Vec<u64> { others.iter().map(|s| s.values[i].to_bits()).collect() };
    let mut keys: Vec<Vec<u64>> = Vec::new();
    let mut curves: Vec<Curve> = Vec::new();
    for i in 0..x.len() {
        let k = key(i);
        match keys.iter().position(|known| *known == k) {
            Some(c) => curves[c].members.push(i),
            None => {
                let parts: Vec<String> = (others.iter())
                    .map(|s| format!("{} = {}", s.name, s.values[i]))
                    .collect();
                keys.push(k);
                curves.push(Curve {
                    label: parts.join(", "),
                    members: vec![i],
                });
            }
        }
    }
    for curve in &mut curves {
        curve.members.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    }
    curves
}

/// One quantity's panel: a labelled line per curve (the first [`MAX_CURVES`]).
fn panel(x: Series<'_>, q: Series<'_>, curves: &[Curve]) -> Panel {
    let mut panel = Panel::new(q.name, x.name, q.name);
    let finite = || q.values.iter().copied().filter(|v| v.is_finite());
    let positive = extent(finite(), Scale::Log);
    if !finite().any(|v| v <= 0.0) && positive.is_some_and(|(lo, hi)| hi >= 100.0 * lo) {
        panel.y_scale = Scale::Log;
    }
    let mut missing = 0;
    for curve in curves.iter().take(MAX_CURVES) {
        let xs: Vec<f64> = curve.members.iter().map(|&i| x.values[i]).collect();
        let ys: Vec<f64> = curve.members.iter().map(|&i| q.values[i]).collect();
        let data = finite_segments(&xs, &ys);
        missing += data.non_finite;
        panel.lines.push(Line {
            label: Some(curve.label.clone()),
            data,
        });
    }
    if missing > 0 {
        panel.notes.push(format!(
            "{missing} member(s) without a value (failed or not run)"
        ));
    }
    panel
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid `l × q[0]` of the sweep tests (the last axis fastest): one curve per `q[0]`,
    /// each through its three members in increasing `l`.
    #[test]
    fn a_two_axis_grid_has_one_curve_per_value_of_the_second_axis() {
        let l = [0.5, 0.5, 1.0, 1.0, 2.0, 2.0];
        let q0 = [0.2, 0.4, 0.2, 0.4, 0.2, 0.4];
        let others = [Series {
            name: "q[0]",
            values: &q0,
        }];
        let got = curves(&l, &others);
        let want = [
            Curve {
                label: "q[0] = 0.2".to_owned(),
                members: vec![0, 2, 4],
            },
            Curve {
                label: "q[0] = 0.4".to_owned(),
                members: vec![1, 3, 5],
            },
        ];
        assert_eq!(got, want);
        let energy = [1e-3, 2e-3, 3e-3, f64::NAN, 5e-3, 6e-3];
        let quantity = Series {
            name: "max_rel_energy_error",
            values: &energy,
        };
        let x = Series {
            name: "l",
            values: &l,
        };
        let panel = panel(x, quantity, &got);
        assert_eq!(panel.lines.len(), 2);
        let points: Vec<Vec<(f64, f64)>> = panel.lines[0].data.segments.clone();
        assert_eq!(points, [vec![(0.5, 1e-3), (1.0, 3e-3), (2.0, 5e-3)]]);
        // The failed member leaves a gap in the second curve.
        assert_eq!(panel.lines[1].data.segments.len(), 2);
        assert_eq!(
            panel.notes,
            ["1 member(s) without a value (failed or not run)"]
        );
    }

    /// Members listed out of order (a shuffled table) are joined by increasing `x`.
    #[test]
    fn curves_are_ordered_by_the_first_axis() {
        let x = [3.0, 1.0, 2.0];
        let c = [7.0, 7.0, 7.0];
        let others = [Series {
            name: "c",
            values: &c,
        }];
        assert_eq!(curves(&x, &others)[0].members, [1, 2, 0]);
    }
}
