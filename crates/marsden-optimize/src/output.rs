//! The files of `marsden optimize`: `trajectory.csv` (every node: `t`, `q_*`, `p_*`),
//! `controls.csv` (`t_k` and one column per control, `u_k` acting on `[t_k, t_{k+1}]`) and
//! `summary.json`, whose `optimal_control` object says how the solve ended.

use std::path::Path;

use marsden::numerics::dense::max_or_nan;
use marsden_control::{Failure, Infeasibility, Solution, Status};
use marsden_io::{Column, Table, write_csv};
use marsden_problem::problem::optimal_control::OptimalControlSpec;
use serde::Serialize;

use crate::error::OptimizeError;
use crate::solve::Optimized;

/// The trajectory file.
pub const TRAJECTORY_CSV: &str = "trajectory.csv";
/// The controls file.
pub const CONTROLS_CSV: &str = "controls.csv";
/// The summary file.
pub const SUMMARY_JSON: &str = "summary.json";

/// The status as `summary.json` spells it: `"converged"`, `"failed"`, `"infeasible"` or
/// `"iteration limit"`.
pub fn status_name(status: &Status) -> &'static str {
    match status {
        Status::Converged => "converged",
        Status::Failed(_) => "failed",
        Status::Infeasible(_) => "infeasible",
        Status::IterationLimit => "iteration limit",
    }
}

/// Why a solve that did not converge stopped, in words (`None` for converged and for the
/// iteration limit, whose status says it all).
pub fn failure_text(spec: &OptimalControlSpec, status: &Status) -> Option<String> {
    match status {
        Status::Infeasible(i) => Some(infeasibility_text(spec, i)),
        Status::Failed(Failure::NonFinite) => {
            Some("a cost, constraint or derivative was not finite".to_owned())
        }
        Status::Failed(Failure::LineSearch { step }) => Some(format!(
            "the line search found no decrease down to step {step:e}"
        )),
        Status::Failed(Failure::Subproblem {
            status,
            regularization,
        }) => Some(format!(
            "the QP subproblem failed ({status}) with regularization {regularization:e}"
        )),
        _ => None,
    }
}

/// The infeasible subproblem in words: where, and which bounds and path inequalities its
/// certificate uses.
fn infeasibility_text(spec: &OptimalControlSpec, i: &Infeasibility) -> String {
    let at = match i.iteration {
        0 => "at the first iterate".to_owned(),
        k => format!("at SQP iteration {k}"),
    };
    let names = (i.controls.iter().filter_map(|&j| spec.controls.get(j)))
        .chain(
            i.coordinates
                .iter()
                .filter_map(|&j| spec.coordinates.get(j)),
        )
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>();
    let paths = (i.path.iter().filter_map(|&j| spec.path_texts.get(j)))
        .map(|g| format!("`{g} <= 0`"))
        .collect::<Vec<_>>();
    let bounds = match (names.is_empty(), paths.is_empty()) {
        (true, true) => "no bound: the boundary conditions contradict the dynamics".to_owned(),
        (false, true) => format!("the bounds on {}", names.join(", ")),
        (true, false) => format!("the path inequalities {}", paths.join(", ")),
        (false, false) => format!(
            "the bounds on {} and the path inequalities {}",
            names.join(", "),
            paths.join(", ")
        ),
    };
    let elastic = match i.elastic_steps {
        0 => "no elastic step could reduce the violation".to_owned(),
        1 => "1 elastic step reduced the violation, then none could".to_owned(),
        k => format!("{k} elastic steps reduced the violation, then none could"),
    };
    format!(
        "the linearised dynamics and boundary conditions {at} cannot be met within the bounds \
         (a checked certificate of the QP solver, using {bounds}); {elastic} (a local minimum \
         of the violation: `constraint_violation`); loosen those bounds or inequalities, \
         lengthen t_end, or start from another guess"
    )
}

/// `summary.json`.
#[derive(Debug, Serialize)]
pub struct Summary<'a> {
    /// The run's name.
    pub name: &'a str,
    /// The problem file.
    pub problem_file: String,
    /// The rule.
    pub method: &'a str,
    /// Steps `N`.
    pub steps: usize,
    /// Initial time.
    pub t0: f64,
    /// Final time.
    pub t_end: f64,
    /// Coordinate names.
    pub coordinates: &'a [String],
    /// Control names.
    pub controls: &'a [String],
    /// How the solve ended, and its checks.
    pub optimal_control: OptimalControlSummary<'a>,
    /// One record per SQP iteration.
    pub history: Vec<HistoryRecord>,
    /// The files written, relative to the output directory.
    pub files: Vec<String>,
}

