//! Constraint multipliers against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport, Series};
use super::prepare::{check_lengths, max_abs, sci, time_line};
use super::render::{Figure, Panel, render};
use crate::error::Result;

/// Draws each multiplier `λ_i(t)` (the constraint forces `−Dφ(q)ᵀλ`) against `t`, one line
/// per multiplier with a legend giving its largest `|λ_i|`, to a PNG at `path`. Linear axis;
/// long series reduced to min/max per bucket; non-finite values are gaps.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if a series' length differs from `t`'s or
/// the image size is out of range; I/O errors name `path`.
pub fn plot_multipliers(
    path: impl AsRef<Path>,
    t: &[f64],
    multipliers: &[Series<'_>],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    for m in multipliers {
        check_lengths(path, ("t", t), (m.name, m.values))?;
    }
    let mut panel = Panel::new("", "t", "λ(t)");
    let mut notes = Vec::new();
    for m in multipliers {
        let label = format!("{} (max |λ| = {})", m.name, sci(max_abs(m.values)));
        panel.lines.push(time_line(
            Some(m.name),
            Some(label),
            t,
            m.values,
            opts.max_points,
            &mut notes,
        ));
    }
    panel.notes = notes;
    let mut fig = Figure {
        title: "Constraint multipliers".to_owned(),
        grid: (1, 1),
        panels: vec![panel],
    };
    let notes = render(path, opts, &mut fig)?;
    Ok(PlotReport {
        path: path.to_path_buf(),
        notes,
    })
}
