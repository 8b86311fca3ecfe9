//! `[output] checkpoint_every`: which runs can be checkpointed and resumed.
//!
//! A checkpoint holds everything a run carries from one step to the next (the integrator's
//! carried data, the monitors' accumulators, the event detector, the writers' positions), so a
//! resumed run is bit for bit the uninterrupted one. That is built for the runs of a rule on a
//! Lagrangian (a catalog system, an expression `L` or `H`), with or without constraints and
//! events, forces and `[sensitivity]` (whose tangent run is checkpointed too); the other kinds
//! of run are refused here, before anything is written, with the
//! reason. A sweep checkpoints its finished members instead (each member reruns whole), so a
//! sweep of any kind of member takes `checkpoint_every` and is not checked here.

use std::ops::Range;

use super::check::Checker;
use super::method::Method;
use super::raw::RawProblem;
use super::spec::{LagrangianSpec, SystemSpec};
use crate::error::Diagnostic;

/// What the run does besides stepping, as far as checkpoints care.
#[derive(Debug, Clone, Copy)]
pub struct RunKind<'s> {
    /// The system.
    pub system: &'s SystemSpec,
    /// The integrator's method.
    pub method: &'s Method,
}

/// Refuses `checkpoint_every` (written or `--checkpoint-every`) for a run that cannot be
/// resumed bit for bit yet, pointing at the key.
///
/// # Errors
/// The reason, with the caret on `checkpoint_every` when the file wrote it.
pub fn refuse_unsupported(
    ck: &Checker<'_>,
    raw: &RawProblem,
    every: Option<usize>,
    run: RunKind<'_>,
) -> Result<(), Diagnostic> {
    let span = (raw.output.as_ref())
        .and_then(|o| o.get_ref().checkpoint_every.as_ref())
        .map(|c| c.span());
    refuse_at(ck, span, every, run)
}

/// [`refuse_unsupported`] with the caret on `span` (`None`: the value came from an override,
/// not from the file).
///
/// # Errors
/// As [`refuse_unsupported`].
pub fn refuse_at(
    ck: &Checker<'_>,
    span: Option<Range<usize>>,
    every: Option<usize>,
    run: RunKind<'_>,
) -> Result<(), Diagnostic> {
    if every.is_none() {
        return Ok(());
    }
    let Some(reason) = unsupported(run) else {
        return Ok(());
    };
    Err(ck
        .error(span, format!("checkpoints are not available for {reason}"))
        .note(
            "checkpoints are written for runs of a rule on a Lagrangian or a Hamiltonian, with \
             or without forces, constraints, events and [sensitivity]",
        )
        .help("remove `checkpoint_every` (or `--checkpoint-every`) to run it in one go"))
}

/// Why the run cannot be checkpointed (`None`: it can).
fn unsupported(run: RunKind<'_>) -> Option<&'static str> {
    let reason = match &run.system.lagrangian {
        LagrangianSpec::Discrete(_) => "a `discrete_lagrangian` system",
        LagrangianSpec::Rigid(_) => "a rigid body",
        LagrangianSpec::Multibody(_) => "a multibody system",
        _ if *run.method == Method::Exact => "the method `exact` (a shooting per step)",
        _ => return None,
    };
    Some(reason)
}