/// The `optimal_control` object of `summary.json`.
#[derive(Debug, Serialize)]
pub struct OptimalControlSummary<'a> {
    /// `"converged"`, `"failed"`, `"infeasible"` or `"iteration limit"`.
    pub status: &'static str,
    /// Why a failed solve stopped.
    pub failure: Option<String>,
    /// Whether the files hold the last iterate of a solve that did not converge.
    pub last_iterate: bool,
    /// The discrete cost `J_d` at the returned iterate.
    pub cost: f64,
    /// SQP iterations taken.
    pub iterations: usize,
    /// The KKT residual.
    pub kkt_residual: f64,
    /// The largest violation of the forced DEL and boundary constraints (`|c_i|`) and of the
    /// path inequalities (`max(0, g_i)`).
    pub constraint_violation: f64,
    /// Per path inequality (`null` when the file has none): its largest value over the
    /// points where it is imposed, how many of them it is active at, and its largest
    /// multiplier.
    pub path: Option<Vec<PathSummary>>,
    /// Per symmetry: `{momentum_change, total_impulse, total_defect, max_defect, steps}` of
    /// the forced Noether balance ([`crate::balance`]); `null` when the file declares none.
    pub noether_balance: Option<serde_json::Map<String, serde_json::Value>>,
    /// `max |(q, p)_{k+1} − Φ_k(q_k, p_k)|` over the steps replayed by the core integrator
    /// with the returned controls (`null` if a step failed).
    pub replay_defect: Option<f64>,
    /// How the first iterate was made.
    pub guess: &'static str,
    /// Control values per step: 1 (piecewise constant), or one per quadrature node of a
    /// Galerkin rule (the rows of `controls.csv` are then `t_k + c_i h`).
    pub controls_per_step: usize,
    /// The nodes `c_i` of the control values within a step (`[0]` for one value per step).
    pub control_nodes: &'a [f64],
}

/// One path inequality `g ≤ 0` at the returned iterate.
#[derive(Debug, Serialize)]
pub struct PathSummary {
    /// The expression `g` as written.
    pub expression: String,
    /// `max g` over the points (≤ 0 where met).
    pub max: f64,
    /// The points where `g ≥ −10⁻⁸` (the inequality is active there).
    pub active_points: usize,
    /// The points where it is imposed (`N` × control values per step).
    pub points: usize,
    /// Its largest multiplier (`≥ 0`; 0 where inactive everywhere).
    pub max_multiplier: f64,
}

/// Each path inequality's summary, from the values and multipliers of the solution.
pub fn path_summary(spec: &OptimalControlSpec, s: &Solution) -> Option<Vec<PathSummary>> {
    let count = spec.path_texts.len();
    if count == 0 {
        return None;
    }
    let column = |rows: &[Vec<f64>], i: usize| -> Vec<f64> {
        rows.iter()
            .flat_map(|step| step.iter().skip(i).step_by(count).copied())
            .collect()
    };
    let summaries = (spec.path_texts.iter().enumerate())
        .map(|(i, expression)| {
            let values = column(&s.path_values, i);
            let multipliers = column(&s.path_multipliers, i);
            PathSummary {
                expression: expression.clone(),
                max: values.iter().copied().fold(f64::NEG_INFINITY, max_or_nan),
                active_points: values.iter().filter(|&&g| g >= -1e-8).count(),
                points: values.len(),
                max_multiplier: multipliers.iter().copied().fold(0.0, max_or_nan),
            }
        })
        .collect();
    Some(summaries)
}

/// One SQP iteration.
#[derive(Debug, Serialize)]
pub struct HistoryRecord {
    /// Cost.
    pub cost: f64,
    /// `max |c_i|`.
    pub violation: f64,
    /// KKT residual.
    pub kkt: f64,
    /// Accepted step length.
    pub step: f64,
    /// Hessian regularisation.
    pub regularization: f64,
}

