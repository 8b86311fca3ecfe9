//! The tangent run of `[sensitivity]`: the file's own Lagrangian and forces ([`TangentJob`],
//! compiled with the run's own `Problem` type) or the parametric model at the file's
//! parameter values ([`WithParameters`]), watched by the caller's controls as the file's run is
//! ([`Watched`]) and checkpointed as planned ([`crate::checkpoint::tangent`]). The Jacobians it
//! hands on are picked and written by [`crate::sensitivity`].

use std::cell::RefCell;
use std::ops::ControlFlow;
use std::time::Instant;

use marsden::sensitivity::{
    ConstrainedParametricIntegrator, ParametricIntegrator, SensitiveStep, Tangent,
    TangentCheckpoint, TangentOptions, TangentSample, tangent_continued,
};
use marsden::{Lagrangian, State, TimeGrid};
use marsden_problem::model::ExprParametric;
use marsden_problem::problem::RunSpec;

use crate::checkpoint::tangent::{SensitivityCheckpoint, TangentPlan};
use crate::checkpoint::{Mark, file};
use crate::controls::{CHECK_EVERY, Controls, Progress};
use crate::start;

/// Where a tangent run's kept samples go, and what a checkpoint records of them.
pub(crate) trait SampleOut {
    /// Takes a kept sample.
    fn sample(&mut self, sample: &TangentSample);
    /// Samples taken.
    fn handed(&self) -> usize;
    /// Flushes what was taken into its file and says where the file stands (`None`: no file).
    fn mark(&mut self) -> Result<Option<Mark>, String>;
}

/// The caller's controls as a tangent run sees them, where its kept samples go, and its
/// checkpoints (`[output] checkpoint_every`, [`crate::checkpoint::tangent`]).
pub struct Watched<'c, 'a> {
    controls: &'c Controls<'a>,
    total: usize,
    clock: Instant,
    out: RefCell<&'c mut dyn SampleOut>,
    checkpoints: Option<&'c TangentPlan>,
    /// Why a checkpoint could not be written (the tangent run stopped there).
    error: RefCell<Option<String>>,
}

impl<'c, 'a> Watched<'c, 'a> {
    pub(crate) fn new(
        spec: &RunSpec,
        controls: &'c Controls<'a>,
        out: &'c mut dyn SampleOut,
        checkpoints: Option<&'c TangentPlan>,
    ) -> Self {
        Self {
            controls,
            total: spec.integrator.grid.steps,
            clock: Instant::now(),
            out: RefCell::new(out),
            checkpoints,
            error: RefCell::new(None),
        }
    }

    /// Calls the progress callback, if any.
    pub(crate) fn report(&self, step: usize, done: bool) {
        if let Some(progress) = self.controls.progress {
            progress(Progress {
                step,
                total: self.total,
                elapsed: self.clock.elapsed(),
                done,
            });
        }
    }

    /// Samples handed on (those before a checkpoint resumed from included).
    pub(crate) fn handed(&self) -> usize {
        self.out.borrow().handed()
    }

    /// Why a checkpoint could not be written, if one could not.
    pub(crate) fn checkpoint_error(&self) -> Option<String> {
        self.error.borrow().clone()
    }

    /// The tangent run of `stepper` from `state` — or from the plan's checkpoint, `stepper`
    /// restored from it — watched every [`CHECK_EVERY`] steps and checkpointed as planned.
    pub(crate) fn tangent<D: SensitiveStep + ?Sized>(
        &self,
        stepper: &mut D,
        state: State,
        spec: &RunSpec,
    ) -> Result<Tangent, marsden::Error> {
        let from = match self.checkpoints.and_then(|p| p.resume.as_deref()) {
            Some(resumed) => {
                stepper.restore_carried(&resumed.tangent.integrator)?;
                resumed.tangent.sample()
            }
            None => TangentSample::start(state, 2 * stepper.dof() + stepper.parameters()),
        };
        let active = self.controls.is_active();
        let watch = |stepper: &D, sample: &TangentSample| {
            let k = sample.step;
            if let Some(plan) = self.checkpoints
                && k.is_multiple_of(plan.every)
                && let Err(e) = self.save(plan, stepper, sample)
            {
                *self.error.borrow_mut() = Some(e);
                return ControlFlow::Break(());
            }
            if !active || !k.is_multiple_of(CHECK_EVERY) {
                return ControlFlow::Continue(());
            }
            self.report(k, false);
            if !self.controls.stop_requested() {
                return ControlFlow::Continue(());
            }
            // A signal's stop is checkpointed where it happened: the resume loses no steps.
            if let Some(plan) = self.checkpoints
                && !k.is_multiple_of(plan.every)
                && let Err(e) = self.save(plan, stepper, sample)
            {
                *self.error.borrow_mut() = Some(e);
            }
            ControlFlow::Break(())
        };
        let grid: &TimeGrid = &spec.integrator.grid;
        let mut sink = |sample: &TangentSample| self.out.borrow_mut().sample(sample);
        tangent_continued(stepper, from, grid, &options(spec), watch, &mut sink)
    }

