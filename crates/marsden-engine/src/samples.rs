//! The states of a run at the times of `[output] times`: the core's
//! [`TimeSampler`](marsden::run::events::TimeSampler) watching the run beside the event
//! detector ([`crate::events::Watched`]), each sample written at once as a row
//! `t, q…, p…, observables…` (the observables evaluated at the sampled `(t, q, v, p)`).

use std::ops::ControlFlow;

use marsden::run::events::{Sample, TimeSampler};
use marsden::{Lagrangian, Observer, StepView, Termination};
use marsden_io::RowSink;

use crate::checkpoint::SamplesCheckpoint;
use marsden_problem::error::Diagnostic;
use marsden_problem::model::Observables;
use marsden_problem::problem::OutputSpec;

/// The file name of the samples.
pub const SAMPLES_CSV: &str = "samples.csv";

/// The columns of the samples of a system with `coordinates` and `observables`:
/// `t, q_…, p_…, observables…`.
pub fn sample_columns(coordinates: &[String], observables: &[String]) -> Vec<String> {
    let q = coordinates.iter().map(|c| format!("q_{c}"));
    let p = coordinates.iter().map(|c| format!("p_{c}"));
    std::iter::once("t".to_owned())
        .chain(q)
        .chain(p)
        .chain(observables.iter().cloned())
        .collect()
}

/// What the samples of a run came to.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SampleTally {
    /// Times requested.
    pub requested: usize,
    /// Samples taken (fewer than requested when the run ended early).
    pub taken: usize,
    /// The first error writing a sample (the run stops there).
    pub io_error: Option<String>,
}

/// The sampler of a run and where its samples go.
pub struct TimeSamples<'a, 's, L> {
    sampler: TimeSampler<'a, L>,
    observables: &'a Observables,
    sink: Option<&'s mut (dyn RowSink + 's)>,
    /// Samples of the sampler already written.
    written: usize,
    row: Vec<f64>,
    tally: SampleTally,
}

impl<'a, 's, L: Lagrangian> TimeSamples<'a, 's, L> {
    /// The sampler of `lagrangian`'s runs at the times of `output` (`None` when there are
    /// none), each read off the step's interpolant or, with `exact_times`, reached by a step
    /// of its own size; writing into `sink` (none: counted only).
    ///
    /// # Errors
    /// The core's objection to the times or to the Lagrangian (a singular declared mass
    /// matrix).
    pub fn new(
        lagrangian: &'a L,
        output: &OutputSpec,
        observables: &'a Observables,
        sink: Option<&'s mut (dyn RowSink + 's)>,
    ) -> Result<Option<Self>, Diagnostic> {
        let times = output.times.as_slice();
        if times.is_empty() {
            return Ok(None);
        }
        let sampler = TimeSampler::new(lagrangian, times)
            .map_err(|e| Diagnostic::new(format!("the times cannot be sampled: {e}")))?;
        let sampler = match output.exact_times {
            true => sampler.by_steps(),
            false => sampler,
        };
        Ok(Some(Self {
            sampler,
            observables,
            sink,
            written: 0,
            row: Vec::new(),
            tally: SampleTally {
                requested: times.len(),
                ..SampleTally::default()
            },
        }))
    }

    /// What the samples came to.
    pub fn tally(&self) -> SampleTally {
        SampleTally {
            taken: self.written,
            ..self.tally.clone()
        }
    }

    /// What the sampler carries to the next step, its file flushed and its position taken.
    ///
    /// # Errors
    /// The write error of the flush (kept in the tally too).
    pub fn checkpoint(&mut self) -> Result<SamplesCheckpoint, String> {
        let file = match self.sink.as_mut().map(|s| s.mark()) {
            Some(Ok(mark)) => Some(mark.into()),
            Some(Err(e)) => {
                let message = format!("writing the samples failed: {e}");
                self.tally.io_error = Some(message.clone());
                return Err(message);
            }
            None => None,
        };
        Ok(SamplesCheckpoint {
            sampler: self.sampler.checkpoint(),
            written: self.written,
            file,
        })
    }

    /// Restores a [`TimeSamples::checkpoint`].
    ///
    /// # Errors
    /// A checkpoint of other times.
    pub fn restore(&mut self, checkpoint: &SamplesCheckpoint) -> Result<(), String> {
        self.sampler
            .restore(&checkpoint.sampler)
            .map_err(|e| e.to_string())?;
        self.written = checkpoint.written;
        Ok(())
    }

    /// Writes the samples taken since the last call; `Break` on a write error.
    fn stream(&mut self) -> ControlFlow<()> {
        let new = &self.sampler.samples()[self.written..];
        self.written += new.len();
        let Some(sink) = self.sink.as_mut() else {
            return ControlFlow::Continue(());
        };
        for sample in new {
            fill_row(&mut self.row, sample, self.observables);
            if let Err(e) = sink.write_row(&self.row) {
                self.tally.io_error = Some(format!("writing the samples failed: {e}"));
                return ControlFlow::Break(());
            }
        }
        ControlFlow::Continue(())
    }
}

/// `row ← [t, q…, p…, observables…]`.
fn fill_row(row: &mut Vec<f64>, sample: &Sample, observables: &Observables) {
    row.clear();
    row.push(sample.t);
    row.extend_from_slice(&sample.q);
    row.extend_from_slice(&sample.p);
    let start = row.len();
    row.resize(start + observables.len(), 0.0);
    observables.eval_into(sample.t, &sample.q, &sample.v, &sample.p, &mut row[start..]);
}

impl<L: Lagrangian> Observer for TimeSamples<'_, '_, L> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.sampler.start(initial);
        // A write error is kept in the tally and ends the run at its first step.
        let _ = self.stream();
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        if self.tally.io_error.is_some() {
            return ControlFlow::Break(());
        }
        let sampled = self.sampler.observe(view);
        let written = self.stream();
        match (sampled, written) {
            (ControlFlow::Continue(()), ControlFlow::Continue(())) => ControlFlow::Continue(()),
            _ => ControlFlow::Break(()),
        }
    }

    fn landing(&self, step: usize, t: f64, next: f64) -> Option<f64> {
        self.sampler.landing(step, t, next)
    }

    fn landed(&mut self, reached: Result<&StepView<'_>, &marsden::Error>) -> ControlFlow<()> {
        let landed = self.sampler.landed(reached);
        let written = self.stream();
        match (landed, written) {
            (ControlFlow::Continue(()), ControlFlow::Continue(())) => ControlFlow::Continue(()),
            _ => ControlFlow::Break(()),
        }
    }

    fn termination(&self) -> Option<Termination> {
        self.sampler.termination()
    }
}