/// Writes the three files into `dir` (created if needed); returns their names.
///
/// # Errors
/// [`OptimizeError::Write`] naming the file.
pub fn write(
    dir: &Path,
    spec: &OptimalControlSpec,
    optimized: &Optimized,
    plots: &[String],
) -> Result<Vec<String>, OptimizeError> {
    std::fs::create_dir_all(dir).map_err(|e| OptimizeError::write(dir, e))?;
    let s = &optimized.solution;
    let trajectory = trajectory_table(spec, s)?;
    let path = dir.join(TRAJECTORY_CSV);
    write_csv(&path, &trajectory).map_err(|e| OptimizeError::write(&path, e))?;
    let controls = controls_table(spec, s)?;
    let path = dir.join(CONTROLS_CSV);
    write_csv(&path, &controls).map_err(|e| OptimizeError::write(&path, e))?;
    let mut files = vec![
        TRAJECTORY_CSV.to_owned(),
        CONTROLS_CSV.to_owned(),
        SUMMARY_JSON.to_owned(),
    ];
    files.extend(plots.iter().cloned());
    let summary = summary(spec, optimized, files.clone());
    let text = serde_json::to_string_pretty(&summary)
        .map_err(|e| OptimizeError::write(SUMMARY_JSON, e))?;
    let path = dir.join(SUMMARY_JSON);
    std::fs::write(&path, text + "\n").map_err(|e| OptimizeError::write(&path, e))?;
    Ok(files)
}

/// `t`, `q_<name>…`, `p_<name>…` at every node.
pub fn trajectory_table(spec: &OptimalControlSpec, s: &Solution) -> Result<Table, OptimizeError> {
    let mut columns = vec![Column::new("t", s.t.clone())];
    for (prefix, nodes) in [("q", &s.q), ("p", &s.p)] {
        for (i, name) in spec.coordinates.iter().enumerate() {
            let values = nodes.iter().map(|x| x[i]).collect();
            columns.push(Column::new(format!("{prefix}_{name}"), values));
        }
    }
    Table::new(columns).map_err(|e| OptimizeError::write(TRAJECTORY_CSV, e))
}

/// `t` and one column per control: a row per step (`t_k`), or per stage (`t_k + c_i h`).
pub fn controls_table(spec: &OptimalControlSpec, s: &Solution) -> Result<Table, OptimizeError> {
    let mut columns = vec![Column::new("t", s.control_times.clone())];
    for (j, name) in spec.controls.iter().enumerate() {
        columns.push(Column::new(
            name.clone(),
            s.u.iter().map(|u| u[j]).collect(),
        ));
    }
    Table::new(columns).map_err(|e| OptimizeError::write(CONTROLS_CSV, e))
}

/// The summary of a solve; `files` lists what was written beside it (none from Python).
pub fn summary<'a>(
    spec: &'a OptimalControlSpec,
    o: &'a Optimized,
    files: Vec<String>,
) -> Summary<'a> {
    let s = &o.solution;
    let noether = (!o.noether.is_empty()).then(|| {
        o.noether
            .iter()
            .map(|b| {
                let value = serde_json::json!({
                    "momentum_change": b.momentum_change,
                    "total_impulse": b.total_impulse,
                    "total_defect": b.total_defect,
                    "max_defect": b.max_defect,
                    "steps": b.steps,
                });
                (b.name.clone(), value)
            })
            .collect()
    });
    Summary {
        name: &spec.name,
        problem_file: spec.source.path().display().to_string(),
        method: &o.method,
        steps: spec.steps,
        t0: spec.t0,
        t_end: spec.t_end,
        coordinates: &spec.coordinates,
        controls: &spec.controls,
        optimal_control: OptimalControlSummary {
            status: status_name(&s.status),
            failure: failure_text(spec, &s.status),
            last_iterate: !s.converged(),
            cost: s.cost,
            iterations: s.iterations,
            kkt_residual: s.kkt_residual,
            constraint_violation: s.constraint_violation,
            path: path_summary(spec, s),
            noether_balance: noether,
            replay_defect: o.replay_defect,
            guess: o.guess,
            controls_per_step: s.stages.count(),
            control_nodes: &s.stages.times,
        },
        history: s
            .history
            .iter()
            .map(|it| HistoryRecord {
                cost: it.cost,
                violation: it.violation,
                kkt: it.kkt,
                step: it.step,
                regularization: it.regularization,
            })
            .collect(),
        files,
    }
}
