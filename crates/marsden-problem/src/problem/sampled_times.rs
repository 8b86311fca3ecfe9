//! `[output] times`: the run's state at chosen times, between grid points too.
//!
//! ```toml
//! [output]
//! times = [0.5, "pi", 10]     # numbers or constant expressions, strictly increasing,
//!                             # from t0 to the final time
//! exact_times = true          # optional: each reached by a step of its own size
//! ```
//!
//! Each time is sampled on the Hermite interpolant of the step it lies in, with `v = FL⁻¹(q,
//! p)` at the step's ends (the core's `marsden::run::events::TimeSampler`), or is the state
//! itself at a grid time; the samples go to `samples.csv` (or `samples.npy`) beside the
//! trajectory. Checked here, each with the caret on the offending value: the order, the range
//! of the run, and the kinds of run the interpolant is built for (a continuous Lagrangian or
//! Hamiltonian: not a file's own `discrete_lagrangian`, nor rigid bodies, nor a sweep).
//!
//! With `exact_times = true` a time inside a step is reached instead by a variational step of
//! its own size from the grid point before it, taken aside (the run goes on unchanged): the
//! sample is bit for bit the final state of the same file with `t_end` at that time, exact to
//! the method's order, for one extra step per time.

use marsden::TimeGrid;

use super::check::Checker;
use super::raw::RawProblem;
use super::spec::{LagrangianSpec, SystemSpec};
use crate::error::Diagnostic;

/// The checked `[output] times` of `raw` (empty when not written), for a run of `system` on
/// `grid`.
///
/// # Errors
/// A time out of order or outside `[t0, t_end]`, or a system without an interpolant, with the
/// caret on it.
pub fn times(
    ck: &Checker<'_>,
    raw: &RawProblem,
    system: &SystemSpec,
    grid: &TimeGrid,
) -> Result<Vec<f64>, Diagnostic> {
    let Some(list) = (raw.output.as_ref()).and_then(|o| o.get_ref().times.as_ref()) else {
        return Ok(Vec::new());
    };
    if let Some(kind) = without_interpolant(system) {
        return Err(ck
            .error(
                Some(list.span()),
                format!("`times` cannot be sampled for {kind}"),
            )
            .note(
                "the samples are read off the interpolant of each step, which needs the \
                 velocities v = FL⁻¹(q, p) of a continuous Lagrangian",
            )
            .help("remove `times`, and take the states at grid times from the trajectory"));
    }
    let (t0, t_end) = (grid.t0, grid.t_end());
    let mut times = Vec::with_capacity(list.get_ref().len());
    for written in list.get_ref() {
        let t = *written.get_ref();
        let span = Some(written.span());
        if let Some(&previous) = times.last()
            && t <= previous
        {
            return Err(ck
                .error(
                    span,
                    format!("the time {t} is not after the one before it, {previous}"),
                )
                .help("list the times in increasing order, each once"));
        }
        if t < t0 || t > t_end {
            return Err(ck
                .error(
                    span,
                    format!("the time {t} is outside the run, from t0 = {t0} to {t_end}"),
                )
                .help("give times between the initial and the final time"));
        }
        times.push(t);
    }
    Ok(times)
}

/// `[output] exact_times` (default false): each requested time inside a step reached by a
/// variational step of its own size from the grid point before it — the state a run ending at
/// that time reaches — rather than read off the step's interpolant.
///
/// # Errors
/// `exact_times = true` without `times`, with the caret on it.
pub fn exact(ck: &Checker<'_>, raw: &RawProblem, times: &[f64]) -> Result<bool, Diagnostic> {
    let Some(exact) = (raw.output.as_ref()).and_then(|o| o.get_ref().exact_times.as_ref()) else {
        return Ok(false);
    };
    if *exact.get_ref() && times.is_empty() {
        return Err(ck
            .error(
                Some(exact.span()),
                "`exact_times = true` needs the times to reach: `times` is not given",
            )
            .help("add `times = [...]` to [output], or remove `exact_times`"));
    }
    Ok(*exact.get_ref())
}

/// Which kind of system has no interpolant to sample (`None`: it has one).
fn without_interpolant(system: &SystemSpec) -> Option<&'static str> {
    match &system.lagrangian {
        LagrangianSpec::Discrete(_) => Some("a `discrete_lagrangian` system"),
        LagrangianSpec::Rigid(_) => Some("a rigid body"),
        LagrangianSpec::Multibody(_) => Some("a multibody system"),
        _ => None,
    }
}
