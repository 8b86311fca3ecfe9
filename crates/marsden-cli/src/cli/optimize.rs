//! `marsden optimize FILE [--out DIR] [--steps N] [--quiet]`: the file's `[optimal_control]`
//! problem solved by DMOC; `trajectory.csv`, `controls.csv`, `summary.json` and plots in the
//! output directory.
//!
//! Exit statuses: 0 converged; 1 the solve stopped without converging (the last iterate is
//! written, `summary.json` says why); 2 a bad problem file (nothing written).

use marsden_optimize::{OptimizeError, Outcome, output};
use marsden_problem::problem::optimal_control::{self, OptimalControlSpec};
use marsden_spec::{Diagnostic, Overrides};

use super::OptimizeArgs;
use crate::error::{CliError, Status};

/// Solves the problem file's optimal control problem and writes its results.
pub fn optimize(args: &OptimizeArgs) -> Result<Status, CliError> {
    let overrides = Overrides {
        steps: args.steps,
        h: None,
        out: args.out.clone(),
        checkpoint_every: None,
        every: None,
    };
    let spec = optimal_control::load(&args.file, &overrides)?;
    let outcome = marsden_optimize::run(&spec).map_err(|e| match e {
        OptimizeError::Setup(_) => CliError::bad_input(Diagnostic::new(e.to_string())),
        OptimizeError::Write { .. } | OptimizeError::Plot(_) => {
            CliError::failed(Diagnostic::new(e.to_string()))
        }
    })?;
    for warning in &outcome.warnings {
        eprintln!("warning: {warning}");
    }
    if !args.quiet {
        print!("{}", render(&spec, &outcome));
    }
    let s = &outcome.optimized.solution;
    if s.converged() {
        return Ok(Status::Completed);
    }
    eprintln!(
        "error: the optimal control solve ended with status \"{}\" after {} iterations",
        output::status_name(&s.status),
        s.iterations,
    );
    if let Some(reason) = output::failure_text(&spec, &s.status) {
        eprintln!("  = note: {reason}");
    }
    eprintln!(
        "  = note: the last iterate and summary.json (status \"{}\") are in {}",
        output::status_name(&s.status),
        spec.output.dir.display(),
    );
    Ok(Status::Failed)
}

/// The report on stdout.
fn render(spec: &OptimalControlSpec, outcome: &Outcome) -> String {
    let o = &outcome.optimized;
    let s = &o.solution;
    let mut text = format!(
        "{}: optimal control with {}, {} steps on [{}, {}], controls {}\n",
        spec.name,
        o.method,
        spec.steps,
        spec.t0,
        spec.t_end,
        spec.controls.join(", ")
    );
    let mut line = |key: &str, value: String| text.push_str(&format!("  {key:<22}{value}\n"));
    line(
        "status",
        format!(
            "{} after {} SQP iterations",
            output::status_name(&s.status),
            s.iterations
        ),
    );
    line("cost", format!("{:.10e}", s.cost));
    line("KKT residual", format!("{:.3e}", s.kkt_residual));
    line(
        "constraint violation",
        format!("{:.3e}", s.constraint_violation),
    );
    if let Some(d) = o.replay_defect {
        line("replay defect", format!("{d:.3e}"));
    }
    for g in output::path_summary(spec, s).unwrap_or_default() {
        line(
            &format!("path {} <= 0", g.expression),
            format!(
                "max {:.3e}, active at {} of {} points",
                g.max, g.active_points, g.points
            ),
        );
    }
    for b in &o.noether {
        line(
            &format!("Noether {}", b.name),
            format!("max defect {:.3e}", b.max_defect),
        );
    }
    line(
        "wrote",
        format!(
            "{} in {}",
            outcome.files.join(", "),
            spec.output.dir.display()
        ),
    );
    text
}
