//! `summary.json`: what ran, how it ended and what it preserved (a contract: extend, don't
//! rename).
//!
//! Non-finite numbers are written as `null` (JSON has no NaN).

use std::path::Path;

use serde::Serialize;

use super::balance::BalanceSummary;
use super::certify::Certificate;
use super::noether_balance::NoetherBalance;
use super::output::SUMMARY_JSON;
use super::sensitivity::SensitivitySummary;
use super::solve::{FinalState, RunRecord};
use crate::problem::spec::ENERGY_NOT_AVAILABLE;
use marsden_engine::serialize::as_object;

pub use super::summary_bodies::{MultibodySummary, RigidBodySummary};

/// Why a forced or time-dependent run has no energy balance: the balance is that of two-point
/// rules (forces and `∂L_d/∂t₀` at `q_k`, `q_{k+1}`); a method with internal stages puts its
/// discrete forces on the stage points, which the run does not keep.
pub const BALANCE_NOT_AVAILABLE: &str = "not available for a method with internal stages (its \
     discrete forces act on stage points the run does not keep); use a two-point method \
     (midpoint, trapezoid, alpha-<a>, symmetrized-<a>) for the balance";
use crate::problem::{LagrangianSpec, RunSpec};

/// Why a rigid body driven by torques or forces (or a time-dependent potential) has no energy
/// balance.
pub const RIGID_BALANCE_NOT_AVAILABLE: &str = "not computed for a rigid body: the discrete \
     energy balance of the Lie group integrator's torques is not implemented";

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RunStatus {
    /// Every requested step was taken.
    Completed,
    /// The simulation (or writing the trajectory) failed; the samples before it are kept.
    Failed,
    /// Stopped through [`Controls::stop`](super::Controls::stop); the samples are kept.
    Interrupted,
    /// Ended by an event with `action = "stop"` (`summary.json`: `"stopped by event <name>"`).
    Stopped,
}

impl RunStatus {
    /// `"completed"`, `"failed"` or `"interrupted"`.
    pub fn name(self) -> &'static str {
        match self {
            RunStatus::Completed => "completed",
            RunStatus::Failed => "failed",
            RunStatus::Interrupted => "interrupted",
            RunStatus::Stopped => "stopped",
        }
    }

    /// A number for numeric tables (a sweep's `.npy`): 0 completed, 1 failed, 2 interrupted,
    /// 3 stopped by an event.
    pub fn code(self) -> u8 {
        match self {
            RunStatus::Completed => 0,
            RunStatus::Failed => 1,
            RunStatus::Interrupted => 2,
            RunStatus::Stopped => 3,
        }
    }

    /// The status of `record`: a failure first, then a stop by the user, then by an event.
    pub fn of(record: &RunRecord) -> Self {
        match (&record.error, record.interrupted) {
            (Some(_), _) => RunStatus::Failed,
            (None, true) => RunStatus::Interrupted,
            (None, false) if record.events.stopped_by.is_some() => RunStatus::Stopped,
            (None, false) => RunStatus::Completed,
        }
    }

    /// The status as `summary.json` writes it: the name, or `"stopped by event <name>"`.
    pub fn text(self, stopped_by: Option<&str>) -> String {
        match (self, stopped_by) {
            (RunStatus::Stopped, Some(event)) => format!("stopped by event {event}"),
            _ => self.name().to_owned(),
        }
    }
}

