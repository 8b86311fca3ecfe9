//! A rigid body's run ([`RigidEngine`]): the Lie group variational integrator of the core
//! (`marsden::lie::lgvi`, [LLM07]) on the file's body, potential and loads, its samples streamed
//! as rows `t, R11 … R33, Pi1 … Pi3, q_x … p_z (with a mass), energy, J…`, with the energy,
//! the declared momentum maps, the Casimir `|Π|` and the orthogonality defect `max |RᵀR − I|`
//! monitored at every stored sample.
//!
//! [LLM07]: marsden#references

mod run;
mod symmetry;

use marsden::lie::body::RigidBody;
use marsden::lie::invariants;
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::sensitivity::Tangent;
use marsden_problem::error::{Diagnostic, Error};
use marsden_problem::model::rigid::{ExprRigidLoads, ExprRigidPotential};
use marsden_problem::order::Plan;
use marsden_problem::problem::rigid::{RigidInitial, RigidSpec};
use marsden_problem::problem::{InitialData, RunSpec};

use crate::controls::Controls;
use crate::engine::Engine;
use crate::order_runner::Results;
use crate::solve::{Destination, RunRecord};
use crate::start::Start;
use crate::tangent::TangentJob;

pub use run::{RigidMonitor, RigidRecord};

/// The system of a file's body: one body, the expression potential and loads.
pub type FileRigidSystem = RigidSystem<ExprRigidPotential, ExprRigidLoads>;

/// A rigid body of a problem file.
#[derive(Debug, Clone, Copy)]
pub struct RigidEngine<'a>(pub &'a RigidSpec);

impl RigidEngine<'_> {
    /// The core's system of the body.
    ///
    /// # Errors
    /// A mass the core refuses (checked when the file was read: not expected).
    pub fn system(&self) -> Result<FileRigidSystem, Diagnostic> {
        let body = match self.0.mass {
            Some(m) => RigidBody::free(self.0.inertia, m)
                .map_err(|e| Diagnostic::new(format!("rigid_body.mass: {e}")))?,
            None => RigidBody::fixed_point(self.0.inertia),
        };
        Ok(RigidSystem::new(vec![body], self.0.potential.clone()).with_loads(self.0.loads.clone()))
    }

    /// The initial state of `spec` in the core's form.
    ///
    /// # Errors
    /// Initial data the core refuses, or a file without the body's initial data.
    pub fn state(
        &self,
        spec: &RunSpec,
        system: &FileRigidSystem,
    ) -> Result<RigidState, Diagnostic> {
        let Some(RigidInitial { attitude, momentum }) = spec.initial.rigid else {
            return Err(Diagnostic::new(
                "internal error: a rigid body without its initial attitude",
            ));
        };
        let mut body = BodyInitial {
            attitude,
            angular_momentum: momentum,
            position: [0.0; 3],
            linear_momentum: [0.0; 3],
        };
        if let Some(m) = self.0.mass {
            body.position.copy_from_slice(&spec.initial.q);
            match &spec.initial.data {
                InitialData::Momentum(p) => body.linear_momentum.copy_from_slice(p),
                InitialData::Velocity(v) => {
                    for (p, v) in body.linear_momentum.iter_mut().zip(v) {
                        *p = m * v;
                    }
                }
            }
        }
        RigidState::new(system, spec.initial.t0, &[body])
            .map_err(|e| Diagnostic::new(format!("the initial state: {e}")))
    }
}

impl Engine for RigidEngine<'_> {
    fn prepare(&self, spec: &RunSpec) -> Result<Start, Diagnostic> {
        let system = self.system()?;
        let state = self.state(spec, &system)?;
        let checks = symmetry::check(self.0, &system, &state);
        let warnings = checks.iter().filter_map(symmetry::warning).collect();
        let centre = |v: &[f64]| v[..3 * usize::from(self.0.mass.is_some())].to_vec();
        let mass = self.0.mass.unwrap_or(1.0);
        let p = centre(&state.linear_momenta);
        Ok(Start {
            t: state.t,
            q: centre(&state.positions),
            v: p.iter().map(|p| p / mass).collect(),
            p,
            energy: invariants::energy(&system, &state),
            warnings,
            symmetries: checks,
        })
    }

    fn run(
        &self,
        spec: &RunSpec,
        destination: Destination<'_>,
        controls: &Controls<'_>,
    ) -> Result<RunRecord, Diagnostic> {
        let system = self.system()?;
        let state = self.state(spec, &system)?;
        run::run(
            self.0,
            spec,
            run::Begin { system, state },
            destination,
            controls,
        )
    }

    fn initial_tangent(&self, _job: TangentJob<'_>) -> Result<Tangent, String> {
        Err("derivatives of a rigid body's run are not available".to_owned())
    }

    fn order_study(&self, _spec: &RunSpec, _plan: &Plan) -> Result<Results, Error> {
        Err(Error::bad_input(
            Diagnostic::new("the order study of a rigid body is not available from a problem file")
                .note("the LGVI's orders 2, 4 and 6 are measured by the core's tests against the exact free rigid body"),
        ))
    }
}
