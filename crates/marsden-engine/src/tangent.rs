//! The tangent run of `[sensitivity]`: the file's own Lagrangian and forces ([`TangentJob`],
//! compiled with the run's own `Problem` type) or the parametric model at the file's
//! parameter values ([`WithParameters`]), watched by the caller's controls as the file's run is
//! ([`Watched`]). The Jacobians it hands on are picked and written by [`crate::sensitivity`].

use std::cell::RefCell;
use std::ops::ControlFlow;
use std::time::Instant;

use marsden::sensitivity::{
    ConstrainedParametricIntegrator, ParametricIntegrator, SensitiveStep, Tangent, TangentOptions,
    TangentSample, tangent_streamed,
};
use marsden::{Lagrangian, State, TimeGrid};
use marsden_problem::model::ExprParametric;
use marsden_problem::problem::RunSpec;

use crate::controls::{CHECK_EVERY, Controls, Progress};
use crate::start;

/// The caller's controls as a tangent run sees them, and where its stored samples go.
pub struct Watched<'c, 'a> {
    controls: &'c Controls<'a>,
    total: usize,
    clock: Instant,
    sink: RefCell<&'c mut dyn FnMut(&TangentSample)>,
}

impl<'c, 'a> Watched<'c, 'a> {
    pub(crate) fn new(
        spec: &RunSpec,
        controls: &'c Controls<'a>,
        sink: &'c mut dyn FnMut(&TangentSample),
    ) -> Self {
        Self {
            controls,
            total: spec.integrator.grid.steps,
            clock: Instant::now(),
            sink: RefCell::new(sink),
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

    /// The tangent run of `stepper`, watched every [`CHECK_EVERY`] steps.
    pub(crate) fn tangent<D: SensitiveStep + ?Sized>(
        &self,
        stepper: &mut D,
        state: State,
        spec: &RunSpec,
    ) -> Result<Tangent, marsden::Error> {
        let active = self.controls.is_active();
        let watch = |k: usize| {
            if !active || !k.is_multiple_of(CHECK_EVERY) {
                return ControlFlow::Continue(());
            }
            self.report(k, false);
            match self.controls.stop_requested() {
                true => ControlFlow::Break(()),
                false => ControlFlow::Continue(()),
            }
        };
        let grid: &TimeGrid = &spec.integrator.grid;
        let mut sink = self.sink.borrow_mut();
        tangent_streamed(stepper, state, grid, &options(spec), watch, &mut **sink)
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
