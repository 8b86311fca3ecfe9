//! A run's [`Outcome`] as the dictionary the Python `Solution` is made from: the samples as
//! NumPy arrays (one row per stored sample; `q`, `p` and `v` with one column per coordinate,
//! the multipliers with one per constraint; a rigid body's attitude `R` as `samples × 3 × 3`
//! and body momentum `Pi` as `samples × 3`; jointed bodies' `attitudes` as
//! `samples × bodies × 3 × 3` and `body_momenta` as `samples × 3·bodies`),
//! `summary.json`'s text, the status, the error message and the warnings; with
//! `[sensitivity]`, the stored Jacobians as a `samples × 2n × columns` array; the observables
//! by name, and the events' located crossings by event name.

use marsden_spec::EventSamples;
use marsden_spec::SampledStates;
use marsden_spec::{Outcome, Samples};
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The dictionary of `outcome` (empty arrays if nothing was stored).
pub fn outcome<'py>(py: Python<'py>, outcome: &Outcome) -> PyResult<Bound<'py, PyDict>> {
    let samples = outcome.samples.clone().unwrap_or_default();
    let d = PyDict::new(py);
    d.set_item("coordinates", &samples.coordinates)?;
    d.set_item("q", rows(py, &samples.q, samples.len()))?;
    d.set_item("p", rows(py, &samples.p, samples.len()))?;
    d.set_item("v", rows(py, &samples.v, samples.len()))?;
    d.set_item("multipliers", rows(py, &samples.lambda, samples.len()))?;
    // A rigid body: `R` as `samples × 3 × 3`, `Π` as `samples × 3` (absent otherwise).
    match samples.attitude.len() {
        9 => {
            let attitude = &samples.attitude;
            let at = |(k, i, j): (usize, usize, usize)| attitude[3 * i + j][k];
            let r = Array3::from_shape_fn((samples.len(), 3, 3), at).into_pyarray(py);
            d.set_item("R", r)?;
            d.set_item("Pi", rows(py, &samples.body_momentum, samples.len()))?;
        }
        _ => {
            d.set_item("R", py.None())?;
            d.set_item("Pi", py.None())?;
        }
    }
    // Jointed bodies: every body's `R` as `samples × bodies × 3 × 3`, `Π` as
    // `samples × 3·bodies` (the Python side splits them by body).
    if let Some(bodies) = (outcome.summary.multibody.as_ref()).map(|m| m.bodies) {
        let attitude = &samples.attitude;
        let at = |(k, b, i, j): (usize, usize, usize, usize)| attitude[9 * b + 3 * i + j][k];
        let r = numpy::ndarray::Array4::from_shape_fn((samples.len(), bodies, 3, 3), at);
        d.set_item("attitudes", r.into_pyarray(py))?;
        d.set_item(
            "body_momenta",
            rows(py, &samples.body_momentum, samples.len()),
        )?;
    }
    let Samples {
        t,
        energy,
        momenta,
        constraint_residual,
        constraint_velocity_residual,
        observables,
        ..
    } = samples;
    let named = PyDict::new(py);
    for (name, values) in observables {
        named.set_item(name, PyArray1::from_vec(py, values))?;
    }
    d.set_item("observables", named)?;
    d.set_item("events", events(py, outcome.events.as_ref())?)?;
    d.set_item("at_times", at_times(py, outcome.sampled.as_ref())?)?;
    d.set_item("t", PyArray1::from_vec(py, t))?;
    d.set_item("energy", PyArray1::from_vec(py, energy))?;
    let maps = PyDict::new(py);
    for (name, values) in momenta {
        maps.set_item(name, PyArray1::from_vec(py, values))?;
    }
    d.set_item("momenta", maps)?;
    d.set_item(
        "constraint_residual",
        constraint_residual.map(|r| PyArray1::from_vec(py, r)),
    )?;
    d.set_item(
        "constraint_velocity_residual",
        constraint_velocity_residual.map(|r| PyArray1::from_vec(py, r)),
    )?;
    let summary = outcome
        .summary
        .to_json()
        .map_err(pyo3::exceptions::PyRuntimeError::new_err)?;
    d.set_item("summary", summary)?;
    d.set_item("status", &outcome.summary.status_text)?;
    d.set_item("error", outcome.summary.error.clone())?;
    d.set_item("warnings", outcome.warnings.clone())?;
    let jacobians = (outcome.summary.sensitivity.as_ref())
        .zip(outcome.sensitivity.as_ref())
        .map(|(block, samples)| sensitivity(py, &block.columns, samples))
        .transpose()?;
    d.set_item("sensitivity", jacobians)?;
    Ok(d)
}

