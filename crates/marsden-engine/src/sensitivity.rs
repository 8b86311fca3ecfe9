//! `[sensitivity]` of a run: the Jacobian `∂(q_k, p_k)/∂(q₀, p₀, θ)` at the stored steps and
//! at the end, by a tangent run beside the file's run ([`marsden::sensitivity::tangent`](fn@marsden::sensitivity::tangent)).
//!
//! The tangent run takes the same steps from the same initial state on the same grid; it uses
//! the general Newton path (the fast paths of separable Lagrangians keep no stage offsets to
//! differentiate), so its states agree with the file's run to round-off, not bit for bit,
//! and the run's own outputs are untouched. Each step's Jacobian comes from the implicit
//! function theorem on the converged step ([MW01] §1.5), `S_{k+1} = DF_x S_k + [0 | DF_θ]`.
//! With parameters, the step is that of [`ExprParametric`] (the file's texts with the named
//! parameters as inputs) at the file's values. A constrained run (SHAKE + RATTLE) is
//! differentiated with its multipliers and its projection ([`marsden::sensitivity`]): its
//! Jacobian is that of the constrained run on tangent vectors of `T*N`, which the summary's
//! `note` says. Parameters of a constrained run (in `L`, the forces or the constraints) are
//! differentiated with [`ConstrainedParametricIntegrator`], multipliers and projection included.
//!
//! The tangent run is watched as the file's run is ([`Controls`], [`compute_with`]): the
//! progress callback every [`CHECK_EVERY`] steps and the stop flag there; a stopped tangent run
//! keeps the Jacobians of the steps it took and says so in the summary's `error`.
//!
//! Files: `sensitivity.npy` of shape `[samples, 2n, columns]`, or `sensitivity.csv` (one row
//! per stored step: `t`, then the entries row by row, named `q_x/q0_x`) with `format = "csv"`.
//!
//! [MW01]: marsden#references

use marsden::sensitivity::{Tangent, TangentSample};
use marsden::{Constraint as _, State, Termination};
use serde::Serialize;

use crate::checkpoint::Mark;
use crate::checkpoint::tangent::TangentPlan;
use crate::controls::Controls;
use crate::engine::Engine;
pub use crate::sensitivity_writer::{
    JacobianFile, SENSITIVITY_CSV, SENSITIVITY_NPY, SensitivityWriter, write,
};
use crate::start::Start;
use crate::tangent::{SampleOut, TangentJob, Watched, WithParameters};
use marsden_problem::problem::{RunSpec, SensitivitySpec};

/// The derivatives of a run, as `summary.json` gives them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SensitivitySummary {
    /// Row names: `q_<coordinate>` then `p_<coordinate>`.
    pub rows: Vec<String>,
    /// Column names: `q0_<coordinate>`, `p0_<coordinate>` (with `initial = true`), then the
    /// parameters.
    pub columns: Vec<String>,
    /// `∂(q_K, p_K)/∂(columns)` at the final state, one list per row.
    #[serde(rename = "final")]
    pub final_jacobian: Vec<Vec<f64>>,
    /// Stored Jacobians (the entries of the sensitivity file).
    pub samples: usize,
    /// Why the derivatives could not be computed (null when they were).
    pub error: Option<String>,
    /// How to read them, when that needs saying (constrained runs; null otherwise).
    pub note: Option<String>,
}

/// The note of a constrained run's Jacobians.
const ON_TANGENT_VECTORS: &str = "constrained: the Jacobian extends the step off the \
     constraint manifold; only its action on tangent vectors of T*N (δq with Dφ(q₀)·δq = 0 and \
     the hidden constraint's derivative zero) is the derivative of the constrained run";

/// The tangent run's Jacobians restricted to the asked columns.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensitivities {
    /// What the summary shows.
    pub summary: SensitivitySummary,
    /// `(t_k, J_k)` at the stored steps, `J_k` row-major `2n × columns`.
    pub samples: Vec<(f64, Vec<f64>)>,
    /// The tangent run was stopped by the caller's stop flag (a signal) before its end: the
    /// run is not complete, whatever its first loop did.
    pub interrupted: bool,
}

/// Runs the tangent run of `spec` from `start`, unwatched ([`compute_with`]).
///
/// # Errors
/// The core's error (a step that failed, a rule whose step cannot be differentiated), as text.
pub fn compute(
    engine: &dyn Engine,
    spec: &RunSpec,
    asked: &SensitivitySpec,
    start: &Start,
) -> Result<Sensitivities, String> {
    compute_with(engine, spec, asked, start, &Controls::none())
}

