//! A multibody file's run ([`MultibodyEngine`]): the constrained Lie group variational
//! integrator of the core (`marsden::lie::multibody`, [LMO08] on the bodies' groups) on the
//! file's bodies and joints, its samples streamed as rows
//! `t, <body>_R11…, <body>_Pi1…, <body>_x…, <body>_p_x…, energy, constraint_residual,
//! lambda_<joint>_<i>…, constraint_velocity_residual`, with the joints' residuals (positions
//! and rates), the attitudes' orthogonality and the total momenta monitored.
//!
//! [LMO08]: marsden#references

mod run;

use marsden::lie::invariants;
use marsden::lie::multibody::damper::Dampers;
use marsden::lie::multibody::initial;
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::state::RigidState;
use marsden::sensitivity::Tangent;
use marsden_problem::error::{Diagnostic, Error};
use marsden_problem::model::multibody::{MultibodySystem, core, dampers};
use marsden_problem::order::Plan;
use marsden_problem::problem::RunSpec;
use marsden_problem::problem::multibody::MultibodySpec;

use crate::controls::Controls;
use crate::engine::Engine;
use crate::order_runner::Results;
use crate::solve::{Destination, RunRecord};
use crate::start::Start;
use crate::tangent::TangentJob;

pub use run::MultibodyRecord;

/// The bodies and joints of a problem file.
#[derive(Debug, Clone, Copy)]
pub struct MultibodyEngine<'a>(pub &'a MultibodySpec);

/// What a run starts from.
pub(crate) struct Begin {
    pub system: MultibodySystem,
    pub joints: JointSet,
    pub dampers: Dampers,
    pub state: RigidState,
}

impl MultibodyEngine<'_> {
    /// The system, joints and initial state, projected onto the joints with `project = true`.
    ///
    /// # Errors
    /// What the core refuses (the file's checks make it unexpected), or a projection that
    /// fails (the joints cannot be closed near the initial state).
    pub(crate) fn begin(&self, spec: &RunSpec) -> Result<Begin, Diagnostic> {
        let (system, joints, state) = core(self.0, spec.initial.t0)
            .map_err(|e| Diagnostic::new(format!("the multibody system: {e}")))?;
        let state = match spec.initial.project {
            false => state,
            true => initial::project(&system, &joints, &state).map_err(|e| {
                Diagnostic::new(format!("projecting the initial state onto the joints: {e}"))
                    .help("start the bodies nearer to where the joints hold")
            })?,
        };
        Ok(Begin {
            system,
            joints,
            dampers: dampers(self.0),
            state,
        })
    }
}

impl Engine for MultibodyEngine<'_> {
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic> {
        let begin = self.begin(spec)?;
        initial::check(&begin.system, &begin.joints, &begin.state)
            .map_err(|e| Diagnostic::new(format!("the initial state: {e}")))?;
        Ok(Start {
            t: begin.state.t,
            q: begin.state.positions.clone(),
            v: Vec::new(),
            p: begin.state.linear_momenta.clone(),
            energy: invariants::energy(&begin.system, &begin.state),
            warnings: Vec::new(),
            symmetries: Vec::new(),
        })
    }

    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic> {
        let begin = self.begin(spec)?;
        run::run(self.0, spec, begin, destination, controls)
    }

    fn initial_tangent(&self, _job: TangentJob<'_>) -> Result<Tangent, String> {
        Err("derivatives of a multibody run are not available".to_owned())
    }

    fn order_study(&self, _spec: &RunSpec, _plan: &Plan) -> Result<Results, Error> {
        Err(Error::bad_input(
            Diagnostic::new("the order study of a multibody system is not available from a problem file")
                .note("the constrained LGVI's orders 2 and 4 are measured by the core's tests against a reduced-coordinate model"),
        ))
    }
}