/// The whole summary.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// How the run ended (written as [`Summary::status_text`]).
    #[serde(skip)]
    pub status: RunStatus,
    /// `"completed"`, `"failed"`, `"interrupted"` or `"stopped by event <name>"`.
    #[serde(rename = "status")]
    pub status_text: String,
    /// The event that ended the run, by name (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_by_event: Option<String>,
    /// The failure's message, or null.
    pub error: Option<String>,
    /// The run's name.
    pub name: String,
    /// `builtin <name>` or `expression`.
    pub system: String,
    /// Coordinate names.
    pub coordinates: Vec<String>,
    /// Method name as in the problem file.
    pub method: String,
    /// Order of the method, which a constrained run keeps (the Gauss rules, which would not,
    /// are refused with constraints); `null` for `exact` (no truncation error).
    pub order: Option<u32>,
    /// Time step.
    pub h: f64,
    /// The size of the last step when `t_end` is not a whole number of steps (a shorter,
    /// still variational step ending at `t_end` exactly); absent on a uniform grid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub last_step: Option<f64>,
    /// Steps completed.
    pub steps: usize,
    /// Steps requested.
    pub steps_requested: usize,
    /// Initial time.
    pub t_initial: f64,
    /// Time of the last good state.
    pub t_final: f64,
    /// Wall-clock time of the integration (streaming included, plots excluded).
    pub wall_seconds: f64,
    /// The part of `wall_seconds` spent compiling expressions to native code (the JIT, at the
    /// first use of each tape): left out of the time per step.
    pub jit_compile_seconds: f64,
    /// Energy errors over the stored samples.
    pub energy: EnergySummary,
    /// Momentum maps, by symmetry name (in the file's order).
    #[serde(serialize_with = "as_map")]
    pub momenta: Vec<(String, MomentumSummary)>,
    /// Constraint residuals.
    pub constraints: ConstraintSummary,
    /// Newton work.
    pub newton: NewtonSummary,
    /// The last good state.
    pub final_state: FinalState,
    /// What was written.
    pub output: OutputSummary,
    /// Where the results come from.
    pub provenance: Provenance,
    /// Why the energy is not conserved (`"forces act"`, `"the Lagrangian depends on t"`), or
    /// null; when not null, `energy`'s errors are null (there is no error to measure) and
    /// `energy_balance` accounts for the change.
    pub energy_not_conserved: Option<&'static str>,
    /// Why there is no energy at all (a file's own `L_d`: no continuous L), or absent; when
    /// present, every number of `energy` is null.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_not_available: Option<&'static str>,
    /// The discrete energy balance of a forced run with a two-point method, over every step
    /// (null otherwise).
    pub energy_balance: Option<BalanceSummary>,
    /// Why a run whose energy is not conserved has no `energy_balance` (a method with internal
    /// stages), or absent.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_balance_not_available: Option<&'static str>,
    /// The forced Noether balance of every declared symmetry of a forced run with a two-point
    /// method, over every step (absent otherwise).
    #[serde(skip_serializing_if = "Vec::is_empty", serialize_with = "as_object")]
    pub noether_balance: Vec<(String, NoetherBalance)>,
    /// Certificates, with `[analysis] certify = true` (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub certificate: Option<Certificate>,
    /// `[sensitivity]`: the Jacobian of the final `(q, p)` with respect to the initial state
    /// and the named parameters (absent without `[sensitivity]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sensitivity: Option<SensitivitySummary>,
    /// A rigid body's invariants and last attitude (absent for other systems).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rigid_body: Option<RigidBodySummary>,
    /// A multibody run's joints, attitudes and momenta (absent for other systems).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub multibody: Option<MultibodySummary>,
    /// `[[events]]`: the crossings recorded, per event name in the file's order (absent
    /// without events).
    #[serde(skip_serializing_if = "Vec::is_empty", serialize_with = "as_object")]
    pub events: Vec<(String, usize)>,
    /// `[output] times`: how many were requested and how many the run reached (absent without
    /// `times`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<SamplesSummary>,
}

/// `samples { … }`: the states at `[output] times`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SamplesSummary {
    /// Times requested.
    pub requested: usize,
    /// Samples taken (fewer than requested when the run ended before the last time).
    pub taken: usize,
    /// How a time inside a step was reached: `"interpolant"` (the step's Hermite
    /// interpolant) or `"step"` (a variational step of its own size, `exact_times = true`).
    pub reached_by: &'static str,
}

/// `energy { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct EnergySummary {
    /// `E_0`.
    pub initial: f64,
    /// `max |E_k − E_0|`.
    pub max_abs_error: f64,
    /// `max |E_k − E_0| / |E_0|`.
    pub max_rel_error: f64,
    /// `(E_N − E_0) / |E_0|`.
    pub final_rel_error: f64,
    /// Least-squares slope of `E_k − E_0` against time.
    pub drift_per_unit_time: f64,
    /// Samples used (the stored states with a finite energy).
    pub samples: usize,
    /// Stored states whose energy was not finite (the run is then reported as failed).
    pub non_finite: usize,
}

/// `momenta { name: { … } }`.
#[derive(Debug, Clone, Serialize)]
pub struct MomentumSummary {
    /// `J_0`.
    pub initial: f64,
    /// `max |J_k − J_0|` over the stored states.
    pub max_abs_drift: f64,
    /// Whether the declared action was found to be a symmetry (of `L`, or of a file's own
    /// `L_d`) at every state it was checked at: only then is `J` conserved.
    pub symmetry: bool,
    /// What was checked: `"L at the initial state and 8 states near it: largest relative
    /// defect 1.2e-17"`.
    pub checked: String,
}

/// `constraints { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct ConstraintSummary {
    /// Number of constraints.
    pub count: usize,
    /// `max |φ(q_k)|` over the stored states (null without constraints).
    pub max_residual: Option<f64>,
    /// `max |Dφ(q_k)·v_k|` over the stored states, the velocity (hidden) constraint (null
    /// without constraints).
    pub max_velocity_residual: Option<f64>,
}

