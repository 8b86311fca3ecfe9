//! The checked file as a DMOC problem ([`marsden_control::OptimalControl`]) solved with the
//! file's rule, and the checks read off the result ([`crate::balance`]).

use marsden::Rule;
use marsden_control::{
    Boundary, ControlError, Horizon, OptimalControl, Rate, Solution, SqpOptions, StagedControls,
};
use marsden_problem::problem::optimal_control::{EndSpec, OptimalControlSpec, RateSpec};

use crate::balance::{self, NoetherBalance};
use crate::error::OptimizeError;
use crate::guess;
use crate::model::{ExprControlForce, ExprCost, ExprFinalCost, ExprPath};

/// A solved (or stopped) optimal control problem.
#[derive(Debug, Clone, PartialEq)]
pub struct Optimized {
    /// The core's solution: status, cost, trajectory, controls, history.
    pub solution: Solution,
    /// The rule's name.
    pub method: String,
    /// How the first iterate was made (`"simulation"` or `"line"`).
    pub guess: &'static str,
    /// The forced Noether balance of each `[[system.symmetry]]`.
    pub noether: Vec<NoetherBalance>,
    /// The largest difference between the returned nodes and the core integrator's steps
    /// from them with the returned controls (`None` if a step failed).
    pub replay_defect: Option<f64>,
}

/// Solves the problem of `spec` with its rule.
///
/// A solve that does not converge is not an error: [`Optimized::solution`] carries its status
/// and last iterate.
///
/// # Errors
/// [`OptimizeError::Setup`] when the core refuses the problem (nothing solved).
pub fn optimize(spec: &OptimalControlSpec) -> Result<Optimized, OptimizeError> {
    let Some(rule) = spec.method.rule() else {
        return Err(ControlError::UnsupportedRule {
            rule: spec.method.to_string(),
            reason: "it has no discrete Lagrangian to transcribe".to_owned(),
        }
        .into());
    };
    // The rule chosen at run time is itself a rule (`marsden::discrete::rules::chosen`): one
    // compiled transcription for every rule, the same numbers as the concrete rule's.
    Ok(solve(spec, rule)?)
}

/// Solves with `rule`.
fn solve<R: Rule + StagedControls>(
    spec: &OptimalControlSpec,
    rule: &R,
) -> Result<Optimized, ControlError> {
    let force = ExprControlForce {
        programs: &spec.force,
        controls: spec.controls.len(),
    };
    let cost = ExprCost {
        program: &spec.cost,
    };
    let final_cost = ExprFinalCost {
        program: spec.final_cost.as_ref(),
        t_end: spec.t_end,
    };
    let horizon = Horizon {
        t0: spec.t0,
        duration: spec.t_end - spec.t0,
        steps: spec.steps,
    };
    let (start, end) = (boundary(&spec.start), boundary(&spec.end));
    let problem = OptimalControl::new(&spec.lagrangian, force, cost, horizon, start, end)?
        .with_final_cost(final_cost)
        .with_path(ExprPath {
            programs: &spec.path,
        });
    let problem = with_bounds(problem, spec)?;
    let grid = *problem.grid();
    let first = guess::initial(spec, &spec.lagrangian, &force, grid, rule);
    let problem = problem.with_guess(first.guess)?;
    let options = SqpOptions {
        kkt_tolerance: spec.solver.tolerance,
        constraint_tolerance: spec.solver.constraint_tolerance,
        max_iterations: spec.solver.max_iterations,
    };
    let solution = problem.solve(rule, &options)?;
    let parts = balance::Parts {
        lagrangian: &spec.lagrangian,
        force: &force,
        grid,
        rule,
    };
    Ok(Optimized {
        noether: balance::noether(&spec.symmetries, &parts, &solution),
        replay_defect: balance::replay(&parts, &solution),
        method: rule.name(),
        guess: first.kind,
        solution,
    })
}

type Problem<'a> = OptimalControl<
    &'a marsden_problem::model::ExprLagrangian,
    ExprControlForce<'a>,
    ExprCost<'a>,
    ExprFinalCost<'a>,
    ExprPath<'a>,
>;

fn with_bounds<'a>(
    problem: Problem<'a>,
    spec: &OptimalControlSpec,
) -> Result<Problem<'a>, ControlError> {
    let (u, q) = (&spec.control_bounds, &spec.state_bounds);
    let mut problem = problem.with_control_bounds(&u.lower, &u.upper)?;
    if q.any() {
        problem = problem.with_state_bounds(&q.lower, &q.upper)?;
    }
    Ok(problem)
}

/// The core's boundary from the checked one.
fn boundary(end: &EndSpec) -> Boundary {
    Boundary {
        q: end.q.clone(),
        rate: match &end.rate {
            RateSpec::Velocity(v) => Rate::Velocity(v.clone()),
            RateSpec::Momentum(p) => Rate::Momentum(p.clone()),
        },
    }
}
