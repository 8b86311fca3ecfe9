//! The native half of `marsden.Simulation`: a run's checkpointed state, and a stretch of the
//! run continued from a state ([`marsden_spec::segment`]); the problem's initial state is
//! the one prepared when it was checked ([`crate::checked::CheckedProblem`]).

use std::path::PathBuf;

use marsden_spec::resume::{self, Found};
use marsden_spec::segment::{self, StretchEnd, StretchStart};
use marsden_spec::{Diagnostic, RunSpec, Store};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::{bad, convert, to_py, watched};

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

/// Where a stretch starts and where it ends.
pub struct Stretch {
    /// `(t, q, p)`: the state it continues from.
    pub state: (f64, Vec<f64>, Vec<f64>),
    /// After some steps, or at a time.
    pub end: StretchEnd,
}

/// The end of a stretch: after `steps` steps or at `t_end` (exactly one of them).
///
/// # Errors
/// Neither or both given.
pub fn stretch_end(steps: Option<usize>, t_end: Option<f64>) -> PyResult<StretchEnd> {
    match (steps, t_end) {
        (Some(n), None) => Ok(StretchEnd::Steps(n)),
        (None, Some(t)) => Ok(StretchEnd::Time(t)),
        _ => Err(bad(Diagnostic::new(
            "a stretch ends after `steps` or at `t_end`: give exactly one",
        ))),
    }
}

/// The run of `spec` continued as `stretch` asks, kept in memory, as `solve` returns it. The
/// initial state differs from the problem's, so the run prepares it.
pub fn stretch_of<'py>(
    py: Python<'py>,
    spec: &RunSpec,
    stretch: Stretch,
    progress: Option<Py<PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (t, q, p) = stretch.state;
    let spec = segment::continued(spec, StretchStart { t, q, p }, stretch.end).map_err(bad)?;
    let outcome = watched(py, progress, |controls| {
        marsden_spec::execute(&spec, Store::Memory, controls)
    })?;
    convert::outcome(py, &outcome.map_err(to_py)?)
}
