//! # marsden-optimize: `marsden optimize`
//!
//! Optimal control problems written in problem files (`[system] controls` and
//! `[optimal_control]`, checked by [`marsden_problem::problem::optimal_control`]) solved by
//! discrete mechanics and optimal control ([`marsden_control`], [OJM11]) with the file's rule,
//! and written up like `marsden run`: `trajectory.csv`, `controls.csv`, `summary.json` and
//! plots in the output directory.
//!
//! ```no_run
//! use marsden_problem::problem::optimal_control;
//! use marsden_problem::Overrides;
//!
//! let spec = optimal_control::load("examples/pendulum_swing_up.toml".as_ref(), &Overrides::default())?;
//! let outcome = marsden_optimize::run(&spec)?;
//! println!("{} after {} iterations", outcome.optimized.solution.cost, outcome.optimized.solution.iterations);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Map
//!
//! | module | concept |
//! |---|---|
//! | [`model`] | the file's forces and costs as the core's `ControlForce`, `RunningCost`, `FinalCost` |
//! | [`guess`] | the first iterate: zero-control simulation or straight line |
//! | [`solve`] | the spec as an `OptimalControl`, solved with the file's rule |
//! | [`balance`] | the per-step replay by the core integrator, the forced Noether balance |
//! | [`output`], [`plots`] | `trajectory.csv`, `controls.csv`, `summary.json`; the PNG plots |
//!
//! [OJM11]: marsden_control#references

pub mod balance;
pub mod error;
pub mod guess;
pub mod model;
pub mod output;
pub mod plots;
pub mod solve;

use marsden_problem::problem::optimal_control::OptimalControlSpec;

pub use error::OptimizeError;
pub use solve::{Optimized, optimize};

/// A finished `marsden optimize`: the solve and what was written.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The solve.
    pub optimized: Optimized,
    /// The files written into the output directory.
    pub files: Vec<String>,
    /// Plots that could not be drawn (the data files are written regardless).
    pub warnings: Vec<String>,
}

/// Solves the problem and writes its results into `spec.output.dir`; a solve that does not
/// converge writes its last iterate (status not `"converged"` in `summary.json`).
///
/// # Errors
/// [`OptimizeError::Setup`] before anything is written; [`OptimizeError::Write`] if a data
/// file cannot be written.
pub fn run(spec: &OptimalControlSpec) -> Result<Outcome, OptimizeError> {
    let optimized = optimize(spec)?;
    let dir = &spec.output.dir;
    std::fs::create_dir_all(dir).map_err(|e| OptimizeError::write(dir, e))?;
    let mut warnings = Vec::new();
    let plots = match spec.output.plots {
        false => Vec::new(),
        true => plots::draw(dir, spec, &optimized.solution).unwrap_or_else(|e| {
            warnings.push(format!("plots not drawn: {e}"));
            Vec::new()
        }),
    };
    let files = output::write(dir, spec, &optimized, &plots)?;
    Ok(Outcome {
        optimized,
        files,
        warnings,
    })
}
