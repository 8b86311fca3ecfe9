//! The horizon, rule, first iterate and solver options of `[optimal_control]`.

use toml::Spanned;

use super::raw::RawOptimalControl;
use super::{GuessKind, SolverSpec};
use crate::error::Diagnostic;
use crate::problem::check::Checker;
use crate::problem::method::Method;
use crate::problem::spec::Overrides;

/// `t0`, `t_end` and `steps` (`--steps` replaces `steps`).
pub(super) fn horizon(
    ck: &Checker<'_>,
    section: &Spanned<RawOptimalControl>,
    overrides: &Overrides,
) -> Result<(f64, f64, usize), Diagnostic> {
    let table = section.get_ref();
    let t0 = match &table.t0 {
        Some(t0) => ck.finite("t0", t0)?,
        None => 0.0,
    };
    let Some(t_end) = &table.t_end else {
        return Err(ck.error(
            Some(section.span()),
            "[optimal_control] needs the final time `t_end`",
        ));
    };
    let end = ck.finite("t_end", t_end)?;
    if end <= t0 {
        return Err(ck.error(
            Some(t_end.span()),
            format!("t_end = {end} is not after t0 = {t0}"),
        ));
    }
    let steps = match (overrides.steps, &table.steps) {
        (Some(n), _) => usize::try_from(n)
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| Diagnostic::new(format!("--steps {n}: need at least 1 step")))?,
        (None, Some(n)) => usize::try_from(*n.get_ref())
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| ck.error(Some(n.span()), "steps must be at least 1"))?,
        (None, None) => {
            return Err(ck.error(
                Some(section.span()),
                "[optimal_control] needs the number of `steps`",
            ));
        }
    };
    Ok((t0, end, steps))
}

/// The rule: any rule of the core (a two-point rule, a Galerkin rule with its control stages,
/// a composition); `exact` has no discrete Lagrangian to transcribe.
pub(super) fn method(
    ck: &Checker<'_>,
    raw: Option<&Spanned<String>>,
) -> Result<Method, Diagnostic> {
    let Some(name) = raw else {
        return Ok(Method::midpoint());
    };
    let method = Method::parse(name.get_ref()).map_err(|e| {
        ck.error(Some(name.span()), e.message)
            .suggest(e.suggestion.as_deref())
    })?;
    match method.rule() {
        Some(_) => Ok(method),
        None => Err(ck
            .error(
                Some(name.span()),
                format!("the method `{method}` cannot be used for optimal control"),
            )
            .note(
                "the DMOC transcription needs a discrete Lagrangian: midpoint, trapezoid, \
                 alpha-<a>, symmetrized-<a>, gauss-<s>, lobatto-<s>, galerkin-…, or a \
                 composition such as triple-jump-4(midpoint)",
            )),
    }
}

pub(super) fn guess(
    ck: &Checker<'_>,
    raw: Option<&Spanned<String>>,
) -> Result<GuessKind, Diagnostic> {
    match raw.map(|g| (g.get_ref().as_str(), g.span())) {
        None | Some(("simulation", _)) => Ok(GuessKind::Simulation),
        Some(("line", _)) => Ok(GuessKind::Line),
        Some((other, span)) => Err(ck
            .error(Some(span), format!("unknown guess `{other}`"))
            .suggest(marsden_expr::closest(other, ["simulation", "line"]))
            .note("guesses: simulation (zero controls from `start`), line (between the ends)")),
    }
}

pub(super) fn solver(
    ck: &Checker<'_>,
    table: &RawOptimalControl,
) -> Result<SolverSpec, Diagnostic> {
    let positive = |what: &str, v: &Option<Spanned<f64>>, default: f64| match v {
        None => Ok(default),
        Some(v) => {
            let x = ck.finite(what, v)?;
            if x > 0.0 {
                Ok(x)
            } else {
                Err(ck.error(Some(v.span()), format!("{what} must be positive ({x})")))
            }
        }
    };
    let max_iterations = match &table.max_iterations {
        None => 200,
        Some(n) => usize::try_from(*n.get_ref())
            .ok()
            .filter(|&n| n >= 1)
            .ok_or_else(|| ck.error(Some(n.span()), "max_iterations must be at least 1"))?,
    };
    Ok(SolverSpec {
        max_iterations,
        tolerance: positive("tolerance", &table.tolerance, 1e-8)?,
        constraint_tolerance: positive("constraint_tolerance", &table.constraint_tolerance, 1e-10)?,
    })
}