/// The located crossings by event name: `{name: {"t": (k,), "q": (k × n), "p": (k × n)}}`, in
/// the file's order (an event that never fired has empty arrays).
fn events<'py>(py: Python<'py>, records: Option<&EventSamples>) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let Some(records) = records else {
        return Ok(d);
    };
    for (i, name) in records.names.iter().enumerate() {
        let mine: Vec<usize> = (0..records.len())
            .filter(|&k| records.event[k] == i)
            .collect();
        let pick = |columns: &[Vec<f64>]| -> Vec<Vec<f64>> {
            (columns.iter())
                .map(|c| mine.iter().map(|&k| c[k]).collect())
                .collect()
        };
        let one = PyDict::new(py);
        let t: Vec<f64> = mine.iter().map(|&k| records.t[k]).collect();
        one.set_item("t", PyArray1::from_vec(py, t))?;
        one.set_item("q", rows(py, &pick(&records.q), mine.len()))?;
        one.set_item("p", rows(py, &pick(&records.p), mine.len()))?;
        d.set_item(name, one)?;
    }
    Ok(d)
}

/// The states at `[output] times`: `{"t": (k,), "q": (k × n), "p": (k × n), "observables":
/// {name: (k,)}}`, or `None` when no times were requested.
fn at_times<'py>(
    py: Python<'py>,
    sampled: Option<&SampledStates>,
) -> PyResult<Option<Bound<'py, PyDict>>> {
    let Some(sampled) = sampled else {
        return Ok(None);
    };
    let k = sampled.t.len();
    let d = PyDict::new(py);
    d.set_item("t", PyArray1::from_vec(py, sampled.t.clone()))?;
    d.set_item("q", rows(py, &sampled.q, k))?;
    d.set_item("p", rows(py, &sampled.p, k))?;
    let named = PyDict::new(py);
    for (name, values) in sampled.observable_names.iter().zip(&sampled.observables) {
        named.set_item(name, PyArray1::from_vec(py, values.clone()))?;
    }
    d.set_item("observables", named)?;
    Ok(Some(d))
}

/// The stored Jacobians: `t` (one per sample) and `jacobians` (`samples × 2n × columns`).
fn sensitivity<'py>(
    py: Python<'py>,
    columns: &[String],
    samples: &[(f64, Vec<f64>)],
) -> PyResult<Bound<'py, PyDict>> {
    let width = columns.len();
    let rows = samples.first().map_or(0, |(_, j)| j.len() / width.max(1));
    let at = |(k, r, c): (usize, usize, usize)| {
        (samples.get(k))
            .and_then(|(_, j)| j.get(r * width + c))
            .copied()
            .unwrap_or(f64::NAN)
    };
    let d = PyDict::new(py);
    let t: Vec<f64> = samples.iter().map(|(t, _)| *t).collect();
    d.set_item("t", PyArray1::from_vec(py, t))?;
    let cube: Bound<'py, PyArray3<f64>> =
        Array3::from_shape_fn((samples.len(), rows, width), at).into_pyarray(py);
    d.set_item("jacobians", cube)?;
    Ok(d)
}

/// Columns (one per coordinate) as a `samples × columns` array.
fn rows<'py>(py: Python<'py>, columns: &[Vec<f64>], samples: usize) -> Bound<'py, PyArray2<f64>> {
    let at = |(i, j): (usize, usize)| {
        columns
            .get(j)
            .and_then(|c| c.get(i))
            .copied()
            .unwrap_or(f64::NAN)
    };
    Array2::from_shape_fn((samples, columns.len()), at).into_pyarray(py)
}
