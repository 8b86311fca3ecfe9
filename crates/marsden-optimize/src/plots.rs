//! The plots of `marsden optimize`, drawn with the project's plotting ([`marsden_io::plot`]):
//! the controls against time (piecewise constant, drawn as steps), the trajectory (positions
//! and momenta against time, phase portrait) and the convergence history of the SQP iteration
//! (KKT residual and constraint violation, log axis; cost).

use std::path::Path;

use marsden_control::Solution;
use marsden_io::plot::{
    LinePanel, PHASE_PORTRAIT_PNG, PhaseCurve, PlotOptions, Series, TIME_SERIES_PNG, plot_lines,
    plot_phase_portrait, plot_time_series,
};
use marsden_problem::problem::optimal_control::OptimalControlSpec;

use crate::error::OptimizeError;

/// The controls plot.
pub const CONTROLS_PNG: &str = "controls.png";
/// The convergence plot.
pub const CONVERGENCE_PNG: &str = "convergence.png";

/// Draws every plot into `dir`; returns the file names.
///
/// # Errors
/// [`OptimizeError::Plot`] naming the file.
pub fn draw(
    dir: &Path,
    spec: &OptimalControlSpec,
    s: &Solution,
) -> Result<Vec<String>, OptimizeError> {
    let opts = PlotOptions {
        angles: spec.output.angles.clone(),
        energy_conserved: false,
        ..PlotOptions::default()
    };
    controls(dir, spec, s, &opts)?;
    trajectory(dir, spec, s, &opts)?;
    convergence(dir, s, &opts)?;
    Ok([
        CONTROLS_PNG,
        TIME_SERIES_PNG,
        PHASE_PORTRAIT_PNG,
        CONVERGENCE_PNG,
    ]
    .map(str::to_owned)
    .to_vec())
}

/// `u_k` on `[t_k, t_{k+1}]`: each value drawn at both ends of its step; stage values (a
/// Galerkin rule) drawn at their times `t_k + c_i h`.
fn controls(
    dir: &Path,
    spec: &OptimalControlSpec,
    s: &Solution,
    opts: &PlotOptions,
) -> Result<(), OptimizeError> {
    let staged = s.stages.count() > 1;
    let (x, values): (Vec<f64>, Vec<Vec<f64>>) = match staged {
        true => (
            s.control_times.clone(),
            (0..spec.controls.len())
                .map(|j| s.u.iter().map(|u| u[j]).collect())
                .collect(),
        ),
        false => (
            (0..s.u.len()).flat_map(|k| [s.t[k], s.t[k + 1]]).collect(),
            (0..spec.controls.len())
                .map(|j| s.u.iter().flat_map(|u| [u[j], u[j]]).collect())
                .collect(),
        ),
    };
    let series: Vec<Series<'_>> = spec
        .controls
        .iter()
        .zip(&values)
        .map(|(name, values)| Series { name, values })
        .collect();
    let panel = LinePanel {
        title: match staged {
            true => "Controls (at the rule's quadrature nodes)",
            false => "Controls (piecewise constant per step)",
        },
        x_label: "t",
        y_label: "u",
        x: &x,
        series: &series,
        log: false,
    };
    plot_lines(dir.join(CONTROLS_PNG), "Optimal controls", &[panel], opts)?;
    Ok(())
}

fn trajectory(
    dir: &Path,
    spec: &OptimalControlSpec,
    s: &Solution,
    opts: &PlotOptions,
) -> Result<(), OptimizeError> {
    let column = |nodes: &[Vec<f64>], i: usize| -> Vec<f64> {
        nodes
            .iter()
            .map(|x| {
                let v = x[i];
                match opts.is_angle(&spec.coordinates[i]) {
                    true => wrap(v),
                    false => v,
                }
            })
            .collect()
    };
    let q: Vec<Vec<f64>> = (0..spec.coordinates.len())
        .map(|i| column(&s.q, i))
        .collect();
    let p: Vec<Vec<f64>> = (0..spec.coordinates.len())
        .map(|i| s.p.iter().map(|x| x[i]).collect())
        .collect();
    let q_names: Vec<String> = spec.coordinates.iter().map(|c| format!("q_{c}")).collect();
    let p_names: Vec<String> = spec.coordinates.iter().map(|c| format!("p_{c}")).collect();
    let qs: Vec<Series<'_>> = q_names
        .iter()
        .zip(&q)
        .map(|(name, values)| Series { name, values })
        .collect();
    let ps: Vec<Series<'_>> = p_names
        .iter()
        .zip(&p)
        .map(|(name, values)| Series { name, values })
        .collect();
    plot_time_series(dir.join(TIME_SERIES_PNG), &s.t, &qs, &ps, opts)?;
    let curves: Vec<PhaseCurve<'_>> = spec
        .coordinates
        .iter()
        .zip(q.iter().zip(&p))
        .map(|(name, (q, p))| PhaseCurve { name, q, p })
        .collect();
    plot_phase_portrait(dir.join(PHASE_PORTRAIT_PNG), &curves, opts)?;
    Ok(())
}

/// `x` wrapped to (−π, π].
fn wrap(x: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let y = x - tau * (x / tau).round();
    if y <= -std::f64::consts::PI {
        y + tau
    } else {
        y
    }
}

fn convergence(dir: &Path, s: &Solution, opts: &PlotOptions) -> Result<(), OptimizeError> {
    let x: Vec<f64> = (0..s.history.len()).map(|k| k as f64).collect();
    let kkt: Vec<f64> = s.history.iter().map(|it| it.kkt).collect();
    let violation: Vec<f64> = s.history.iter().map(|it| it.violation).collect();
    let cost: Vec<f64> = s.history.iter().map(|it| it.cost).collect();
    let residuals = [
        Series {
            name: "KKT residual",
            values: &kkt,
        },
        Series {
            name: "constraint violation",
            values: &violation,
        },
    ];
    let costs = [Series {
        name: "cost",
        values: &cost,
    }];
    let panels = [
        LinePanel {
            title: "Residuals",
            x_label: "SQP iteration",
            y_label: "residual",
            x: &x,
            series: &residuals,
            log: true,
        },
        LinePanel {
            title: "Cost",
            x_label: "SQP iteration",
            y_label: "J_d",
            x: &x,
            series: &costs,
            log: false,
        },
    ];
    plot_lines(dir.join(CONVERGENCE_PNG), "SQP convergence", &panels, opts)?;
    Ok(())
}
