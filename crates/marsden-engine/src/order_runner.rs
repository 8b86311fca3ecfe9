//! The runs of an order study: the file's problem (Lagrangian, forces, initial data) built
//! once as in `marsden run` ([`crate::start::constrained_problem`]), one reference
//! solution `(q(T), p(T))` by the extrapolation integrator of [`marsden::discrete::exact`], then
//! [`marsden::studies::order::measure_order`] for each method, dispatched to its concrete rule.
//! A constrained problem's reference comes from constrained Lobatto IIIA–IIIB of order 8 at
//! small steps ([`marsden::studies::order::constrained_reference`]), with its accuracy estimate.

use marsden::studies::order::{
    CONSTRAINED_REFERENCE_METHOD, OrderOptions, OrderStudy, REFERENCE_PIECES,
    constrained_reference, measure_order, validated_reference,
};
use marsden::{Constraint, Force, Lagrangian, NewtonOptions, Problem};

use crate::start;
use marsden_problem::error::{Diagnostic, Error};
use marsden_problem::order::Plan;
use marsden_problem::problem::{Method, RunSpec};

/// The reference solution and one study per method (in the plan's order).
#[derive(Debug, Clone, PartialEq)]
pub struct Results {
    /// `(q(T), p(T))`.
    pub reference: (Vec<f64>, Vec<f64>),
    /// One study per method.
    pub studies: Vec<OrderStudy>,
    /// How the reference was computed.
    pub reference_source: String,
}

/// Largest difference, relative to `max(|q|, |p|, 1)`, between the two computations of the
/// reference (whole interval, pieces) for it to count as exact: far below any error an order
/// study measures, far above the flow's round-off (tolerance 1e-14 per substep).
const REFERENCE_AGREEMENT: f64 = 1e-9;

/// Steps of a constrained reference relative to the finest run of the study.
const REFERENCE_REFINEMENT: usize = 4;

/// Newton options of the runs: the file's, with the residual tolerance tightened to the order
/// study's (round-off, so that the solver's error does not mask the method's).
pub fn options(spec: &RunSpec) -> OrderOptions {
    let study = OrderOptions::default();
    let file = spec.integrator.newton;
    OrderOptions {
        newton: NewtonOptions {
            residual_tolerance: file.residual_tolerance.min(study.newton.residual_tolerance),
            ..file
        },
        ..study
    }
}

/// Runs the study of `plan` on the problem of `spec`, whose Lagrangian is `lagrangian`
/// ([`crate::engine::Engine::order_study`]).
///
/// # Errors
/// Status 2 for initial data the core rejects; status 1 if the reference solution cannot be
/// computed. A run that fails is a point with error `NaN` in its study, not an error.
pub fn study_with<L: Lagrangian>(
    spec: &RunSpec,
    plan: &Plan,
    lagrangian: &L,
) -> Result<Results, Error> {
    let system = &spec.system;
    // The force by reference: the same problem type as a run's, so the order study reuses
    // the run's compiled integrators.
    let force = system.force.on(lagrangian);
    let problem =
        start::constrained_problem(spec, lagrangian, &system.constraint)?.with_force(&force);
    let options = options(spec);
    // A failure of the reference is the reference integrator's, not the file's: it says
    // what happened to it and what to try, without blaming the Lagrangian.
    let failed = |e: marsden::Error| {
        Error::failed(
            Diagnostic::new(format!(
                "cannot compute the reference solution at T = {}: the reference integration \
                 failed ({e})",
                plan.t_end
            ))
            .note(
                "this is a failure of the reference (an extrapolated integration of the \
                 Euler–Lagrange equations), not a finding about the problem: the runs' \
                 errors cannot be measured without it",
            )
            .help("study a shorter interval (--t-end), or compare the methods with `marsden run`"),
        )
    };
    let (reference, reference_source) = if system.constraint.count() > 0 {
        let finest = plan.steps().last().copied().unwrap_or(1);
        let steps = REFERENCE_REFINEMENT * finest;
        let r =
            constrained_reference(&problem, plan.t_end, steps, options.newton).map_err(failed)?;
        let source = format!(
            "the constrained reference ({CONSTRAINED_REFERENCE_METHOD}, order 8, {} steps; \
             {} steps differ by {:.1e})",
            r.steps, steps, r.difference
        );
        ((r.q, r.p), source)
    } else {
        let r = validated_reference(&problem, plan.t_end).map_err(failed)?;
        let scale = r.q.iter().chain(&r.p).fold(1.0_f64, |m, x| m.max(x.abs()));
        let agrees = r.difference <= REFERENCE_AGREEMENT * scale;
        if !agrees {
            return Err(Error::failed(
                Diagnostic::new(format!(
                    "the reference solution at T = {} is not reliable: computed over the \
                     whole interval and in {REFERENCE_PIECES} pieces it differs by {:.3e}",
                    plan.t_end, r.difference
                ))
                .note("the errors of the runs cannot be measured against it")
                .help("study a shorter interval (--t-end)"),
            ));
        }
        let source = format!(
            "the extrapolated reference (two computations agree to {:.1e})",
            r.difference
        );
        ((r.q, r.p), source)
    };
    let (q, p) = &reference;
    let studies = plan
        .methods
        .iter()
        .map(|method| study(&problem, method, plan, q, p, &options))
        .collect::<Result<_, _>>()?;
    Ok(Results {
        reference,
        studies,
        reference_source,
    })
}

/// One method's study against the reference `(q(T), p(T))` (the method itself is the rule,
/// [`marsden::discrete::rules::chosen`]).
fn study<L: Lagrangian, F: Force, C: Constraint>(
    problem: &Problem<L, F, C>,
    method: &Method,
    plan: &Plan,
    q: &[f64],
    p: &[f64],
    options: &OrderOptions,
) -> Result<OrderStudy, Error>
where
    Problem<L, F, C>: Clone,
{
    let steps = plan.steps();
    let Some(rule) = method.rule() else {
        return Err(Error::bad_input(Diagnostic::new(format!(
            "`{method}` has no order to measure"
        ))));
    };
    measure_order(problem, rule, plan.t_end, &steps, q, p, options).map_err(|e| {
        Error::bad_input(Diagnostic::new(format!(
            "cannot set up the runs of {method}: {e}"
        )))
    })
}