/// Runs the tangent run of `spec` from `start`, showing its progress to `controls` and stopping
/// when its flag is set (looked at every [`CHECK_EVERY`] steps): a stopped run gives the
/// Jacobians of the steps it took, with the summary's `error` saying where it stopped. The
/// stored Jacobians are kept in memory ([`compute_streamed`] hands them on instead).
///
/// # Errors
/// The core's error (a step that failed, a rule whose step cannot be differentiated), as text.
pub fn compute_with(
    engine: &dyn Engine,
    spec: &RunSpec,
    asked: &SensitivitySpec,
    start: &Start,
    controls: &Controls<'_>,
) -> Result<Sensitivities, String> {
    let mut samples = Vec::new();
    let mut keep = |t: f64, jacobian: &[f64]| samples.push((t, jacobian.to_vec()));
    let mut found = compute_streamed(engine, spec, asked, start, controls, &mut keep)?;
    found.samples = samples;
    Ok(found)
}

/// [`compute_with`], handing each stored Jacobian to `sink` as the tangent run reaches it
/// (`(t_k, J_k)`, `J_k` row-major `2n × columns` of the asked columns) instead of keeping it:
/// a run of 10⁶ stored steps holds two Jacobians, not all of them. The result's `samples` is
/// empty; its summary counts what was handed on.
///
/// # Errors
/// The core's error (a step that failed, a rule whose step cannot be differentiated), as text.
pub fn compute_streamed(
    engine: &dyn Engine,
    spec: &RunSpec,
    asked: &SensitivitySpec,
    start: &Start,
    controls: &Controls<'_>,
    sink: &mut dyn FnMut(f64, &[f64]),
) -> Result<Sensitivities, String> {
    let job = TangentRun {
        engine,
        spec,
        asked,
        start,
        controls,
    };
    job.into(&mut Closure(sink), None)
}

/// A tangent run of a file's `[sensitivity]`: the engine, the file, what it asks, where it
/// starts and the caller's controls.
pub struct TangentRun<'r, 'c> {
    /// The system's engine.
    pub engine: &'r dyn Engine,
    /// The file.
    pub spec: &'r RunSpec,
    /// Its `[sensitivity]`.
    pub asked: &'r SensitivitySpec,
    /// The run's initial state.
    pub start: &'r Start,
    /// Progress and the stop flag.
    pub controls: &'r Controls<'c>,
}

impl TangentRun<'_, '_> {
    /// Runs it, handing each stored Jacobian to `out` as [`compute_streamed`] does, and
    /// checkpointing it as `checkpoints` plans — from the plan's checkpoint, when it has one,
    /// instead of the start (the Jacobians handed on before it are counted, not handed again).
    /// A checkpoint that cannot be written stops the run, with the reason in the summary's
    /// `error`.
    ///
    /// # Errors
    /// As [`compute_streamed`]; also a checkpoint that does not fit this run's integrator.
    pub fn into(
        self,
        out: &mut dyn JacobianSink,
        checkpoints: Option<&TangentPlan>,
    ) -> Result<Sensitivities, String> {
        let Self {
            engine,
            spec,
            asked,
            start,
            controls,
        } = self;
        let state = State {
            t: start.t,
            q: start.q.clone(),
            p: start.p.clone(),
        };
        let Some(rule) = spec.integrator.method.rule() else {
            return Err(
                "method = \"exact\" has no step Jacobian to propagate; choose a rule".into(),
            );
        };
        let picker = Picker::of(spec, asked);
        let resumed = checkpoints.and_then(|p| p.resume.as_deref());
        let mut forward = Forward {
            picker: &picker,
            handed: resumed.map_or(0, |c| c.samples),
            out,
        };
        let watched = Watched::new(spec, controls, &mut forward, checkpoints);
        let run = match &asked.model {
            Some(model) => WithParameters {
                spec,
                model,
                state,
                v: &start.v,
                watched: &watched,
            }
            .call(rule)
            .map_err(|e| e.to_string()),
            None => engine.initial_tangent(TangentJob {
                spec,
                rule,
                state,
                watched: &watched,
            }),
        }?;
        watched.report(run_steps(&run, spec.integrator.grid.steps), true);
        let checkpoint_error = watched.checkpoint_error();
        let mut found = select(spec, asked, &picker, &run, watched.handed());
        if let Some(e) = checkpoint_error {
            found.summary.error = Some(format!("the tangent run stopped: {e}"));
        } else if let Termination::Stopped { steps } = run.termination {
            found.interrupted = true;
            found.summary.error = Some(format!(
                "the tangent run was stopped after {steps} of {} steps; the Jacobians are those \
                 of the steps taken",
                spec.integrator.grid.steps
            ));
        }
        Ok(found)
    }
}

/// Where the stored Jacobians of a tangent run go: the asked columns, row-major
/// `2n × columns`.
pub trait JacobianSink {
    /// Takes the Jacobian of the stored step at `t`.
    fn take(&mut self, t: f64, jacobian: &[f64]);

