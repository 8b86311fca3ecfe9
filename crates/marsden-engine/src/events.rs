//! The events of a problem file watched along its run: the core's
//! [`EventDetector`](marsden::run::events::EventDetector) beside the observer that streams the
//! rows ([`Watched`]), each located crossing written at once as a row
//! `event, t, q…, p…` (`event` is the index of the event in the file's `[[events]]`).
//!
//! A file without events is watched by nothing: [`Watched`] then forwards every call to the
//! streaming observer unchanged (same steps seen, same rows written). With events the detector
//! watches every step inside the stretches the run loop hands the stepper: it evaluates each
//! `g` once per step (with the velocities, an inverse Legendre transform, only if some `when`
//! reads them), ends the stretch at a sign change, and locates it on the step's Hermite
//! interpolant (Brent's method).

use std::ops::ControlFlow;

use marsden::run::WatchedSteps;
use marsden::run::events::{Event, EventDetector, EventRecord};
use marsden::{Lagrangian, Observer, StepView, Termination};
use marsden_io::RowSink;

use crate::checkpoint::{EventsCheckpoint, SamplesCheckpoint};
use crate::samples::{SampleTally, TimeSamples};
use marsden_problem::error::Diagnostic;
use marsden_problem::model::ExprEvent;
use marsden_problem::problem::events::EventsSpec;

/// The file name of the event records.
pub const EVENTS_CSV: &str = "events.csv";

/// The columns of the event records of a system with `coordinates`: `event, t, q_…, p_…`.
pub fn event_columns(coordinates: &[String]) -> Vec<String> {
    let q = coordinates.iter().map(|c| format!("q_{c}"));
    let p = coordinates.iter().map(|c| format!("p_{c}"));
    ["event".to_owned(), "t".to_owned()]
        .into_iter()
        .chain(q)
        .chain(p)
        .collect()
}

/// What the events of a run came to.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EventTally {
    /// Crossings recorded, per event (the file's order).
    pub counts: Vec<usize>,
    /// The event that ended the run (`action = "stop"`), by index.
    pub stopped_by: Option<usize>,
    /// The first error writing a record (the run stops there).
    pub io_error: Option<String>,
}

/// An observer `inner` and the detector of the file's events, whose records go to `sink`.
pub struct Watched<'a, 's, L, O> {
    /// The observer streaming the rows.
    pub inner: O,
    detector: Option<EventDetector<'a, L, ExprEvent<'a>>>,
    sink: Option<&'s mut (dyn RowSink + 's)>,
    /// Records of the detector already written.
    written: usize,
    row: Vec<f64>,
    tally: EventTally,
    /// The samples at `[output] times` (`None`: none requested).
    samples: Option<TimeSamples<'a, 's, L>>,
}

impl<'a, 's, L: Lagrangian, O: Observer> Watched<'a, 's, L, O> {
    /// `inner` alone: no events.
    pub fn without_events(inner: O) -> Self {
        Self {
            inner,
            detector: None,
            sink: None,
            written: 0,
            row: Vec::new(),
            tally: EventTally::default(),
            samples: None,
        }
    }

    /// The same watch, also sampling the run at requested times (`None`: none).
    pub fn with_samples(self, samples: Option<TimeSamples<'a, 's, L>>) -> Self {
        Self { samples, ..self }
    }

    /// What the samples' watch carries to the next step (`None` without sampled times).
    ///
    /// # Errors
    /// The write error of the flush of the samples' file.
    pub fn samples_checkpoint(&mut self) -> Result<Option<SamplesCheckpoint>, String> {
        self.samples
            .as_mut()
            .map(TimeSamples::checkpoint)
            .transpose()
    }

    /// Restores a [`Watched::samples_checkpoint`] (`None`: the file samples no times).
    ///
    /// # Errors
    /// A checkpoint of other times.
    pub fn restore_samples(
        &mut self,
        checkpoint: Option<&SamplesCheckpoint>,
    ) -> Result<(), String> {
        match (&mut self.samples, checkpoint) {
            (None, None) => Ok(()),
            (Some(samples), Some(c)) => samples.restore(c),
            _ => Err("the checkpoint's sampled times do not match the problem file's".to_owned()),
        }
    }

