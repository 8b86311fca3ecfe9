//! Energy error against time.

use std::path::Path;

use super::options::{PlotOptions, PlotReport};
use super::prepare::{check_lengths, first_finite, max_abs, sci, time_line};
use super::render::{Figure, Panel, render};
use crate::error::Result;

/// Draws the relative energy error `(E(t) − E₀)/|E₀|` against `t` to a PNG at `path`.
///
/// `E₀` is the first finite energy (normally `E(t₀)`); if it is zero the absolute error
/// `E(t) − E₀` is drawn instead (noted). The axis is **linear with scientific tick labels**:
/// the sign and shape of the error (bounded oscillation vs. drift) is what a reader of a
/// variational integrator's output looks for, and the title states the maximum `|error|`, so
/// magnitudes from 1e-15 to 1e-3 read directly. Long series are reduced to min/max per bucket
/// so spikes survive.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if `t` and `energy` differ in length or the
/// image size is out of range; I/O errors name `path`.
pub fn plot_energy_error(
    path: impl AsRef<Path>,
    t: &[f64],
    energy: &[f64],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    check_lengths(path, ("t", t), ("energy", energy))?;
    let mut notes = Vec::new();
    let reference = first_finite(energy);
    let (errors, y_label, what) = match reference {
        Some((_, e0)) if e0 != 0.0 => (
            energy
                .iter()
                .map(|e| (e - e0) / e0.abs())
                .collect::<Vec<_>>(),
            "(E − E₀) / |E₀|",
            "|ΔE/E₀|",
        ),
        Some((_, e0)) => {
            notes.push("E₀ = 0: absolute error E − E₀ shown".to_owned());
            (energy.iter().map(|e| e - e0).collect(), "E − E₀", "|ΔE|")
        }
        None => (energy.to_vec(), "(E − E₀) / |E₀|", "|ΔE/E₀|"),
    };
    if let Some((i, _)) = reference.filter(|(i, _)| *i > 0) {
        notes.push(format!(
            "E(t₀) is not finite: E₀ is the energy at t = {}",
            t[i]
        ));
    }
    let line = time_line(None, None, t, &errors, opts.max_points, &mut notes);
    let mut panel = Panel::new("", "t", y_label);
    panel.lines.push(line);
    panel.notes = notes;
    let mut fig = Figure {
        title: format!("Energy error (max {what} = {})", sci(max_abs(&errors))),
        grid: (1, 1),
        panels: vec![panel],
    };
    let notes = render(path, opts, &mut fig)?;
    Ok(PlotReport {
        path: path.to_path_buf(),
        notes,
    })
}

/// Draws the discrete energy balance of a forced run to a PNG at `path`: above, the energy
/// change `E(t) − E₀` (`change`, at the times `t`) and the accumulated discrete work
/// `W(t) = Σ_{k<t/h} W_k` of the forces (`work`);
/// below, what the work does not account for, `E(t) − E₀ − W(t)` (the accumulated defect,
/// round-off for R12). Energy is not conserved in such a run, so no "energy error" is drawn.
///
/// # Errors
/// [`Error::PlotInput`](crate::Error::PlotInput) if the series differ in length or the image
/// size is out of range; I/O errors name `path`.
pub fn plot_energy_balance(
    path: impl AsRef<Path>,
    t: &[f64],
    change: &[f64],
    work: &[f64],
    opts: &PlotOptions,
) -> Result<PlotReport> {
    let path = path.as_ref();
    check_lengths(path, ("t", t), ("energy change", change))?;
    check_lengths(path, ("t", t), ("work", work))?;
    let unaccounted: Vec<f64> = change.iter().zip(work).map(|(e, w)| e - w).collect();
    let mut notes = Vec::new();
    let mut top = Panel::new("Energy change and work of the forces", "t", "energy");
    for (name, values) in [("E − E₀", change), ("work W", work)] {
        let label = Some(name.to_owned());
        let line = time_line(Some(name), label, t, values, opts.max_points, &mut notes);
        top.lines.push(line);
    }
    top.notes = notes;
    let mut notes = Vec::new();
    let name = "E − E₀ − W";
    let line = time_line(
        Some(name),
        None,
        t,
        &unaccounted,
        opts.max_points,
        &mut notes,
    );
    let mut bottom = Panel::new("Not accounted for by the work", "t", name);
    bottom.lines.push(line);
    bottom.notes = notes;
    let mut fig = Figure {
        title: format!(
            "Energy balance (max |E − E₀ − W| = {})",
            sci(max_abs(&unaccounted))
        ),
        grid: (2, 1),
        panels: vec![top, bottom],
    };
    let notes = render(path, opts, &mut fig)?;
    Ok(PlotReport {
        path: path.to_path_buf(),
        notes,
    })
}
