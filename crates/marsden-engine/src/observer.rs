//! The observer that streams a run to disk: every `every`-th state (and the first and the last)
//! becomes one row `t, q, p, energy, J…, residual, λ…, observables…, velocity residual`, written
//! at once, and feeds the diagnostics. With constraints, `residual` is `max_i |φ_i(q)|` and
//! the velocity residual the hidden constraint's `|Dφ(q)·v|` at `v = FL⁻¹(q, p)` ([HLW06]
//! §VII.1: RATTLE keeps both at the Newton tolerance).
//!
//! [HLW06]: marsden#references
//! Memory stays bounded whatever the number of steps; a failed run keeps every row written.
//!
//! The observer needs to see only the sampled steps, plus every [`CHECK_EVERY`]-th step when
//! the caller gave [`Controls`] (a progress callback, a stop flag): it says so
//! ([`Observer::every_step`], [`Observer::next_stop`]), so an explicit run takes the steps in
//! between in one loop ([`marsden::Integrator::advance`]) with no per-step work of its own.

use std::ops::ControlFlow;
use std::time::Instant;

use marsden::analysis::diagnostics::residuals_at;
use marsden::holonomic::multipliers_at;
use marsden::run::next_multiple;
use marsden::{Constraint, Lagrangian, Observer, StepView, Trajectory, mechanics};
use marsden_io::RowSink;

use crate::checkpoint::StreamCheckpoint;
use crate::controls::{CHECK_EVERY, Controls, Progress};
use crate::diagnostics::Diagnostics;
use marsden_problem::model::{MomentumMap, Observables};

/// Streams samples to a [`RowSink`] and accumulates [`Diagnostics`].
pub struct StreamObserver<'a, 's, L, C, M> {
    /// The continuous Lagrangian of the energy column (`None`: a file's own `L_d`, no energy).
    lagrangian: Option<&'a L>,
    constraint: &'a C,
    maps: &'a [M],
    sink: &'s mut (dyn RowSink + 's),
    every: usize,
    total: usize,
    row: Vec<f64>,
    velocity: Vec<f64>,
    scratch: Vec<f64>,
    last_written: Option<usize>,

    /// Append the velocities to each row (for the in-memory samples, see `samples`).
    with_velocity: bool,
    controls: &'a Controls<'a>,
    /// Whether `controls` has anything to look at.
    watch: bool,
    started: Instant,
    /// What was monitored so far.
    pub diagnostics: Diagnostics,
    /// The first write error (the run stops there).
    pub io_error: Option<marsden_io::Error>,
    /// Whether the run was stopped through [`Controls::stop`].
    pub interrupted: bool,
    /// Feed the diagnostics from every step, not only the stored rows (`[analysis] every_step`).
    monitor_every_step: bool,
    /// `[output] observables`: columns after the others (before the velocities).
    observables: Option<&'a Observables>,
}

/// Where a sample comes from.
#[derive(Debug, Clone, Copy)]
pub struct Sample<'s> {
    /// Steps completed.
    pub step: usize,
    /// Time.
    pub t: f64,
    /// Positions.
    pub q: &'s [f64],
    /// Momenta.
    pub p: &'s [f64],
}

/// The system a [`StreamObserver`] reads its rows from.
#[derive(Debug)]
pub struct StreamSystem<'a, L, C, M> {
    /// The Lagrangian (energy, velocities); `None` for a file's own `L_d`, whose rows have no
    /// energy and NaN velocities.
    pub lagrangian: Option<&'a L>,
    /// Number of coordinates.
    pub n: usize,
    /// The constraint (its residuals are columns of the row).
    pub constraint: &'a C,
    /// The momentum maps of the declared symmetries.
    pub maps: &'a [M],
}

/// Where a [`StreamObserver`]'s rows go, and which.
pub struct StreamRows<'s> {
    /// The sink.
    pub sink: &'s mut (dyn RowSink + 's),
    /// Whether each row is followed by the velocities.
    pub with_velocity: bool,
    /// Every `every`-th step is written (and the first and the last).
    pub every: usize,
    /// Steps of the run.
    pub total: usize,
}

impl<'a, 's, L: Lagrangian, C: Constraint, M: MomentumMap> StreamObserver<'a, 's, L, C, M> {
    /// An observer writing the rows `rows` asks for of `system`'s run, watched by `controls`.
    pub fn new(
        system: StreamSystem<'a, L, C, M>,
        rows: StreamRows<'s>,
        controls: &'a Controls<'a>,
    ) -> Self {
        let StreamSystem {
            lagrangian,
            n,
            constraint,
            maps,
        } = system;
        let StreamRows {
            sink,
            with_velocity,
            every,
            total,
        } = rows;
        Self {
            lagrangian,
            constraint,
            maps,
            sink,
            every: every.max(1),
            total,
            row: Vec::with_capacity(2 * n + 3 + maps.len()),
            velocity: vec![0.0; n],
            scratch: Vec::new(),
            last_written: None,

            with_velocity,
            controls,
            watch: controls.is_active(),
            started: Instant::now(),
            diagnostics: Diagnostics::new(maps.len(), constraint.count() > 0),
            io_error: None,
            interrupted: false,
            monitor_every_step: false,
            observables: None,
        }
    }

