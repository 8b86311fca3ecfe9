//! A problem checked once: `check` validates problem text and prepares its initial state, and
//! the [`CheckedProblem`] it returns is what Python's `Problem` holds, so that `solve()`, its
//! sweep and its `Simulation` run it without reading the text again or preparing its initial
//! state again ([`Prepared`]). Text that changed (a `[sensitivity]` table or a sweep added from
//! Python) is another problem, checked by the functions that take text.

use std::borrow::Cow;

use marsden_spec::segment;
use marsden_spec::{Diagnostic, Overrides, Prepared, RunSpec};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::simulation::{Stretch, stretch_end, stretch_of};
use crate::{SolveRequest, bad, convert, every_override, optimize, sweep_of, to_py, watched};

/// Problem text, validated and with its initial state prepared (an `[optimal_control]` problem
/// is only described: `optimize` solves it from its text).
#[pyclass(frozen, module = "marsden._native")]
pub struct CheckedProblem {
    /// What Python's `Problem` shows: name, coordinates, parameters, method, `h`, steps, the
    /// sweep's target and members, whether it has `[sensitivity]`.
    info: Py<PyDict>,
    /// `None` for an `[optimal_control]` problem.
    prepared: Option<Prepared>,
}

/// Checks problem text (`origin` names it in messages): validated, its initial state prepared
/// and checked, described in [`CheckedProblem::info`].
#[pyfunction]
pub fn check(py: Python<'_>, text: &str, origin: &str) -> PyResult<CheckedProblem> {
    if marsden_problem::problem::optimal_control::is_optimal_control(text) {
        return Ok(CheckedProblem {
            info: optimize::describe(py, text, origin)?.unbind(),
            prepared: None,
        });
    }
    let spec = marsden_spec::from_toml_str(text, origin, &Overrides::default()).map_err(bad)?;
    let prepared = Prepared::new(spec).map_err(bad)?;
    Ok(CheckedProblem {
        info: describe(py, prepared.spec())?.unbind(),
        prepared: Some(prepared),
    })
}

/// The description of a problem Python's `Problem` shows.
fn describe<'py>(py: Python<'py>, spec: &RunSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", &spec.name)?;
    d.set_item("coordinates", &spec.system.coordinates)?;
    d.set_item("parameters", spec.system.parameters.clone())?;
    d.set_item("method", spec.integrator.method.to_string())?;
    d.set_item("h", spec.integrator.grid.h)?;
    d.set_item("steps", spec.integrator.grid.steps)?;
    d.set_item("every", spec.output.every)?;
    d.set_item("lagrangian", spec.system.lagrangian.describe())?;
    let sweep = spec.sweep.as_ref().map(|s| {
        let members: Vec<Vec<f64>> = (0..s.count()).map(|k| s.values_of(k)).collect();
        (s.label(), members)
    });
    d.set_item("sweep", sweep)?;
    d.set_item("sensitivity", spec.sensitivity.is_some())?;
    Ok(d)
}

#[pymethods]
impl CheckedProblem {
    /// The description made when the problem was checked (see [`check`]).
    #[getter]
    fn info(&self, py: Python<'_>) -> Py<PyDict> {
        self.info.clone_ref(py)
    }

    /// Runs the problem as the function `solve` runs its text, from the prepared state; the
    /// overrides are applied to a copy of the checked problem.
    #[pyo3(signature = (every=None, progress=None, dir=None, checkpoint_every=None))]
    fn solve<'py>(
        &self,
        py: Python<'py>,
        every: Option<usize>,
        progress: Option<Py<PyAny>>,
        dir: Option<std::path::PathBuf>,
        checkpoint_every: Option<u64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let request = SolveRequest::new(every, dir, checkpoint_every)?;
        let held = self.prepared()?;
        let overridden;
        let prepared = match request.overrides == Overrides::default() {
            true => held,
            false => {
                overridden = held.with_overrides(&request.overrides).map_err(bad)?;
                &overridden
            }
        };
        let outcome = watched(py, progress, |controls| {
            prepared.execute(request.store, controls)
        })?;
        convert::outcome(py, &outcome.map_err(to_py)?)
    }

    /// Runs every member of the problem's `[sweep]`, as the function `sweep` runs its text.
    #[pyo3(signature = (every=None, threads=None))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        every: Option<usize>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyList>> {
        let base = self.overridden(every_override(every)?)?;
        sweep_of(py, &base, threads)
    }

    /// The complete initial state `(t0, q, p)`, as prepared when the problem was checked;
    /// refused for what cannot be stepped ([`segment::steppable`]).
    fn initial_state(&self) -> PyResult<(f64, Vec<f64>, Vec<f64>)> {
        let prepared = self.prepared()?;
        segment::steppable(prepared.spec()).map_err(bad)?;
        let start = prepared.start();
        Ok((start.t, start.q.clone(), start.p.clone()))
    }

    /// The run continued from `(t, q, p)` for `steps` steps or until `t_end` (exactly one of
    /// them), kept in memory, as `solve` returns it.
    #[pyo3(signature = (state, steps=None, t_end=None, every=None, progress=None))]
    fn stretch<'py>(
        &self,
        py: Python<'py>,
        state: (f64, Vec<f64>, Vec<f64>),
        steps: Option<usize>,
        t_end: Option<f64>,
        every: Option<usize>,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let end = stretch_end(steps, t_end)?;
        let spec = self.overridden(every_override(every)?)?;
        let stretch = Stretch { state, end };
        stretch_of(py, &spec, stretch, progress)
    }
}

impl CheckedProblem {
    /// The prepared problem; refused for an `[optimal_control]` one (Python's `Problem` refuses
    /// it before asking).
    fn prepared(&self) -> PyResult<&Prepared> {
        self.prepared.as_ref().ok_or_else(|| {
            bad(Diagnostic::new(
                "this problem has an [optimal_control] table: solve it with problem.optimize()",
            ))
        })
    }

    /// The checked problem with `overrides` (itself, not a copy, without any).
    fn overridden(&self, overrides: Overrides) -> PyResult<Cow<'_, RunSpec>> {
        let spec = self.prepared()?.spec();
        match overrides == Overrides::default() {
            true => Ok(Cow::Borrowed(spec)),
            false => spec.with_overrides(&overrides).map(Cow::Owned).map_err(bad),
        }
    }
}