    /// Flushes what was taken into its file, and says where the file stands — what a
    /// checkpoint records (`None`, the default: no file).
    ///
    /// # Errors
    /// A write error, as text.
    fn mark(&mut self) -> Result<Option<Mark>, String> {
        Ok(None)
    }
}

/// A closure as a [`JacobianSink`] without a file.
struct Closure<'f>(&'f mut dyn FnMut(f64, &[f64]));

impl JacobianSink for Closure<'_> {
    fn take(&mut self, t: f64, jacobian: &[f64]) {
        (self.0)(t, jacobian);
    }
}

/// The kept samples of the tangent run, their asked columns picked and handed on.
struct Forward<'s> {
    picker: &'s Picker,
    handed: usize,
    out: &'s mut dyn JacobianSink,
}

impl SampleOut for Forward<'_> {
    fn sample(&mut self, sample: &TangentSample) {
        self.handed += 1;
        self.out
            .take(sample.state.t, &self.picker.pick(&sample.jacobian));
    }

    fn handed(&self) -> usize {
        self.handed
    }

    fn mark(&mut self) -> Result<Option<Mark>, String> {
        self.out.mark()
    }
}

/// The asked columns of the tangent run's Jacobians (`(q₀, p₀)` with `initial = true`, then the
/// parameters), picked out of its full `2n × (2n + P)` Jacobians.
struct Picker {
    rows: usize,
    columns: usize,
    picked: Vec<usize>,
}

impl Picker {
    fn of(spec: &RunSpec, asked: &SensitivitySpec) -> Self {
        let n = spec.system.dof();
        let columns = 2 * n + asked.parameters.len();
        let mut picked: Vec<usize> = Vec::new();
        if asked.initial {
            picked.extend(0..2 * n);
        }
        picked.extend(2 * n..columns);
        Self {
            rows: 2 * n,
            columns,
            picked,
        }
    }

    /// The picked columns of `jacobian`, row-major `2n × picked`.
    fn pick(&self, jacobian: &[f64]) -> Vec<f64> {
        (0..self.rows)
            .flat_map(|r| self.picked.iter().map(move |&c| (r, c)))
            .map(|(r, c)| jacobian[r * self.columns + c])
            .collect()
    }
}

/// Steps taken by a tangent run of `total` steps.
fn run_steps(run: &Tangent, total: usize) -> usize {
    match run.termination {
        Termination::Stopped { steps } => steps,
        _ => total,
    }
}

/// The summary of the asked columns: names, the final Jacobian, the number of samples handed on.
fn select(
    spec: &RunSpec,
    asked: &SensitivitySpec,
    picker: &Picker,
    run: &Tangent,
    samples: usize,
) -> Sensitivities {
    let last = picker.pick(&run.jacobian);
    let width = picker.picked.len();
    let mut summary = names(spec, asked);
    summary.final_jacobian = last.chunks(width.max(1)).map(<[f64]>::to_vec).collect();
    summary.samples = samples;
    Sensitivities {
        summary,
        samples: Vec::new(),
        interrupted: false,
    }
}

/// The summary's names of the asked derivatives (rows `q_x`, `p_x`; columns `q0_x`, `p0_x`,
/// then the parameters), before anything is computed; no Jacobian yet.
pub fn names(spec: &RunSpec, asked: &SensitivitySpec) -> SensitivitySummary {
    let coordinates = &spec.system.coordinates;
    let mut columns = Vec::new();
    if asked.initial {
        columns.extend(coordinates.iter().map(|c| format!("q0_{c}")));
        columns.extend(coordinates.iter().map(|c| format!("p0_{c}")));
    }
    columns.extend(asked.parameters.iter().cloned());
    let rows: Vec<String> = (coordinates.iter().map(|c| format!("q_{c}")))
        .chain(coordinates.iter().map(|c| format!("p_{c}")))
        .collect();
    SensitivitySummary {
        rows,
        columns,
        final_jacobian: Vec::new(),
        samples: 0,
        error: None,
        note: (spec.system.constraint.count() > 0).then(|| ON_TANGENT_VECTORS.to_owned()),
    }
}

/// The console line: what was computed, and the largest entry of the final Jacobian.
pub fn describe(summary: &SensitivitySummary) -> String {
    if let Some(e) = &summary.error {
        return format!("sensitivity: not computed: {e}");
    }
    let note = summary
        .note
        .as_ref()
        .map_or(String::new(), |n| format!(" ({n})"));
    let largest = (summary.final_jacobian.iter().flatten()).fold(0.0_f64, |m, x| {
        marsden::numerics::dense::max_or_nan(m, x.abs())
    });
    format!(
        "sensitivity: ∂(q, p)/∂({}), {}×{} at {} stored steps; final max |entry| \
         {largest:.3e}{note}",
        summary.columns.join(", "),
        summary.rows.len(),
        summary.columns.len(),
        summary.samples,
    )
}