    /// Writes the values of `observables` at every stored state as the last columns of the
    /// file's row (NaN where the velocities are not available).
    pub fn with_observables(mut self, observables: &'a Observables) -> Self {
        self.observables = (!observables.is_empty()).then_some(observables);
        self
    }

    /// Feeds the diagnostics from every step (the summary's maxima are then over every step),
    /// at the price of the energy and the monitored quantities at each step.
    pub fn monitoring_every_step(mut self, on: bool) -> Self {
        self.monitor_every_step = on;
        self
    }

    /// The energy `⟨p, q̇⟩ − L` at `s` (NaN if the inverse Legendre transform fails), the
    /// velocities left in `self.velocity`, fed to the diagnostics; `None` without a continuous
    /// Lagrangian (the velocities are then NaN).
    fn energy(&mut self, s: Sample<'_>) -> Option<f64> {
        let Some(lagrangian) = self.lagrangian else {
            self.velocity.fill(f64::NAN);
            return None;
        };
        let energy = mechanics::energy_from_momentum(lagrangian, s.t, s.q, s.p, &mut self.velocity)
            .unwrap_or(f64::NAN);
        self.diagnostics.energy.push(s.t, energy);
        Some(energy)
    }

    /// Feeds the diagnostics with a step that is not stored (no row is written).
    fn monitor(&mut self, s: Sample<'_>) {
        let energy = self.energy(s).unwrap_or(f64::NAN);
        for (map, stats) in self.maps.iter().zip(&mut self.diagnostics.maps) {
            stats.push(map.value(s.q, s.p, &mut self.scratch));
        }
        if self.constraint.count() > 0 {
            let r = self.residual(s.q);
            self.diagnostics.push_residual(r);
            let rate = match energy.is_finite() {
                true => residuals_at(self.constraint, s.q, &self.velocity).1,
                false => f64::NAN,
            };
            self.diagnostics.push_velocity_residual(rate);
        }
        if !energy.is_finite() && self.lagrangian.is_some() {
            self.velocity.fill(0.0);
        }
    }

    /// Number of rows written.
    pub fn rows(&self) -> u64 {
        self.sink.rows_written()
    }

