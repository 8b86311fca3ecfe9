//! The run of a rigid body: LGVI steps, a row per stored sample, the invariants monitored.

use marsden::Statistics;
use marsden::discrete::rules::Method as CoreMethod;
use marsden::lie::invariants;
use marsden::lie::lgvi::{Lgvi, LgviOptions};
use marsden::lie::state::RigidState;
use marsden_problem::error::Diagnostic;
use marsden_problem::model::rigid::{ExprRigidLoads, ExprRigidPotential};
use marsden_problem::problem::rigid::RigidSpec;
use marsden_problem::problem::{Method, RunSpec};

use super::FileRigidSystem;
use crate::controls::Controls;
use crate::diagnostics::{Diagnostics, MapStats};
use crate::group_loop::{GroupStepper, LoopOutcome, drive};
use crate::solve::{Destination, FinalState, RunRecord};

/// What a rigid body's run monitored besides the energy and the momentum maps.
#[derive(Debug, Clone, Default)]
pub struct RigidMonitor {
    /// `max_k max |R_kᵀR_k − I|` over the stored samples.
    pub max_orthogonality_defect: f64,
    /// The Casimir `|Π|²` at the start and its largest drift: constant for a free body
    /// (`d|Π|²/dt = 2Π·M`, and without moment the LGVI's `Π_{k+1} = F_kᵀΠ_k` is a rotation, so it
    /// stays constant to round-off).
    pub casimir: MapStats,
}

/// The rigid part of a run's record: the invariants and the last attitude.
#[derive(Debug, Clone)]
pub struct RigidRecord {
    /// The monitored invariants.
    pub monitor: RigidMonitor,
    /// The last good attitude, row-major.
    pub final_attitude: Vec<f64>,
    /// The last good body momentum `Π`.
    pub final_momentum: Vec<f64>,
}

/// The system and the initial state of a run.
pub(super) struct Begin {
    pub system: FileRigidSystem,
    pub state: RigidState,
}

/// The file's run of `body`: `spec.integrator.grid.steps` LGVI steps, rows into `destination`.
///
/// # Errors
/// Only if the core refuses the step size or the Newton options; a failed step ends the run
/// with the rows so far and the failure in the record.
pub(super) fn run(
    body: &RigidSpec,
    spec: &RunSpec,
    begin: Begin,
    destination: Destination<'_>,
    controls: &Controls<'_>,
) -> Result<RunRecord, Diagnostic> {
    let options = LgviOptions {
        newton: spec.integrator.newton,
        composition: match &spec.integrator.method {
            Method::Rule(CoreMethod::Composed(scheme, _)) => Some(*scheme),
            _ => None,
        },
    };
    let grid = spec.integrator.grid;
    let mut lgvi = Lgvi::new(begin.system, begin.state, grid.h, options)
        .map_err(|e| Diagnostic::new(format!("the rigid body's integrator: {e}")))?;
    let mut writer = Rows::new(body, destination);
    let jit_before = marsden_problem::model::jit_compile_seconds();
    let every = spec.output.every;
    let outcome = drive(&mut lgvi, grid.steps, every, controls, |l| writer.sample(l));
    let jit_compile_seconds = marsden_problem::model::jit_compile_seconds() - jit_before;
    let LoopOutcome {
        steps,
        most,
        interrupted,
        error,
        wall_seconds,
    } = outcome;
    let state = lgvi.state();
    let statistics = Statistics {
        steps,
        newton_iterations: lgvi.statistics().newton_iterations,
        max_newton_iterations: most,
        ..Statistics::default()
    };
    let mass = body.mass.is_some();
    let centre = |v: &[f64]| if mass { v[..3].to_vec() } else { Vec::new() };
    Ok(RunRecord {
        error,
        interrupted,
        steps,
        final_state: FinalState {
            t: state.t,
            q: centre(&state.positions),
            p: centre(&state.linear_momenta),
        },
        statistics,
        wall_seconds,
        jit_compile_seconds,
        rows: writer.rows,
        diagnostics: writer.diagnostics,
        balance: None,
        balance_series: None,
        noether_balance: Vec::new(),
        certificate: None,
        events: crate::events::EventTally::default(),
        samples: None,
        rigid: Some(RigidRecord {
            monitor: writer.monitor,
            final_attitude: state.rotations.clone(),
            final_momentum: state.momenta.clone(),
        }),
        multibody: None,
    })
}

impl GroupStepper for Lgvi<ExprRigidPotential, ExprRigidLoads> {
    fn advance(&mut self) -> Result<(), String> {
        self.step().map_err(|e| e.to_string())
    }
    fn iterations(&self) -> usize {
        self.statistics().newton_iterations
    }
}

/// The row writer and the monitors.
struct Rows<'b, 'd> {
    body: &'b RigidSpec,
    destination: Destination<'d>,
    row: Vec<f64>,
    rows: u64,
    diagnostics: Diagnostics,
    monitor: RigidMonitor,
}

impl<'b, 'd> Rows<'b, 'd> {
    fn new(body: &'b RigidSpec, destination: Destination<'d>) -> Self {
        Self {
            body,
            destination,
            row: Vec::with_capacity(32),
            rows: 0,
            diagnostics: Diagnostics::new(body.symmetries.len(), false),
            monitor: RigidMonitor::default(),
        }
    }

    /// Stores the state of `lgvi`; the error if the row cannot be written or the state is not
    /// finite.
    fn sample(&mut self, lgvi: &Lgvi<ExprRigidPotential, ExprRigidLoads>) -> Option<String> {
        let state = lgvi.state();
        let energy = invariants::energy(lgvi.system(), state);
        let n = if self.body.mass.is_some() { 3 } else { 0 };
        let (x, p) = (&state.positions[..n], &state.linear_momenta[..n]);
        self.row.clear();
        self.row.push(state.t);
        self.row.extend_from_slice(&state.rotations);
        self.row.extend_from_slice(&state.momenta);
        self.row.extend_from_slice(x);
        self.row.extend_from_slice(p);
        self.row.push(energy);
        for (s, stats) in self.body.symmetries.iter().zip(&mut self.diagnostics.maps) {
            let j = s.value(
                &state.rotations,
                &state.momenta,
                &state.positions,
                &state.linear_momenta,
            );
            stats.push(j);
            self.row.push(j);
        }
        if self.destination.with_velocity {
            let m = self.body.mass.unwrap_or(1.0);
            self.row.extend(p.iter().map(|p| p / m));
        }
        self.diagnostics.energy.push(state.t, energy);
        self.monitor.casimir.push(invariants::casimir(state, 0));
        let defect = invariants::orthogonality(state);
        if defect > self.monitor.max_orthogonality_defect || defect.is_nan() {
            self.monitor.max_orthogonality_defect = defect;
        }
        if let Err(e) = self.destination.sink.write_row(&self.row) {
            return Some(format!("writing the trajectory failed: {e}"));
        }
        self.rows += 1;
        (!energy.is_finite() || !self.row.iter().all(|v| v.is_finite())).then(|| {
            format!(
                "the state is not finite at t = {}: the step diverged",
                state.t
            )
        })
    }
}
