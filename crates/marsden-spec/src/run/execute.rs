//! A whole run of a problem file, as `marsden run` does it and as a binding calls it: check
//! the initial state, open the outputs, run with streaming rows, then draw the plots and
//! write `summary.json` — or keep the samples in memory ([`Store`]), or both.

use std::path::PathBuf;

use super::controls::Controls;
use super::event_outputs::{self, EventSamples, EventTee};
use super::sampled_times::{self, SampleOutputs, SampledStates};
use super::samples::{NullSink, Samples, Tee};
use super::sensitivity::SensitivitySummary;
use super::solve::{Destination, RunRecord};
use super::summary::{RunStatus, Summary};
use super::{balance, output, plots, sensitivity, start};
use crate::error::{Diagnostic, Error};
use crate::problem::RunSpec;
use marsden_engine::Engine;
use marsden_engine::checkpoint::tangent::{
    SENSITIVITY_CHECKPOINT_FILE, SensitivityCheckpoint, TangentPlan,
};
use marsden_engine::checkpoint::{self, CHECKPOINT_FILE, CheckpointPlan, RunCheckpoint};

/// Where the samples of a run go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Store {
    /// The trajectory files, `summary.json` and the plots in `[output] dir` (`marsden run`).
    Files,
    /// Only into [`Outcome::samples`]; nothing is written (the summary's format is `memory`).
    Memory,
    /// Both.
    FilesAndMemory,
}

impl Store {
    fn files(self) -> bool {
        self != Store::Memory
    }

    fn memory(self) -> bool {
        self != Store::Files
    }
}

/// The result of a run: the summary (also on disk when files are written), the samples (when
/// kept in memory) and remarks for the user.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// What `summary.json` holds.
    pub summary: Summary,
    /// Where the files are (`None`: nothing written).
    pub dir: Option<PathBuf>,
    /// The stored samples (with [`Store::Memory`] or [`Store::FilesAndMemory`]).
    pub samples: Option<Samples>,
    /// Problems that did not stop the run (a symmetry that is not one, a plot not drawn, …).
    pub warnings: Vec<String>,
    /// `[sensitivity]`: the Jacobian at every stored step, `(t_k, J_k)` with `J_k` row-major
    /// `2n × columns` (the summary names rows and columns); kept in memory as the samples are.
    pub sensitivity: Option<Vec<(f64, Vec<f64>)>>,
    /// `[[events]]`: the located crossings (when the samples are kept in memory and the file
    /// has events).
    pub events: Option<EventSamples>,
    /// `[output] times`: the states at the requested times (when the samples are kept in
    /// memory and the file requests times).
    pub sampled: Option<SampledStates>,
}

/// Runs `spec`: checks the initial state, creates the output directory (unless only in
/// memory), runs with streaming output watched by `controls`, then draws the plots and writes
/// `summary.json`.
///
/// # Errors
/// [`ErrorKind::BadInput`](crate::ErrorKind::BadInput) if the problem cannot start (nothing
/// written); [`ErrorKind::Failed`](crate::ErrorKind::Failed) only if not even the summary could
/// be written. A failed or interrupted simulation is an `Ok` outcome with that status.
pub fn execute(spec: &RunSpec, store: Store, controls: &Controls<'_>) -> Result<Outcome, Error> {
    execute_from(spec, store, controls, None)
}

/// [`execute`], from the checkpoint `resume` when given (`marsden resume`): the output files
/// are not cleared but cut back to the checkpoint's marks and continued, and the run goes on
/// from the checkpoint's step; with `[output] checkpoint_every`, checkpoints are written as
/// the run goes.
///
/// # Errors
/// As [`execute`]; also a checkpoint whose files no longer match (nothing is then changed),
/// and checkpoints asked of a run that keeps its samples only in memory.
pub fn execute_from(
    spec: &RunSpec,
    store: Store,
    controls: &Controls<'_>,
    resume: Option<Box<RunCheckpoint>>,
) -> Result<Outcome, Error> {
    let engine = crate::engine_for(spec);
    let start = engine.prepare(spec)?;
    let run = PreparedRun {
        engine: engine.as_ref(),
        spec,
        start: &start,
    };
    execute_prepared(run, store, controls, resume)
}

/// A run whose initial state was prepared already: the engine of `spec`, and the
/// [`start::Start`] its [`Engine::prepare`] gave for a spec that differs from `spec` at most in
/// `[output]` (which the initial state does not depend on).
#[derive(Clone, Copy)]
pub(crate) struct PreparedRun<'a> {
    /// The engine of `spec`'s system ([`crate::engine_for`]).
    pub engine: &'a dyn Engine,
    /// The problem to run.
    pub spec: &'a RunSpec,
    /// Its complete initial state, checked.
    pub start: &'a start::Start,
}