    /// Evaluates and writes one sample.
    pub fn record(&mut self, s: Sample<'_>) -> ControlFlow<()> {
        let energy = self.energy(s);
        let finite = energy.is_none_or(f64::is_finite);
        self.row.clear();
        self.row.push(s.t);
        self.row.extend_from_slice(s.q);
        self.row.extend_from_slice(s.p);
        self.row.extend(energy);
        for (map, stats) in self.maps.iter().zip(&mut self.diagnostics.maps) {
            let j = map.value(s.q, s.p, &mut self.scratch);
            stats.push(j);
            self.row.push(j);
        }
        let mut velocity_residual = None;
        if self.constraint.count() > 0 {
            let r = self.residual(s.q);
            self.diagnostics.push_residual(r);
            let rate = match finite {
                true => residuals_at(self.constraint, s.q, &self.velocity).1,
                false => f64::NAN,
            };
            self.diagnostics.push_velocity_residual(rate);
            velocity_residual = Some(rate);
            self.row.push(r);
            let d = self.constraint.count();
            let lambda = (self.lagrangian.filter(|_| finite))
                .map(|l| multipliers_at(l, self.constraint, s.t, s.q, &self.velocity));
            match lambda {
                Some(Ok(lambda)) => self.row.extend_from_slice(&lambda),
                _ => self.row.resize(self.row.len() + d, f64::NAN),
            }
        }
        if !finite {
            self.velocity.fill(f64::NAN);
        }
        if let Some(observables) = self.observables {
            let start = self.row.len();
            self.row.resize(start + observables.len(), f64::NAN);
            let (t, q, v, p) = (s.t, s.q, self.velocity.as_slice(), s.p);
            observables.eval_into(t, q, v, p, &mut self.row[start..]);
        }
        // The hidden constraint's residual `|Dφ(q)·v|`: the last column of the files.
        self.row.extend(velocity_residual);
        if self.with_velocity {
            match finite {
                true => self.row.extend_from_slice(&self.velocity),
                false => self
                    .row
                    .resize(self.row.len() + self.velocity.len(), f64::NAN),
            }
        }
        if !finite && self.lagrangian.is_some() {
            // A failed inverse Legendre transform leaves a poor guess behind: restart from 0.
            self.velocity.fill(0.0);
        }
        self.last_written = Some(s.step);
        match self.sink.write_row(&self.row) {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.io_error = Some(e);
                ControlFlow::Break(())
            }
        }
    }

    /// Calls the progress callback and reads the stop flag (every [`CHECK_EVERY`] steps).
    fn tick(&mut self, step: usize) -> ControlFlow<()> {
        if let Some(progress) = self.controls.progress {
            progress(self.progress(step, false));
        }
        self.stop_if_requested()
    }

    fn progress(&self, step: usize, done: bool) -> Progress {
        Progress {
            step,
            total: self.total,
            elapsed: self.started.elapsed(),
            done,
        }
    }

    fn stop_if_requested(&mut self) -> ControlFlow<()> {
        if self.controls.stop_requested() {
            self.interrupted = true;
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }

    /// After the run: the callback's last call (`done = true`) at `steps` steps.
    pub fn finish(&self, steps: usize) {
        if let Some(progress) = self.controls.progress {
            progress(self.progress(steps, true));
        }
    }

    fn residual(&mut self, q: &[f64]) -> f64 {
        self.scratch.resize(self.constraint.count(), 0.0);
        self.constraint.constraint(q, &mut self.scratch);
        self.scratch.iter().fold(
            0.0,
            |m: f64, x| if x.is_nan() { f64::NAN } else { m.max(x.abs()) },
        )
    }

    /// What this observer carries to the next step, with its files flushed and their
    /// positions ([`marsden_io::RowSink::mark`]), for a checkpoint of the run.
    ///
    /// # Errors
    /// The write error of the flush (kept in `io_error` too).
    pub fn checkpoint(&mut self) -> Result<StreamCheckpoint, String> {
        let mark = self.sink.mark().map_err(|e| {
            let message = format!("writing the trajectory failed: {e}");
            self.io_error = Some(e);
            message
        })?;
        Ok(StreamCheckpoint {
            diagnostics: self.diagnostics.clone(),
            velocity: self.velocity.clone(),
            last_written: self.last_written,
            trajectory: mark.into(),
        })
    }

    /// Restores a [`StreamObserver::checkpoint`]: the observer of a resumed run goes on as
    /// the checkpointed one would have (its sink was reopened at the checkpoint's mark).
    ///
    /// # Errors
    /// A checkpoint of another shape (number of coordinates or momentum maps).
    pub fn restore(&mut self, checkpoint: &StreamCheckpoint) -> Result<(), String> {
        let d = &checkpoint.diagnostics;
        if checkpoint.velocity.len() != self.velocity.len()
            || d.maps.len() != self.diagnostics.maps.len()
            || d.max_residual.is_some() != self.diagnostics.max_residual.is_some()
        {
            return Err("the checkpoint's monitors do not match this problem".to_owned());
        }
        self.diagnostics = checkpoint.diagnostics.clone();
        self.velocity.clone_from(&checkpoint.velocity);
        self.last_written = checkpoint.last_written;
        Ok(())
    }

    /// After the run: writes the last state of `trajectory` unless it is already on disk (a
    /// failure between two stored steps), so nothing computed is lost.
    pub fn record_last(&mut self, trajectory: &Trajectory) {
        let Some(i) = trajectory.len().checked_sub(1) else {
            return;
        };
        let step = trajectory.step_indices[i];
        if self.last_written != Some(step) && self.io_error.is_none() {
            let (t, q, p) = (trajectory.t(i), trajectory.q(i), trajectory.p(i));
            let _ = self.record(Sample { step, t, q, p });
        }
    }
}

impl<L: Lagrangian, C: Constraint, M: MomentumMap> Observer for StreamObserver<'_, '_, L, C, M> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.started = Instant::now();
        let s = Sample {
            step: 0,
            t: initial.t,
            q: initial.q,
            p: initial.p,
        };
        // A write error is kept in `io_error`; the first step then stops the run.
        let _ = self.record(s);
    }

    /// Records the step (a row at a sampled step, the monitors at every step when they watch
    /// every step), then reads the stop flag: a run stopped here has this step in its files and
    /// monitors, so the checkpoint written at the stop continues exactly.
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        if self.io_error.is_some() {
            return ControlFlow::Break(());
        }
        let s = Sample {
            step: view.step,
            t: view.t,
            q: view.q,
            p: view.p,
        };
        let sampled = view.step.is_multiple_of(self.every) || view.step == self.total;
        if sampled {
            self.record(s)?;
        } else if self.monitor_every_step {
            self.monitor(s);
        }
        match self.watch {
            true if view.step.is_multiple_of(CHECK_EVERY) => self.tick(view.step),
            true if sampled => self.stop_if_requested(),
            _ => ControlFlow::Continue(()),
        }
    }

    fn every_step(&self) -> bool {
        self.monitor_every_step
    }

    /// The next sampled step, or the next [`CHECK_EVERY`]-th step when controls are watched,
    /// whichever comes first.
    fn next_stop(&self, step: usize) -> usize {
        let sample = next_multiple(step, self.every);
        match self.watch {
            true => sample.min(next_multiple(step, CHECK_EVERY)),
            false => sample,
        }
    }
}
