//! The native half of the `marsden` Python package: problem text in, NumPy arrays out, with
//! the problem-file library ([`marsden_spec`]) doing all the work — the same parsing, checks,
//! runs and summaries as the `marsden` command, so a problem gives the same bits from both.
//!
//! The Python half (`python/marsden/`) builds problem text from keyword arguments or SymPy
//! expressions and wraps the dictionaries returned here in `Problem` and `Solution` objects.
//!
//! | module | what |
//! |---|---|
//! | [`watch`] | runs off the interpreter's lock; Ctrl-C sets the run's stop flag; progress to a Python function |
//! | [`convert`] | an [`marsden_spec::Outcome`] as a dictionary of NumPy arrays |
//! | [`optimize`] | `[optimal_control]` problems: checked, solved, returned as arrays |
//! | [`checked`] | `check`: a problem validated and prepared once ([`checked::CheckedProblem`]), run from there |
//! | [`simulation`] | `Simulation`: the initial state, stretches of a run continued from a state |
//! | this file | the functions Python calls and the `ProblemError` exception |

mod checked;
mod convert;
mod optimize;
mod simulation;
mod watch;

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use marsden_spec::catalog::Builtin;
use marsden_spec::sweep::{self as sweeps, SweepOptions};
use marsden_spec::{Controls, Diagnostic, Error, ErrorKind, Overrides, RunSpec, Store};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

create_exception!(
    _native,
    ProblemError,
    PyValueError,
    "A problem that cannot run: the message is the `marsden` command's, with the caret."
);

/// The Python exception for an error of the problem-file layer.
fn to_py(error: Error) -> PyErr {
    match error.kind {
        ErrorKind::BadInput => ProblemError::new_err(error.to_string()),
        ErrorKind::Failed => PyRuntimeError::new_err(error.to_string()),
    }
}

fn bad(diagnostic: Diagnostic) -> PyErr {
    to_py(Error::bad_input(diagnostic))
}

/// Validates problem text (`origin` names it in messages).
fn spec_of(text: &str, origin: &str, every: Option<usize>) -> PyResult<RunSpec> {
    marsden_spec::from_toml_str(text, origin, &every_override(every)?).map_err(bad)
}

/// The override of `every` a caller gave (`solve(every=…)`), refused if 0.
fn every_override(every: Option<usize>) -> PyResult<Overrides> {
    if every == Some(0) {
        return Err(bad(Diagnostic::new("`every` must be at least 1")));
    }
    Ok(Overrides {
        every: every.map(|e| e as u64),
        ..Overrides::default()
    })
}

/// What `solve` was asked besides the problem: where the samples go, and the overrides of
/// `every`, the output directory and the checkpoints.
struct SolveRequest {
    store: Store,
    overrides: Overrides,
}

impl SolveRequest {
    /// The request of `solve(every, dir, checkpoint_every)`.
    ///
    /// # Errors
    /// Checkpoints without a directory; an `every` of 0.
    fn new(
        every: Option<usize>,
        dir: Option<std::path::PathBuf>,
        checkpoint_every: Option<u64>,
    ) -> PyResult<SolveRequest> {
        if checkpoint_every.is_some() && dir.is_none() {
            return Err(bad(Diagnostic::new(
                "checkpoints are written into an output directory: give `dir` with `checkpoint_every`",
            )));
        }
        let store = match dir {
            Some(_) => Store::FilesAndMemory,
            None => Store::Memory,
        };
        let overrides = Overrides {
            out: dir,
            checkpoint_every,
            ..every_override(every)?
        };
        Ok(SolveRequest { store, overrides })
    }
}

/// Runs problem text with its samples in memory (every `every`-th step, the first and the
/// last), off the interpreter's lock; `progress`, a Python function, is called as
/// `progress(step, total, elapsed_seconds, done)` every few hundred steps and at the end (an
/// exception it raises stops the run and is raised here).
///
/// With `dir`, the files of `marsden run` are written there too, and with `checkpoint_every`
/// checkpoints of the run, which [`resume`] continues.
#[pyfunction]
#[pyo3(signature = (text, origin, every=None, progress=None, dir=None, checkpoint_every=None))]
fn solve<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    every: Option<usize>,
    progress: Option<Py<PyAny>>,
    dir: Option<std::path::PathBuf>,
    checkpoint_every: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let request = SolveRequest::new(every, dir, checkpoint_every)?;
    let spec = marsden_spec::from_toml_str(text, origin, &request.overrides).map_err(bad)?;
    let outcome = watched(py, progress, |controls| {
        marsden_spec::execute(&spec, request.store, controls)
    })?;
    convert::outcome(py, &outcome.map_err(to_py)?)
}

/// Runs `work` off the interpreter's lock with the caller's `progress` function and Ctrl-C
/// watched (see [`solve`]); the exception the function raised, if it raised one.
fn watched<T: Send>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    work: impl FnOnce(&Controls<'_>) -> T + Send,
) -> PyResult<T> {
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    let reporter = progress.map(|f| watch::Reporter::new(f, stop.clone()));
    let result = watch::off_the_lock(py, &stop, || {
        let report = |p: marsden_spec::Progress| {
            if let Some(r) = &reporter {
                r.report(p);
            }
        };
        let controls = Controls {
            progress: reporter
                .is_some()
                .then_some(&report as &dyn Fn(marsden_spec::Progress)),
            stop: Some(flag),
        };
        work(&controls)
    })?;
    match reporter.and_then(watch::Reporter::into_error) {
        Some(error) => Err(error),
        None => Ok(result),
    }
}

