//! Optimal control problems (`[optimal_control]`) from Python: checked and solved by
//! [`marsden_optimize`], the same as `marsden optimize`, returned as NumPy arrays and the
//! summary (nothing is written).

use marsden_optimize::OptimizeError;
use marsden_optimize::output::{self, status_name};
use marsden_problem::Overrides;
use marsden_problem::problem::optimal_control::{self, OptimalControlSpec};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::ProblemError;

fn spec_of(text: &str, origin: &str) -> PyResult<OptimalControlSpec> {
    optimal_control::from_toml_str(text, origin, &Overrides::default())
        .map_err(|d| ProblemError::new_err(d.to_string()))
}

/// What `check` says about an optimal control problem.
pub fn describe<'py>(py: Python<'py>, text: &str, origin: &str) -> PyResult<Bound<'py, PyDict>> {
    let spec = spec_of(text, origin)?;
    let d = PyDict::new(py);
    d.set_item("name", &spec.name)?;
    d.set_item("coordinates", &spec.coordinates)?;
    d.set_item("controls", &spec.controls)?;
    d.set_item("parameters", spec.parameters.clone())?;
    d.set_item("method", spec.method.to_string())?;
    d.set_item("h", (spec.t_end - spec.t0) / spec.steps as f64)?;
    d.set_item("steps", spec.steps)?;
    d.set_item("every", 1)?;
    d.set_item("sweep", py.None())?;
    d.set_item("sensitivity", false)?;
    d.set_item("optimal_control", true)?;
    Ok(d)
}

/// Solves the `[optimal_control]` problem of problem text: `t` (N + 1), `q` and `p`
/// (N + 1 × n), `u` (N σ × m, σ control values per step), `t_u` (their times), `cost`, `status`
/// and `summary` (JSON text, as `summary.json`).
#[pyfunction]
pub fn optimize<'py>(py: Python<'py>, text: &str, origin: &str) -> PyResult<Bound<'py, PyDict>> {
    let spec = spec_of(text, origin)?;
    let optimized = py
        .allow_threads(|| marsden_optimize::optimize(&spec))
        .map_err(|e| match e {
            OptimizeError::Setup(_) => ProblemError::new_err(e.to_string()),
            other => pyo3::exceptions::PyRuntimeError::new_err(other.to_string()),
        })?;
    let s = &optimized.solution;
    let d = PyDict::new(py);
    d.set_item("coordinates", &spec.coordinates)?;
    d.set_item("controls", &spec.controls)?;
    d.set_item("t", PyArray1::from_vec(py, s.t.clone()))?;
    d.set_item("q", matrix(&s.q).into_pyarray(py))?;
    d.set_item("p", matrix(&s.p).into_pyarray(py))?;
    d.set_item("u", matrix(&s.u).into_pyarray(py))?;
    d.set_item("t_u", PyArray1::from_vec(py, s.control_times.clone()))?;
    d.set_item("cost", s.cost)?;
    d.set_item("status", status_name(&s.status))?;
    let summary = serde_json::to_string(&output::summary(&spec, &optimized, Vec::new()))
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    d.set_item("summary", summary)?;
    Ok(d)
}

/// Rows of equal length as a matrix.
fn matrix(rows: &[Vec<f64>]) -> Array2<f64> {
    let width = rows.first().map_or(0, Vec::len);
    Array2::from_shape_fn((rows.len(), width), |(i, j)| rows[i][j])
}
