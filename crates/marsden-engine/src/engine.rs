//! The seam between a checked problem file and the code generic over its Lagrangian.
//!
//! Everything that steps a system is generic over the Lagrangian type `L`, so that the
//! integrator's hot loops are compiled for each system (`marsden::Lagrangian` is not
//! object-safe, by design: its methods take any scalar type). A problem file names its system
//! at run time. The [`Engine`] trait is where the two meet: an object-safe interface with one
//! method per computation a file asks for, implemented once, generically, by [`Typed`] (a
//! Lagrangian with its rule-based runs), [`ExactRun`] (`method = "exact"`, the shooting) and
//! [`DiscreteEngine`] (a file's own `L_d`). Which implementation, for which type, is chosen in
//! one place — the factory of the crate above this one — and the code for each type is
//! compiled where that factory names the type: the catalog's systems in one crate, the
//! expression systems in another, side by side.
//!
//! The caller holds a `Box<dyn Engine>` and calls through it: one indirect call per run, per
//! initial state, per order study; none per step.

use marsden::Lagrangian;
use marsden::sensitivity::Tangent;

use crate::controls::Controls;
use crate::order_runner::Results;
use crate::solve::{Destination, RunRecord};
use crate::start::Start;
use crate::tangent::TangentJob;
use marsden_problem::error::{Diagnostic, Error};
use marsden_problem::model::ExprDiscreteLagrangian;
use marsden_problem::order::Plan;
use marsden_problem::problem::RunSpec;

/// The computations of a problem file on its system, whichever type the system has.
pub trait Engine {
    /// The complete initial state (`p` from `v` or back, projection onto the constraints),
    /// checked for regularity, with the warnings of the symmetry checks.
    ///
    /// # Errors
    /// The core's objection, pointing at the Lagrangian or the initial data.
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic>;

    /// The run of `spec`, its rows streamed into `destination`, watched by `controls`.
    ///
    /// # Errors
    /// Only if the core rejects the initial state; a failing run is a [`RunRecord`] with an
    /// error message.
    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic>;

    /// The tangent run of the file's own Lagrangian and forces (derivatives with respect to
    /// the initial state only).
    ///
    /// # Errors
    /// The core's error (a step that failed, a rule whose step cannot be differentiated), as
    /// text.
    fn initial_tangent(&self, job: TangentJob<'_>) -> Result<Tangent, String>;

    /// The order study of `plan` on the file's problem.
    ///
    /// # Errors
    /// Status 2 for initial data the core rejects; status 1 if the reference solution cannot
    /// be computed.
    fn order_study(&self, spec: &RunSpec, plan: &Plan) -> Result<Results, Error>;
}

/// A Lagrangian of type `L`: every computation with the core's rules. A file whose method is
/// `exact` runs through [`ExactRun`] instead (the factory wraps this engine in one).
#[derive(Debug, Clone, Copy)]
pub struct Typed<'a, L>(pub &'a L);

impl<L: Lagrangian> Engine for Typed<'_, L> {
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic> {
        crate::start::prepare_with(spec, self.0)
    }

    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic> {
        match spec.integrator.method.rule() {
            Some(rule) => crate::solve::run_by_rule(spec, rule, self.0, destination, controls),
            None => Err(Diagnostic::new(
                "internal error: an `exact` run reached the rule-based engine",
            )),
        }
    }

    fn initial_tangent(&self, job: TangentJob<'_>) -> Result<Tangent, String> {
        job.run_with(self.0)
    }

    fn order_study(&self, spec: &RunSpec, plan: &Plan) -> Result<Results, Error> {
        crate::order_runner::study_with(spec, plan, self.0)
    }
}

/// `method = "exact"`: the run steps `L_d^E` of `L` by shooting; every other computation is
/// `rest`'s (the system's own engine). The shooting evaluates `L` thousands of times per step,
/// so a catalog system runs it through the one forwarding type
/// [`marsden_problem::catalog::BuiltinSystem`]: compiled once for the catalog, not once per system.
pub struct ExactRun<'a, L> {
    /// The Lagrangian the shooting integrates.
    pub lagrangian: &'a L,
    /// The system's own engine, for everything but the run.
    pub rest: Box<dyn Engine + 'a>,
}

impl<L: Lagrangian> Engine for ExactRun<'_, L> {
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic> {
        self.rest.prepare(spec)
    }

    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic> {
        crate::solve::run_exact(spec, self.lagrangian, destination, controls)
    }

    fn initial_tangent(&self, job: TangentJob<'_>) -> Result<Tangent, String> {
        self.rest.initial_tangent(job)
    }

    fn order_study(&self, spec: &RunSpec, plan: &Plan) -> Result<Results, Error> {
        self.rest.order_study(spec, plan)
    }
}

/// A file's own discrete Lagrangian: no continuous `L`, so no energy, no tangent run of `L`
/// and no order study; each method says what it can do without one.
#[derive(Debug, Clone, Copy)]
pub struct DiscreteEngine<'a>(pub &'a ExprDiscreteLagrangian);

impl Engine for DiscreteEngine<'_> {
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic> {
        crate::start::prepare_discrete(spec, self.0)
    }

    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic> {
        crate::discrete::run(self.0, spec, destination, controls)
    }

    /// Refused when the file was read; said again here in case a caller builds the spec.
    fn initial_tangent(&self, _: TangentJob<'_>) -> Result<Tangent, String> {
        Err("[sensitivity] cannot be used with `discrete_lagrangian`".to_owned())
    }

    /// A file's own `L_d` is one method at one order nobody stated: there is no family of
    /// rules to compare, and no continuous `L` for the reference solution.
    fn order_study(&self, spec: &RunSpec, _: &Plan) -> Result<Results, Error> {
        Err(Error::bad_input(
            Diagnostic::new(
                "`marsden order` cannot study a `discrete_lagrangian` file: the reference \
                 solution and the rules are computed from a continuous L",
            )
            .at(spec.source.locate_opt(spec.spans.lagrangian.clone()))
            .help("write the Lagrangian as `lagrangian = \"…\"` to study the rules' orders"),
        ))
    }
}