/// `newton { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct NewtonSummary {
    /// Newton iterations over all steps.
    pub iterations_total: usize,
    /// Most iterations in one step.
    pub iterations_max: usize,
    /// Residual tolerance used.
    pub tolerance: f64,
    /// Iteration limit per step.
    pub max_iterations: usize,
    /// Steps taken by an explicit formula (Störmer–Verlet and its compositions): no Newton
    /// system was solved for them.
    pub explicit_steps: usize,
}

/// `output { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct OutputSummary {
    /// `csv` or `npy` (`memory` when nothing was written).
    pub format: &'static str,
    /// Stored every k-th step.
    pub every: usize,
    /// Rows written.
    pub rows: u64,
    /// Column names, in order.
    pub columns: Vec<String>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
    /// Coordinates declared as angles (plots wrap them; `marsden plot` reads them here).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub angles: Vec<String>,
    /// The columns of the event records (`event, t, q_…, p_…`: `events.csv`'s header, the
    /// columns of `events.npy`); absent without `[[events]]`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub event_columns: Vec<String>,
    /// The columns of the samples at `[output] times` (`t, q_…, p_…, observables…`:
    /// `samples.csv`'s header, the columns of `samples.npy`); absent without `times`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sample_columns: Vec<String>,
    /// The names of `[output] observables` (columns of the trajectory; `marsden plot` redraws
    /// `observables.png` from them); absent without observables.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub observables: Vec<String>,
    /// The Poincaré section's axes as `[column of the event records, label]` pairs
    /// (`marsden plot` redraws `section.png` from them); absent without events.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub section: Vec<[String; 2]>,
}

/// `provenance { … }`.
#[derive(Debug, Clone, Serialize)]
pub struct Provenance {
    /// Version of marsden.
    pub marsden_version: &'static str,
    /// The problem file as given.
    pub problem_file: String,
    /// SHA-256 of the problem file.
    pub problem_sha256: String,
}

/// Serialises `(key, value)` pairs as a JSON object, keeping their order.
fn as_map<S: serde::Serializer>(
    pairs: &[(String, MomentumSummary)],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serializer.collect_map(pairs.iter().map(|(k, v)| (k, v)))
}

impl Summary {
    /// Records what the check of each declared symmetry found (in the file's order).
    pub fn set_symmetry_checks(&mut self, checks: &[super::start::SymmetryCheck]) {
        for ((name, m), check) in self.momenta.iter_mut().zip(checks) {
            if *name != check.name {
                continue;
            }
            m.symmetry = check.is_symmetry;
            if check.states == 0 {
                m.checked = format!("{} could not be checked at any state", check.of);
                continue;
            }
            m.checked = format!(
                "{} at the initial state and {} states near it: largest relative defect {:.1e}",
                check.of,
                check.states.saturating_sub(1),
                check.max_relative_defect
            );
        }
    }