/// Continues the run (or the sweep) whose checkpoint is in `dir` to its end (as `marsden
/// resume`): its files in `dir` become those of the uninterrupted run. Returns the run's (or
/// the sweep's) `summary.json` as text.
#[pyfunction]
#[pyo3(signature = (dir, progress=None))]
fn resume(
    py: Python<'_>,
    dir: std::path::PathBuf,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    use marsden_spec::resume::{self, Found};
    let outcome = watched(py, progress, |controls| match resume::find(&dir, None)? {
        Found::Run(checkpoint) => resume::resume_from(&dir, *checkpoint, controls)
            .map(|_| marsden_spec::output::SUMMARY_JSON.to_owned()),
        Found::Sweep(checkpoint) => {
            let summary = format!("summary{}.json", checkpoint.shard().suffix());
            let options = SweepOptions {
                stop: controls.stop.clone(),
                ..SweepOptions::default()
            };
            resume::resume_sweep(&dir, *checkpoint, options).map(|_| summary)
        }
    })?;
    let summary = outcome.map_err(to_py)?;
    std::fs::read_to_string(dir.join(summary)).map_err(|e| {
        bad(Diagnostic::new(format!(
            "cannot read the summary of {}: {e}",
            dir.display()
        )))
    })
}

/// Runs every member of the `[sweep]` of problem text in parallel in this process, off the
/// interpreter's lock; one entry per member in order: its result, or the message of a member
/// that could not start (a string), or `None` if Ctrl-C stopped the sweep before it ran.
#[pyfunction]
#[pyo3(signature = (text, origin, every=None, threads=None))]
fn sweep<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    every: Option<usize>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let base = spec_of(text, origin, every)?;
    sweep_of(py, &base, threads)
}

/// The members of the `[sweep]` of `base`, run as [`sweep`] runs them.
fn sweep_of<'py>(
    py: Python<'py>,
    base: &RunSpec,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let Some(members) = base.sweep.clone() else {
        return Err(bad(Diagnostic::new("the problem has no [sweep]")));
    };
    let stop = Arc::new(AtomicBool::new(false));
    let options = SweepOptions {
        threads,
        stop: Some(stop.clone()),
        ..SweepOptions::default()
    };
    let overrides = Overrides::default();
    let results = watch::off_the_lock(py, &stop, || {
        sweeps::member_outcomes(base, &members, &overrides, &options)
    })?
    .map_err(to_py)?;
    let list = PyList::empty(py);
    for result in results {
        match result {
            Ok(Some(outcome)) => list.append(convert::outcome(py, &outcome)?)?,
            Ok(None) => list.append(py.None())?,
            Err(e) => list.append(e.to_string())?,
        }
    }
    Ok(list)
}

/// Runs member `k` of the `[sweep]` of problem text alone (what an executor's worker calls):
/// the same result as entry `k` of [`sweep`], bit for bit.
#[pyfunction]
#[pyo3(signature = (text, origin, k, every=None))]
fn member<'py>(
    py: Python<'py>,
    text: &str,
    origin: &str,
    k: usize,
    every: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let base = spec_of(text, origin, every)?;
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    let outcome = watch::off_the_lock(py, &stop, || {
        let controls = Controls {
            progress: None,
            stop: Some(flag),
        };
        sweeps::member_outcome(&base, &Overrides::default(), k, &controls)
    })?;
    convert::outcome(py, &outcome.map_err(to_py)?)
}

/// The catalog: one dictionary per system (name, summary, coordinates, parameters with their
/// defaults, the Lagrangian as a formula).
#[pyfunction]
fn systems<'py>(py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for b in Builtin::ALL {
        let d = PyDict::new(py);
        d.set_item("name", b.name())?;
        d.set_item("summary", b.summary())?;
        d.set_item("coordinates", b.coordinates(0))?;
        let defaults: Vec<(&str, f64)> =
            b.parameters().iter().map(|p| (p.name, p.default)).collect();
        d.set_item("parameters", defaults)?;
        d.set_item("needs_masses", b.needs_masses())?;
        d.set_item("lagrangian", b.formula())?;
        d.set_item("text", marsden_spec::report::systems::describe(b))?;
        list.append(d)?;
    }
    Ok(list)
}

/// The extension module `marsden._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("ProblemError", m.py().get_type::<ProblemError>())?;
    m.add_class::<checked::CheckedProblem>()?;
    m.add_function(wrap_pyfunction!(checked::check, m)?)?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(resume, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(member, m)?)?;
    m.add_function(wrap_pyfunction!(systems, m)?)?;
    m.add_function(wrap_pyfunction!(optimize::optimize, m)?)?;
    m.add_function(wrap_pyfunction!(simulation::checkpoint_state, m)?)?;
    Ok(())
}
