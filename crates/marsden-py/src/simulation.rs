//! The native half of `marsden.Simulation`: the problem's initial state, a run's checkpointed
//! state, and a stretch of the run continued from a state ([`marsden_spec::run::segment`]).

use std::path::PathBuf;

use marsden_spec::run::resume::{self, Found};
use marsden_spec::run::segment::{self, StretchEnd, StretchStart};
use marsden_spec::{Diagnostic, Store};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{bad, convert, spec_of, to_py, watched};

/// The complete initial state of problem text: `(t0, q, p)` (`p` from `v` where the file
/// gives velocities, projected onto the constraints where it asks); refused for what cannot
/// be stepped ([`segment::steppable`]).
#[pyfunction]
pub fn initial_state(text: &str, origin: &str) -> PyResult<(f64, Vec<f64>, Vec<f64>)> {
    let spec = spec_of(text, origin, None)?;
    segment::steppable(&spec).map_err(bad)?;
    let start = marsden_spec::prepare(&spec).map_err(bad)?;
    Ok((start.t, start.q, start.p))
}

/// What a run's checkpoint in `dir` holds, to step on from: `(text, origin, t, q, p, steps)`.
/// Refused for a sweep's checkpoint, and for a run whose step size came from `--h` (its problem
/// text does not hold it, so a stretch would step with the file's).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn checkpoint_state(
    dir: PathBuf,
) -> PyResult<(String, String, f64, Vec<f64>, Vec<f64>, usize)> {
    let checkpoint = match resume::find(&dir, None).map_err(to_py)? {
        Found::Run(checkpoint) => checkpoint,
        Found::Sweep(_) => {
            return Err(bad(Diagnostic::new(format!(
                "{}: a sweep's checkpoint; a Simulation steps one run (resume the sweep with \
                 marsden.resume)",
                dir.display()
            ))));
        }
    };
    if let Some(h) = checkpoint.identity.h {
        return Err(bad(Diagnostic::new(format!(
            "the run in {} stepped with --h {h}, which its problem text does not hold: a \
             Simulation would step with the file's h (resume it with marsden.resume)",
            dir.display()
        ))));
    }
    let c = *checkpoint;
    Ok((c.identity.text, c.identity.absolute, c.t, c.q, c.p, c.step))
}

/// The run of problem text continued from `(t, q, p)` for `steps` steps or until `t_end`
/// (exactly one of them), kept in memory, as [`crate::solve`] returns it.
#[pyfunction]
#[pyo3(signature = (text, origin, state, steps=None, t_end=None, every=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn stretch<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    state: (f64, Vec<f64>, Vec<f64>),
    steps: Option<usize>,
    t_end: Option<f64>,
    every: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let end = match (steps, t_end) {
        (Some(n), None) => StretchEnd::Steps(n),
        (None, Some(t)) => StretchEnd::Time(t),
        _ => {
            return Err(bad(marsden_spec::Diagnostic::new(
                "a stretch ends after `steps` or at `t_end`: give exactly one",
            )));
        }
    };
    let spec = spec_of(text, origin, every)?;
    let (t, q, p) = state;
    let spec = segment::continued(&spec, StretchStart { t, q, p }, end).map_err(bad)?;
    let outcome = watched(py, progress, |controls| {
        marsden_spec::execute(&spec, Store::Memory, controls)
    })?;
    convert::outcome(py, &outcome.map_err(to_py)?)
}