/// [`execute_from`] without preparing the initial state again ([`super::prepared::Prepared`]
/// holds it from when the problem was checked).
///
/// # Errors
/// As [`execute_from`].
pub(crate) fn execute_prepared(
    run: PreparedRun<'_>,
    store: Store,
    controls: &Controls<'_>,
    resume: Option<Box<RunCheckpoint>>,
) -> Result<Outcome, Error> {
    let PreparedRun {
        engine,
        spec,
        start,
    } = run;
    let dir = spec.output.dir.clone();
    let plan = checkpoint_plan(spec, store, resume)?;
    let resumed = plan.as_ref().and_then(|p| p.resume.as_deref());
    let tangent_plan = tangent_plan(spec, plan.as_ref())?;
    let io = |what: &str, e: &dyn std::fmt::Display| {
        Error::bad_input(Diagnostic::new(format!(
            "cannot {what} {}: {e}",
            dir.display()
        )))
    };
    // Held until the summary is written: a second run into `dir` is refused meanwhile.
    let _lock = match store.files() {
        true => {
            std::fs::create_dir_all(&dir).map_err(|e| io("create the output directory", &e))?;
            let held = output::lock(&dir).map_err(|m| {
                Error::bad_input(Diagnostic::new(m).help("give this run another `--out` directory"))
            })?;
            if resumed.is_none() {
                output::clear_previous(&dir)
                    .map_err(|e| io("clear the previous results in", &e))?;
            }
            Some(held)
        }
        false => None,
    };
    let layout = output::layout_of(spec).map_err(|e| io("lay out the columns of", &e))?;
    let mut files = match (store.files(), resumed) {
        (true, None) => Some(
            output::open_sink(&dir, spec.output.format, &layout)
                .map_err(|e| io("write the trajectory into", &e))?,
        ),
        (true, Some(c)) => Some(
            output::reopen_sink(
                &dir,
                spec.output.format,
                &layout,
                &(&c.stream.trajectory).into(),
            )
            .map_err(|e| Error::bad_input(Diagnostic::new(e.to_string())))?,
        ),
        (false, _) => None,
    };
    let mut samples = store.memory().then(|| Samples::of(spec));
    let events_mark = resumed
        .and_then(|c| c.events.as_ref())
        .and_then(|e| e.file.as_ref());
    let mut event_file = match store.files() {
        true => event_outputs::open(&dir, spec, events_mark.map(Into::into).as_ref())
            .map_err(|e| io("write the events into", &e))?,
        false => None,
    };
    let has_events = !spec.events.events.is_empty();
    let mut event_memory = (store.memory() && has_events).then(|| EventSamples::of(spec));
    let mut event_tee;
    let events: Option<&mut dyn marsden_io::RowSink> =
        match (event_file.as_mut(), event_memory.as_mut()) {
            (Some(files), Some(memory)) => {
                event_tee = EventTee {
                    files: files.as_mut(),
                    memory,
                };
                Some(&mut event_tee)
            }
            (Some(files), None) => Some(files.as_mut()),
            (None, Some(memory)) => Some(memory),
            (None, None) => None,
        };
    let samples_mark = resumed
        .and_then(|c| c.samples.as_ref())
        .and_then(|s| s.file.as_ref());
    let mut sample_outputs = SampleOutputs::open(
        spec,
        store.files().then_some(dir.as_path()),
        store.memory(),
        samples_mark.map(Into::into).as_ref(),
    )
    .map_err(|e| io("write the samples into", &e))?;
    let sampled: Option<&mut dyn marsden_io::RowSink> = sample_outputs
        .as_mut()
        .map(|s| s as &mut dyn marsden_io::RowSink);
    let (mut tee, mut null);
    let destination = match (files.as_mut(), samples.as_mut()) {
        (Some(files), None) => Destination {
            sink: files.as_mut(),
            with_velocity: false,
            events,
            samples: sampled,
            checkpoints: plan.as_ref(),
        },
        (None, Some(memory)) => Destination {
            sink: memory,
            with_velocity: true,
            events,
            samples: sampled,
            checkpoints: plan.as_ref(),
        },
        (Some(files), Some(memory)) => Destination {
            sink: {
                tee = Tee {
                    files: files.as_mut(),
                    memory,
                };
                &mut tee
            },
            with_velocity: true,
            events,
            samples: sampled,
            checkpoints: plan.as_ref(),
        },
        (None, None) => Destination {
            sink: {
                null = NullSink::default();
                &mut null
            },
            with_velocity: false,
            events,
            samples: sampled,
            checkpoints: plan.as_ref(),
        },
    };
    let mut record = engine.run(spec, destination, controls)?;
    let events_file = event_outputs::file_name(spec.output.format);
    let samples_file = sampled_times::file_name(spec.output.format);
    let mut warnings = start.warnings.clone();
    let mut written = Vec::new();
    if let Some(out) = sample_outputs.as_mut()
        && let Err(e) = marsden_io::RowSink::finish(out)
    {
        record
            .error
            .get_or_insert(format!("writing {samples_file} failed: {e}"));
    }
    if let Some(writer) = event_file.as_mut()
        && let Err(e) = writer.finish()
    {
        record
            .error
            .get_or_insert(format!("writing {} failed: {e}", events_file));
    }
    if let Some(sink) = files.as_mut() {
        if let Err(e) = sink.finish() {
            record
                .error
                .get_or_insert(format!("writing the trajectory failed: {e}"));
        }
        // The rows in the files: a write that failed part-way lost the rows it did not take.
        record.rows = sink.rows_written();
        written = output::trajectory_files(spec.output.format, &layout);
        if event_file.is_some() {
            written.push(events_file.to_owned());
        }
        if sample_outputs.as_ref().is_some_and(|o| o.file.is_some()) {
            written.push(samples_file.to_owned());
        }
        written.push(output::SUMMARY_JSON.to_owned());
        if plan.as_ref().is_some_and(|p| p.path.exists()) {
            written.push(CHECKPOINT_FILE.to_owned());
        }

        if spec.output.plots && record.rows > 0 {
            match plots::draw(spec, &layout) {
                Ok(pngs) => written.extend(pngs),
                Err(e) => warnings.push(format!("plots were not drawn: {e}")),
            }
            if has_events {
                match event_outputs::draw_section(&dir, spec) {
                    Ok(png) => written.push(png),
                    Err(e) => warnings.push(format!("the section was not drawn: {e}")),
                }
            }
            if let Some(series) = &record.balance_series
                && let Err(e) = balance::draw(&dir, series, &mut written)
            {
                warnings.push(format!("the energy balance was not drawn: {e}"));
            }
        }
    }
    let columns = layout
        .column_names()
        .into_iter()
        .map(str::to_owned)
        .collect();
    let sensitivity = derivatives(
        run,
        &record,
        store.files().then_some(&dir),
        store.memory(),
        controls,
        tangent_plan.as_ref(),
    );
    if let Some(Derivatives {
        file: Some(file), ..
    }) = &sensitivity
    {
        written.push(file.clone());
    }
    if tangent_plan.as_ref().is_some_and(|p| p.path.exists()) {
        written.push(SENSITIVITY_CHECKPOINT_FILE.to_owned());
    }
    let mut summary = Summary::new(spec, &record, columns, written);
    summary.set_symmetry_checks(&start.symmetries);
    if sensitivity.as_ref().is_some_and(|d| d.interrupted) {
        summary.status = RunStatus::Interrupted;
    }
    let (block, jacobians) = sensitivity.map_or((None, None), |d| (Some(d.summary), d.samples));
    summary.sensitivity = block;
    if !store.files() {
        summary.output.format = "memory";
    }
    if store.files() {
        summary.write(&dir).map_err(|e| {
            let d = Diagnostic::new(e);
            Error::failed(match &summary.error {
                Some(first) => d.note(format!("the run had failed before: {first}")),
                None => d,
            })
        })?;
    }
    Ok(Outcome {
        summary,
        dir: store.files().then_some(dir),
        samples,
        warnings,
        sensitivity: jacobians.filter(|_| store.memory()),
        events: event_memory,
        sampled: sample_outputs.and_then(|o| o.memory),
    })
}