    /// `inner` and the events of `spec` on the runs of `lagrangian`, their records written to
    /// `sink` (none: counted only).
    ///
    /// # Errors
    /// The core's objection to the events (a singular declared mass matrix).
    pub fn new(
        inner: O,
        lagrangian: &'a L,
        spec: &'a EventsSpec,
        sink: Option<&'s mut (dyn RowSink + 's)>,
    ) -> Result<Self, Diagnostic> {
        if spec.events.is_empty() {
            return Ok(Self::without_events(inner));
        }
        let n = lagrangian.dof();
        let events = (spec.events.iter())
            .zip(spec.functions(n))
            .map(|(e, function)| Event {
                reads_velocity: reads_velocity(&function, n),
                function,
                direction: e.direction,
                action: e.action,
                count: e.count,
            })
            .collect();
        let detector = EventDetector::new(lagrangian, events)
            .map_err(|e| Diagnostic::new(format!("the events cannot be watched: {e}")))?;
        Ok(Self {
            inner,
            detector: Some(detector),
            sink,
            written: 0,
            row: Vec::new(),
            tally: EventTally {
                counts: vec![0; spec.events.len()],
                ..EventTally::default()
            },
            samples: None,
        })
    }

    /// What the watch carries to the next step (`None` without events), its file flushed and
    /// its position taken, for a checkpoint of the run.
    ///
    /// # Errors
    /// The write error of the flush (kept in the tally too).
    pub fn checkpoint(&mut self) -> Result<Option<EventsCheckpoint>, String> {
        let Some(detector) = &self.detector else {
            return Ok(None);
        };
        let file = match self.sink.as_mut().map(|s| s.mark()) {
            Some(Ok(mark)) => Some(mark.into()),
            Some(Err(e)) => {
                let message = format!("writing the event records failed: {e}");
                self.tally.io_error = Some(message.clone());
                return Err(message);
            }
            None => None,
        };
        Ok(Some(EventsCheckpoint {
            detector: detector.checkpoint(),
            written: self.written,
            counts: self.tally.counts.clone(),
            file,
        }))
    }

    /// Restores a [`Watched::checkpoint`] (`None`: the file has no events).
    ///
    /// # Errors
    /// A checkpoint of other events.
    pub fn restore(&mut self, checkpoint: Option<&EventsCheckpoint>) -> Result<(), String> {
        match (&mut self.detector, checkpoint) {
            (None, None) => Ok(()),
            (Some(detector), Some(c)) if c.counts.len() == self.tally.counts.len() => {
                detector.restore(&c.detector).map_err(|e| e.to_string())?;
                self.written = c.written;
                self.tally.counts.clone_from(&c.counts);
                Ok(())
            }
            _ => Err("the checkpoint's events do not match the problem file's".to_owned()),
        }
    }

    /// The streaming observer, what the events came to and what the samples did (`None`: no
    /// times requested).
    pub fn into_parts(self) -> (O, EventTally, Option<SampleTally>) {
        let samples = self.samples.as_ref().map(TimeSamples::tally);
        (self.inner, self.tally, samples)
    }

    /// Writes the records located since the last call; `Break` on a write error.
    fn stream(&mut self) -> ControlFlow<()> {
        let Some(detector) = &self.detector else {
            return ControlFlow::Continue(());
        };
        let new = &detector.records()[self.written..];
        self.written += new.len();
        for record in new {
            self.tally.counts[record.event] += 1;
            let Some(sink) = self.sink.as_mut() else {
                continue;
            };
            fill_row(&mut self.row, record);
            if let Err(e) = sink.write_row(&self.row) {
                self.tally.io_error = Some(format!("writing the event records failed: {e}"));
                return ControlFlow::Break(());
            }
        }
        ControlFlow::Continue(())
    }
}

/// Whether the event's `when` reads a velocity (input slots `n … 2n − 1` of the inputs
/// `[q…, q̇…, p…, t, observables…]`), itself or through an observable it names (slots past
/// `3n`, `t`): if no event does, the detector computes the velocities only at a step where a
/// sign change was found.
fn reads_velocity(event: &ExprEvent<'_>, n: usize) -> bool {
    let velocity = |slots: &[usize]| slots.iter().any(|slot| (n..2 * n).contains(slot));
    let used = event.when.inputs_used();
    let observables = used.iter().any(|&slot| slot > 3 * n);
    velocity(used)
        || observables
            && (event.observables.programs.iter()).any(|program| velocity(program.inputs_used()))
}

/// `row ← [event, t, q…, p…]`.
fn fill_row(row: &mut Vec<f64>, record: &EventRecord) {
    row.clear();
    // Exact: an index far below 2⁵³.
    row.push(record.event as f64);
    row.push(record.t);
    row.extend_from_slice(&record.q);
    row.extend_from_slice(&record.p);
}

impl<L: Lagrangian, O: Observer> Observer for Watched<'_, '_, L, O> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.inner.start(initial);
        if let Some(detector) = &mut self.detector {
            detector.start(initial);
        }
        if let Some(samples) = &mut self.samples {
            samples.start(initial);
        }
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        let flow = self.inner.observe(view);
        let flow = match &mut self.samples {
            Some(samples) if flow.is_continue() => samples.observe(view),
            _ => flow,
        };
        let Some(detector) = &mut self.detector else {
            return flow;
        };
        if flow.is_break() {
            return flow;
        }
        let located = detector.observe(view);
        // The detector ends the run only by returning `Break`: its termination is asked then
        // alone (a clone per step otherwise).
        if located.is_break()
            && let Some(Termination::Event { event, .. }) = detector.termination()
        {
            self.tally.stopped_by = Some(event);
        }
        let written = self.stream();
        match (located, written) {
            (ControlFlow::Continue(()), ControlFlow::Continue(())) => ControlFlow::Continue(()),
            _ => ControlFlow::Break(()),
        }
    }

    /// The detector watches the steps inside the stretches the run loop hands the stepper
    /// ([`Observer::watch_steps`]): events alone do not make the run go step by step.
    fn every_step(&self) -> bool {
        self.samples.is_some() || self.inner.every_step()
    }

    fn watches_steps(&self) -> bool {
        self.detector.is_some()
    }

    fn watch_steps<W: WatchedSteps>(&mut self, steps: &mut W) {
        match self.detector.as_mut() {
            Some(detector) => detector.watch_steps(steps),
            None => while steps.next_step().is_some() {},
        }
    }

    fn next_stop(&self, step: usize) -> usize {
        self.inner.next_stop(step)
    }

    fn landing(&self, step: usize, t: f64, next: f64) -> Option<f64> {
        (self.samples.as_ref()).and_then(|s| s.landing(step, t, next))
    }

    fn landed(&mut self, reached: Result<&StepView<'_>, &marsden::Error>) -> ControlFlow<()> {
        match &mut self.samples {
            Some(samples) => samples.landed(reached),
            None => ControlFlow::Continue(()),
        }
    }

    fn termination(&self) -> Option<Termination> {
        (self.detector.as_ref())
            .and_then(|d| d.termination())
            .or_else(|| self.samples.as_ref().and_then(|s| s.termination()))
            .or_else(|| self.inner.termination())
    }
}
