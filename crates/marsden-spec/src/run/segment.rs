//! A run continued from a state: the problem of a file, started at `(t, q, p)` and run for a
//! number of steps or until a time — the stretch a stepping interface takes at each call
//! (Python's `Simulation.step` and `Simulation.integrate`).
//!
//! A two-point variational integrator is a map `(q_k, p_k) ↦ (q_{k+1}, p_{k+1})` of the
//! position–momentum form of the discrete Euler–Lagrange equations ([MW01] §1.5), so the state
//! `(t, q, p)` is all a continuation needs: a stretch started from the last state of the one
//! before it follows the same discrete flow, up to the Newton tolerance of the steps' solves
//! (a fresh start has no predictor history to start Newton's method from). A stretch that
//! ends at a time off the grid ends with one shorter, still variational step, as a file's
//! `t_end` does. The systems whose state is more than `(q, p)` — rigid bodies and multibody
//! systems (their attitudes), a replayed control table (indexed by the file's own grid) — and
//! the file's parts that span a whole run (`[sweep]`, `[sensitivity]`, `[output] times`,
//! checkpoints) are refused or left out, as [`continued`] says.
//!
//! [MW01]: marsden#references

use marsden::TimeGrid;

use crate::error::Diagnostic;
use crate::problem::{InitialData, RunSpec};

/// Where a stretch starts.
#[derive(Debug, Clone, PartialEq)]
pub struct StretchStart {
    /// Time.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Momenta.
    pub p: Vec<f64>,
}

/// Where a stretch ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StretchEnd {
    /// After this many steps of the file's `h`.
    Steps(usize),
    /// At this time exactly (the last step shorter when it is not a whole number of steps).
    Time(f64),
}

/// The run of `spec` from `start` to `end`, with the file's system, method, `h`, tolerance,
/// forces, constraints, symmetries, events and observables.
///
/// `[output] times` and checkpoints are left out (they belong to the file's whole run);
/// `every` is kept.
///
/// # Errors
/// A system whose state is more than `(q, p)`, a sweep, `[sensitivity]`, a control table; a
/// state of the wrong size or not finite; an end not after the start.
pub fn continued(
    spec: &RunSpec,
    start: StretchStart,
    end: StretchEnd,
) -> Result<RunSpec, Diagnostic> {
    steppable(spec)?;
    let n = spec.system.dof();
    if start.q.len() != n || start.p.len() != n {
        return Err(Diagnostic::new(format!(
            "the state has {} positions and {} momenta; the system has {n} coordinates",
            start.q.len(),
            start.p.len()
        )));
    }
    let values = std::iter::once(&start.t).chain(&start.q).chain(&start.p);
    if let Some(bad) = values.into_iter().find(|x| !x.is_finite()) {
        return Err(Diagnostic::new(format!(
            "the state to continue from is not finite ({bad})"
        )));
    }
    let h = spec.integrator.grid.h;
    let grid = match end {
        StretchEnd::Steps(0) => Err("a stretch takes at least one step".to_owned()),
        StretchEnd::Steps(steps) => TimeGrid::new(start.t, h, steps).map_err(|e| e.to_string()),
        StretchEnd::Time(t) if t <= start.t => Err(format!(
            "the time {t} is not after the current time {}",
            start.t
        )),
        StretchEnd::Time(t) => {
            TimeGrid::ending_exactly_at(start.t, t, h).map_err(|e| e.to_string())
        }
    }
    .map_err(Diagnostic::new)?;
    let mut continued = spec.clone();
    continued.initial.t0 = start.t;
    continued.initial.q = start.q;
    continued.initial.data = InitialData::Momentum(start.p);
    continued.initial.project = false;
    continued.integrator.grid = grid;
    continued.output.times.clear();
    continued.output.checkpoint_every = None;
    Ok(continued)
}

/// Whether the run of `spec` can be taken in stretches: not for a state beyond `(q, p)`, nor
/// for the parts of a file that describe a whole run.
///
/// # Errors
/// What cannot be stepped, and what to do instead.
pub fn steppable(spec: &RunSpec) -> Result<(), Diagnostic> {
    let reason = if spec.system.rigid().is_some() {
        Some("a rigid body (its state holds an attitude besides q and p)")
    } else if spec.system.multibody().is_some() {
        Some("a multibody system (its state holds the bodies' attitudes)")
    } else if spec.sweep.is_some() {
        Some("a sweep (run it with sweep())")
    } else if spec.sensitivity.is_some() {
        Some("[sensitivity] (the derivatives are of a whole run: use solve())")
    } else if spec.system.force.control_table().is_some() {
        Some("a control table (its rows are the file's own grid)")
    } else {
        None
    };
    match reason {
        Some(what) => Err(
            Diagnostic::new(format!("a simulation cannot be stepped for {what}"))
                .help("run the whole problem with solve()"),
        ),
        None => Ok(()),
    }
}