/// The checkpoints of `spec` (`[output] checkpoint_every`), resuming from `resume` if given.
///
/// # Errors
/// Checkpoints asked of a run whose samples stay in memory (there is no directory to write
/// them into, nor files to resume).
fn checkpoint_plan(
    spec: &RunSpec,
    store: Store,
    resume: Option<Box<RunCheckpoint>>,
) -> Result<Option<CheckpointPlan>, Error> {
    let Some(every) = spec.output.checkpoint_every else {
        return Ok(None);
    };
    if !store.files() {
        return Err(Error::bad_input(
            Diagnostic::new(
                "checkpoints are written into the output directory, but this run writes no files",
            )
            .help("give the run an output directory, or remove `checkpoint_every`"),
        ));
    }
    Ok(Some(CheckpointPlan {
        every,
        path: spec.output.dir.join(CHECKPOINT_FILE),
        identity: super::resume::identity(spec),
        resume,
    }))
}

/// The checkpoints of the tangent run of `[sensitivity]` (beside the run's own `plan`),
/// continuing from `sensitivity-checkpoint.bin` when the run resumes and the tangent run had
/// been checkpointed; `None` without `[sensitivity]` or checkpoints.
///
/// # Errors
/// A damaged tangent checkpoint, or one of another run than `plan`'s (nothing changed yet).
fn tangent_plan(
    spec: &RunSpec,
    plan: Option<&CheckpointPlan>,
) -> Result<Option<TangentPlan>, Error> {
    let Some(plan) = plan.filter(|_| spec.sensitivity.is_some()) else {
        return Ok(None);
    };
    let path = spec.output.dir.join(SENSITIVITY_CHECKPOINT_FILE);
    let resume = match &plan.resume {
        Some(run) if path.exists() => {
            let tangent: SensitivityCheckpoint = checkpoint::file::load(&path)
                .map_err(|e| Error::bad_input(Diagnostic::new(e.to_string())))?;
            if tangent.identity != run.identity {
                return Err(Error::bad_input(Diagnostic::new(format!(
                    "{} belongs to another run than {CHECKPOINT_FILE} beside it",
                    path.display()
                ))));
            }
            Some(Box::new(tangent))
        }
        _ => None,
    };
    Ok(Some(TangentPlan {
        every: plan.every,
        path,
        identity: plan.identity.clone(),
        resume,
    }))
}

