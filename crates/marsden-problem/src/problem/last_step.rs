//! A `t_end` that is not a whole number of steps after `t₀`: the run ends with one shorter step
//! `h_N = t_end − t_{N−1}` ([`marsden::TimeGrid::ending_at`]), a variational step of its own
//! size, so the run stops where it was asked to and stays symplectic.
//!
//! The runs of a rule on a Lagrangian or a Hamiltonian take it (their integrators step with any
//! `h`, and the balances of forced runs discretise each step with its own size). The other kinds
//! are refused here, before anything is written, with the two whole grids beside `t_end`.

use marsden::TimeGrid;

use super::check::Checker;
use super::raw::RawProblem;
use super::spec::{LagrangianSpec, SystemSpec};
use crate::error::Diagnostic;

/// Refuses a grid with a shorter last step for a run that steps with one `h` only, pointing at
/// `t_end`.
///
/// # Errors
/// The reason, with the neighbouring whole grids as help.
pub fn refuse_unsupported(
    ck: &Checker<'_>,
    raw: &RawProblem,
    system: &SystemSpec,
    grid: &TimeGrid,
) -> Result<(), Diagnostic> {
    let Some(end) = grid.end else {
        return Ok(());
    };
    let Some(reason) = unsupported(raw, system) else {
        return Ok(());
    };
    let span = (raw.integrator.as_ref())
        .and_then(|i| i.get_ref().t_end.as_ref())
        .map(|t| t.span());
    let whole = grid.steps - 1;
    let (below, above) = (
        grid.t0 + whole as f64 * grid.h,
        grid.t0 + grid.steps as f64 * grid.h,
    );
    Err(ck
        .error(
            span,
            format!(
                "t_end = {end} is not a whole number of steps h = {} after t0 = {}, and {reason} \
                 takes no shorter last step",
                grid.h, grid.t0
            ),
        )
        .help(format!(
            "use t_end = {} or {}, or give `steps`",
            short(below),
            short(above)
        )))
}

/// `x` to 12 significant digits, without trailing zeros (`1.1`, not `1.1000000000000001`).
fn short(x: f64) -> String {
    let text = format!("{:.*e}", 11, x);
    text.parse::<f64>().map_or(text, |v| v.to_string())
}

/// Why the run cannot end with a shorter step (`None`: it can).
fn unsupported(raw: &RawProblem, system: &SystemSpec) -> Option<&'static str> {
    let table = (raw.system.as_ref()).is_some_and(|s| s.get_ref().control_table.is_some());
    let reason = match &system.lagrangian {
        LagrangianSpec::Discrete(_) => "a `discrete_lagrangian` system (written for one h)",
        LagrangianSpec::Rigid(_) => "a rigid body (its LGVI is built for one h)",
        LagrangianSpec::Multibody(_) => "a multibody system (its LGVI is built for one h)",
        _ if table => "a run replaying a control table (one row per step of h)",
        _ => return None,
    };
    Some(reason)
}