    /// Writes the checkpoint of `stepper` at `sample` into the plan's file.
    fn save<D: SensitiveStep + ?Sized>(
        &self,
        plan: &TangentPlan,
        stepper: &D,
        sample: &TangentSample,
    ) -> Result<(), String> {
        let tangent = TangentCheckpoint::of(stepper, sample)
            .ok_or("this run's tangent integrator cannot be checkpointed")?;
        let mut out = self.out.borrow_mut();
        let checkpoint = SensitivityCheckpoint {
            identity: plan.identity.clone(),
            tangent,
            file: out.mark()?,
            samples: out.handed(),
        };
        file::save(&plan.path, &checkpoint)
    }
}

fn options(spec: &RunSpec) -> TangentOptions {
    TangentOptions {
        every: spec.output.every.max(1),
    }
}

/// The tangent run of the file's own Lagrangian and forces (`P = 0`), with the integrator type
/// of the run itself (the same [`marsden::Problem`] type as [`crate::solve::run_by_rule`]
/// builds), so the tangent run adds no integrator code to the build.
pub struct TangentJob<'a> {
    pub(crate) spec: &'a RunSpec,
    pub(crate) rule: &'a marsden::discrete::rules::Method,
    pub(crate) state: State,
    pub(crate) watched: &'a Watched<'a, 'a>,
}

impl TangentJob<'_> {
    /// Runs the job with the file's system, of type `L`.
    ///
    /// # Errors
    /// The core's error, as text.
    pub fn run_with<L: Lagrangian>(self, lagrangian: &L) -> Result<Tangent, String> {
        let s = &self.spec.system;
        let force = s.force.on(lagrangian);
        let problem = start::constrained_problem(self.spec, lagrangian, &s.constraint)
            .map_err(|d| d.to_string())?
            .with_force(&force);
        let spec = self.spec;
        let run = || {
            let integrator = problem.integrator(self.rule, spec.integrator.newton)?;
            let mut vi = integrator.with_fast_paths(false);
            self.watched.tangent(&mut vi, self.state, spec)
        };
        run().map_err(|e: marsden::Error| e.to_string())
    }
}

/// The tangent run of the parametric model at the file's parameter values.
pub(crate) struct WithParameters<'a> {
    pub(crate) spec: &'a RunSpec,
    pub(crate) model: &'a ExprParametric,
    pub(crate) state: State,
    /// The initial velocities (the constrained predictor's first guess).
    pub(crate) v: &'a [f64],
    pub(crate) watched: &'a Watched<'a, 'a>,
}

impl WithParameters<'_> {
    pub(crate) fn call(
        self,
        rule: &marsden::discrete::rules::Method,
    ) -> Result<Tangent, marsden::Error> {
        use marsden::sensitivity::ParametricModel as _;
        let spec = self.spec;
        let theta: Vec<f64> = (self.model.parameter_names().iter())
            .map(|name| {
                (spec.system.parameters.iter())
                    .find(|(n, _)| n == name)
                    .map_or(f64::NAN, |(_, v)| *v)
            })
            .collect();
        let newton = spec.integrator.newton;
        let model = self.model.clone();
        if self.model.constraints() > 0 {
            let vi = ConstrainedParametricIntegrator::new(rule, model, &theta, newton)?;
            let mut vi = vi.with_velocity_hint(self.v);
            return self.watched.tangent(&mut vi, self.state, spec);
        }
        let mut vi = ParametricIntegrator::new(rule, model, &theta, newton)?;
        self.watched.tangent(&mut vi, self.state, spec)
    }
}