/// What `[sensitivity]` gave: the summary's block, the file written, the stored Jacobians.
struct Derivatives {
    summary: SensitivitySummary,
    file: Option<String>,
    samples: Option<Vec<(f64, Vec<f64>)>>,
    /// The tangent run was stopped by a signal: the run is interrupted.
    interrupted: bool,
}

/// `[sensitivity]`: the tangent run beside `run` once it has completed (its `record`; watched
/// by the run's `controls`: Ctrl-C and the progress bar), its Jacobians streamed into the file
/// in `dir` as the run reaches them (and kept in memory only with `keep`), checkpointed as
/// `checkpoints` plans and continued from its checkpoint when the plan has one; `None` without
/// `[sensitivity]`. A failure is reported in the summary's block.
fn derivatives(
    run: PreparedRun<'_>,
    record: &RunRecord,
    dir: Option<&PathBuf>,
    keep: bool,
    controls: &Controls<'_>,
    checkpoints: Option<&TangentPlan>,
) -> Option<Derivatives> {
    let PreparedRun {
        engine,
        spec,
        start,
    } = run;
    let asked = spec.sensitivity.as_ref()?;
    let failed = |error: String| Derivatives {
        summary: SensitivitySummary {
            rows: Vec::new(),
            columns: Vec::new(),
            final_jacobian: Vec::new(),
            samples: 0,
            error: Some(error),
            note: None,
        },
        file: None,
        samples: None,
        interrupted: false,
    };
    if record.error.is_some() || record.interrupted {
        return Some(failed("the run did not complete".to_owned()));
    }
    let names = sensitivity::names(spec, asked);
    let resumed = checkpoints.and_then(|p| p.resume.as_deref());
    let writer = match (dir, resumed.map(|c| c.file.as_ref())) {
        (None, _) => None,
        (Some(dir), None) => {
            match sensitivity::SensitivityWriter::create(dir, spec.output.format, &names) {
                Ok(w) => Some(w),
                Err(e) => return Some(failed(format!("writing the sensitivities failed: {e}"))),
            }
        }
        (Some(dir), Some(Some(mark))) => {
            match sensitivity::SensitivityWriter::reopen(dir, spec.output.format, &names, mark) {
                Ok(w) => Some(w),
                Err(e) => return Some(failed(format!("continuing the sensitivities failed: {e}"))),
            }
        }
        (Some(_), Some(None)) => {
            return Some(failed(
                "the tangent run's checkpoint records no sensitivity file to continue".to_owned(),
            ));
        }
    };
    let mut out = sensitivity::JacobianFile {
        writer,
        kept: keep.then(Vec::new),
        error: None,
    };
    let job = sensitivity::TangentRun {
        engine,
        spec,
        asked,
        start,
        controls,
    };
    let found = match job.into(&mut out, checkpoints) {
        Ok(found) => found,
        Err(e) => return Some(failed(e)),
    };
    let mut summary = found.summary;
    let file = match (out.writer, out.error) {
        (Some(w), None) => match w.finish() {
            Ok(file) => Some(file),
            Err(e) => {
                summary.error = Some(format!("writing the sensitivities failed: {e}"));
                None
            }
        },
        (_, Some(e)) => {
            summary.error = Some(format!("writing the sensitivities failed: {e}"));
            None
        }
        (None, None) => None,
    };
    Some(Derivatives {
        summary,
        file,
        samples: out.kept,
        interrupted: found.interrupted,
    })
}