    /// The summary of `record`, a run of `spec`.
    pub fn new(
        spec: &RunSpec,
        record: &RunRecord,
        columns: Vec<String>,
        files: Vec<String>,
    ) -> Self {
        let d = &record.diagnostics;
        let momenta = (spec.system.momentum_names().into_iter())
            .zip(&d.maps)
            .map(|(name, m)| {
                let value = MomentumSummary {
                    initial: m.initial,
                    max_abs_drift: m.max_abs_drift,
                    symmetry: true,
                    checked: "not checked".to_owned(),
                };
                (name, value)
            })
            .collect();
        let integrator = &spec.integrator;
        let not_conserved = spec.system.energy_not_conserved();
        // An energy error only where energy is conserved.
        let error = |x: f64| if not_conserved.is_some() { f64::NAN } else { x };
        let not_available = (!spec.system.has_energy()).then_some(ENERGY_NOT_AVAILABLE);
        let available = |x: f64| if not_available.is_some() { f64::NAN } else { x };
        let names: Vec<&str> = spec.events.events.iter().map(|e| e.name.as_str()).collect();
        let stopped_by = (record.events.stopped_by).and_then(|i| names.get(i).copied());
        let status = RunStatus::of(record);
        Summary {
            status,
            status_text: status.text(stopped_by),
            stopped_by_event: stopped_by.map(str::to_owned),
            error: record.error.clone(),
            name: spec.name.clone(),
            system: match &spec.system.lagrangian {
                LagrangianSpec::Builtin { builtin, .. } => format!("builtin {}", builtin.name()),
                LagrangianSpec::Expression(_) => "expression".to_owned(),
                LagrangianSpec::Hamiltonian(_) => "hamiltonian".to_owned(),
                LagrangianSpec::Discrete(_) => "discrete_lagrangian".to_owned(),
                LagrangianSpec::Rigid(_) => "rigid_body".to_owned(),
                LagrangianSpec::Multibody(_) => "multibody".to_owned(),
            },
            coordinates: spec.system.coordinates.clone(),
            method: spec.method_name(),
            order: spec.method_order(),
            h: integrator.grid.h,
            last_step: integrator.grid.last_step(),
            steps: record.steps,
            steps_requested: integrator.grid.steps,
            t_initial: integrator.grid.t0,
            t_final: record.final_state.t,
            wall_seconds: record.wall_seconds,
            jit_compile_seconds: record.jit_compile_seconds,
            energy: EnergySummary {
                initial: available(d.energy.report().initial),
                max_abs_error: available(error(d.energy.report().max_abs_error)),
                max_rel_error: available(error(d.energy.report().max_rel_error)),
                final_rel_error: available(error(d.energy.report().final_rel_error)),
                drift_per_unit_time: available(error(d.energy.report().drift_per_unit_time)),
                samples: d.energy.report().samples,
                non_finite: d.energy.report().failures,
            },
            momenta,
            constraints: ConstraintSummary {
                count: spec.system.constraint.components().len()
                    + spec.system.multibody().map_or(0, |m| m.joint_rows()),
                max_residual: d.max_residual,
                max_velocity_residual: d.max_velocity_residual,
            },
            newton: NewtonSummary {
                iterations_total: record.statistics.newton_iterations,
                explicit_steps: record.statistics.explicit_steps,
                iterations_max: record.statistics.max_newton_iterations,
                tolerance: integrator.newton.residual_tolerance,
                max_iterations: integrator.newton.max_iterations,
            },
            final_state: record.final_state.clone(),
            output: OutputSummary {
                format: spec.output.format.name(),
                every: spec.output.every,
                rows: record.rows,
                columns,
                files,
                angles: spec.output.angles.clone(),
                event_columns: match spec.events.events.is_empty() {
                    true => Vec::new(),
                    false => crate::run::event_outputs::event_columns(&spec.system.coordinates),
                },
                sample_columns: match spec.output.times.is_empty() {
                    true => Vec::new(),
                    false => crate::run::sampled_times::columns(spec),
                },
                observables: spec.events.observables.names.clone(),
                section: crate::run::event_outputs::section_axes(spec),
            },
            provenance: Provenance {
                marsden_version: env!("CARGO_PKG_VERSION"),
                problem_file: spec.source.path().display().to_string(),
                problem_sha256: spec.source.sha256().to_owned(),
            },
            energy_not_conserved: not_conserved,
            energy_not_available: not_available,
            energy_balance: record.balance,
            energy_balance_not_available: (not_conserved.is_some() && record.balance.is_none())
                .then_some(match &record.rigid {
                    Some(_) => RIGID_BALANCE_NOT_AVAILABLE,
                    None => BALANCE_NOT_AVAILABLE,
                }),
            noether_balance: record.noether_balance.clone(),
            certificate: record.certificate.clone(),
            sensitivity: None,
            rigid_body: record.rigid.as_ref().map(RigidBodySummary::of),
            multibody: (spec.system.multibody())
                .zip(record.multibody.as_ref())
                .map(|(bodies, record)| MultibodySummary::of(bodies, record)),
            events: (names.iter())
                .zip(&record.events.counts)
                .map(|(name, count)| ((*name).to_owned(), *count))
                .collect(),
            samples: record.samples.as_ref().map(|s| SamplesSummary {
                requested: s.requested,
                taken: s.taken,
                reached_by: match spec.output.exact_times {
                    true => "step",
                    false => "interpolant",
                },
            }),
        }
    }

    /// Writes `summary.json` into `dir`: to a temporary name first, then renamed, so the file
    /// is either whole or absent (a full disk leaves no truncated summary).
    ///
    /// # Errors
    /// The I/O error, as text naming the file.
    pub fn write(&self, dir: &Path) -> Result<(), String> {
        let path = dir.join(SUMMARY_JSON);
        let text = self.to_json()?;
        super::output::write_atomically(&path, (text + "\n").as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display()))
    }

    /// The text of `summary.json` (pretty-printed, without the final line break).
    ///
    /// # Errors
    /// Only if serialisation fails, as text.
    pub fn to_json(&self) -> Result<String, String> {
        serde_json::to_string_pretty(self).map_err(|e| e.to_string())
    }
}
