//! The run of jointed bodies: constrained LGVI steps, a row per stored sample, the joints and
//! invariants monitored.

use marsden::Statistics;
use marsden::discrete::rules::Method as CoreMethod;
use marsden::lie::invariants;
use marsden::lie::lgvi::LgviOptions;
use marsden::lie::multibody::step::MultibodyLgvi;
use marsden::lie::potential::NoLoads;
use marsden::lie::so3::Vec3;
use marsden::numerics::dense::max_norm;
use marsden_problem::error::Diagnostic;
use marsden_problem::problem::multibody::MultibodySpec;
use marsden_problem::problem::{Method, RunSpec};

use super::Begin;
use crate::balance::{BalanceSeries, BalanceSummary};
use crate::controls::Controls;
use crate::diagnostics::{Diagnostics, MapStats};
use crate::group_loop::{GroupStepper, LoopOutcome, drive};
use crate::solve::{Destination, FinalState, RunRecord};

/// The stepper of a file's system (the bodies in a uniform field with springs between them, the
/// dampers held by the stepper, no other loads).
type Stepper = MultibodyLgvi<marsden_problem::model::multibody::Potential, NoLoads>;

/// What a multibody run monitored, and where it ended.
#[derive(Debug, Clone, Default)]
pub struct MultibodyRecord {
    /// `max_k max |g(R_k, x_k)|` over the stored samples: the joints' residual.
    pub max_joint_residual: f64,
    /// `max_k max_i |R_iᵀR_i − I|` over the stored samples.
    pub max_orthogonality_defect: f64,
    /// The total angular momentum about the origin, `Σ R_iΠ_i + x_i × p_i`, per axis: conserved
    /// when the joints and the field are symmetric about that axis through the origin, and
    /// monitored otherwise.
    pub angular_momentum: [MapStats; 3],
    /// The last good attitudes, 9 per body, row-major.
    pub final_attitudes: Vec<f64>,
    /// The last good body momenta, 3 per body.
    pub final_body_momenta: Vec<f64>,
    /// The multipliers of the last step (the joints' reactions).
    pub final_multipliers: Vec<f64>,
    /// Newton iterations on the multipliers over the run.
    pub joint_iterations: usize,
}

/// The file's run: `spec.integrator.grid.steps` steps, rows into `destination`.
///
/// # Errors
/// Only if the core refuses the step size, the Newton options or the initial state (checked
/// when the file was read); a failed step ends the run with the rows so far and the failure.
pub(super) fn run(
    bodies: &MultibodySpec,
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
    let lgvi = MultibodyLgvi::new(begin.system, begin.joints, begin.state, grid.h, options)
        .map_err(|e| Diagnostic::new(format!("the multibody integrator: {e}")))?
        .with_dampers(begin.dampers);
    let mut writer = Rows::new(bodies, destination);
    let balance = (!lgvi.dampers().is_empty())
        .then(|| DamperBalance::new(&lgvi, spec.output.every, grid.steps));
    let mut stepper = Named {
        lgvi,
        bodies,
        balance,
    };
    let outcome = drive(&mut stepper, grid.steps, spec.output.every, controls, |s| {
        writer.sample(&s.lgvi)
    });
    let (lgvi, balance) = (stepper.lgvi, stepper.balance);
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
        newton_iterations: lgvi.statistics().joint_iterations,
        max_newton_iterations: most,
        ..Statistics::default()
    };
    let mut record = writer.monitor;
    record.final_attitudes.clone_from(&state.rotations);
    record.final_body_momenta.clone_from(&state.momenta);
    record.final_multipliers = lgvi.multipliers().to_vec();
    record.joint_iterations = lgvi.statistics().joint_iterations;
    Ok(RunRecord {
        error,
        interrupted,
        steps,
        final_state: FinalState {
            t: state.t,
            q: state.positions.clone(),
            p: state.linear_momenta.clone(),
        },
        statistics,
        wall_seconds,
        // No expression of a multibody file is compiled to native code.
        jit_compile_seconds: 0.0,
        rows: writer.rows,
        diagnostics: writer.diagnostics,
        balance: balance.as_ref().map(|b| b.summary),
        balance_series: balance.map(|b| b.series),
        noether_balance: Vec::new(),
        certificate: None,
        events: crate::events::EventTally::default(),
        samples: None,
        rigid: None,
        multibody: Some(record),
    })
}

/// The stepper, with the file's names for its failures and the dampers' balance.
struct Named<'b> {
    lgvi: Stepper,
    bodies: &'b MultibodySpec,
    balance: Option<DamperBalance>,
}

impl GroupStepper for Named<'_> {
    fn advance(&mut self) -> Result<(), String> {
        (self.lgvi.step()).map_err(|e| with_joint_name(self.bodies, &self.lgvi, e.to_string()))?;
        if let Some(balance) = &mut self.balance {
            balance.step(&self.lgvi);
        }
        Ok(())
    }
    fn iterations(&self) -> usize {
        self.lgvi.statistics().joint_iterations
    }
}

/// The energy balance of the dampers, step by step: `D_k = E_{k+1} − E_k − W_k` with the
/// dampers' work by the trapezoidal rule on their power, `W_k = (h/2)(P_k + P_{k+1})`,
/// `P = −Σ c (ḋ·e)² ≤ 0` at the state ([`marsden::lie::multibody::damper`]), as the step
/// applies their loads: `(h/2) f` at each end. Both sides are second-order, so the defect is
/// `O(h³)` per step, the method's energy error included (the same reading as the forced runs'
/// balance, [`crate::balance`]).
struct DamperBalance {
    summary: BalanceSummary,
    series: BalanceSeries,
    /// `E_k`, `P_k` of the last state.
    energy: f64,
    power: f64,
    h: f64,
    step: usize,
}

impl DamperBalance {
    fn new(lgvi: &Stepper, every: usize, steps: usize) -> Self {
        let (energy, power) = Self::at(lgvi);
        Self {
            summary: BalanceSummary::default(),
            series: BalanceSeries::new(every, steps),
            energy,
            power,
            h: lgvi.h(),
            step: 0,
        }
    }

    /// `(E, P)` at the stepper's state.
    fn at(lgvi: &Stepper) -> (f64, f64) {
        let state = lgvi.state();
        let energy = invariants::energy(lgvi.system(), state);
        (energy, lgvi.dampers().power(&lgvi.system().bodies, state))
    }

    fn step(&mut self, lgvi: &Stepper) {
        let (energy, power) = Self::at(lgvi);
        let work = 0.5 * self.h * (self.power + power);
        self.summary.push(energy - self.energy, work, None);
        self.step += 1;
        self.series.push(self.step, lgvi.state().t, &self.summary);
        (self.energy, self.power) = (energy, power);
    }
}

/// A step failure's message with the joint of a constraint row named.
fn with_joint_name(bodies: &MultibodySpec, lgvi: &Stepper, message: String) -> String {
    let joints = lgvi.joints();
    let worst = (0..joints.rows()).max_by(|&a, &b| {
        let v = &lgvi.joint_rows().values;
        v[a].abs().total_cmp(&v[b].abs())
    });
    match worst.map(|k| joints.joint_of_row(k)) {
        Some(j) if message.contains("constraint") => {
            format!(
                "{message} (the joints' rows are numbered in the file's order; joint `{}` holds the worst at the step's start)",
                bodies.joints[j].name
            )
        }
        _ => message,
    }
}

/// The row writer and the monitors.
struct Rows<'b, 'd> {
    bodies: &'b MultibodySpec,
    destination: Destination<'d>,
    row: Vec<f64>,
    rows: u64,
    diagnostics: Diagnostics,
    monitor: MultibodyRecord,
    /// Scratch of the velocity residual: `J⁻¹Π`, `p/m` per body, the rows' rates.
    omega: Vec<Vec3>,
    velocity: Vec<Vec3>,
    rates: Vec<f64>,
}

impl<'b, 'd> Rows<'b, 'd> {
    fn new(bodies: &'b MultibodySpec, destination: Destination<'d>) -> Self {
        Self {
            bodies,
            destination,
            row: Vec::with_capacity(64),
            rows: 0,
            diagnostics: Diagnostics::new(0, true),
            monitor: MultibodyRecord::default(),
            omega: Vec::new(),
            velocity: Vec::new(),
            rates: Vec::new(),
        }
    }

    /// The hidden constraint's residual `max_k |Σ_i ∂g_k/∂ξ_i · J_i⁻¹Π_i + ∂g_k/∂x_i · p_i/m_i|`:
    /// the rates of the joints' rows, which the RATTLE projection sets to zero.
    fn velocity_residual(&mut self, lgvi: &Stepper) -> f64 {
        let state = lgvi.state();
        let bodies = &lgvi.system().bodies;
        self.omega.clear();
        self.velocity.clear();
        for (i, body) in bodies.iter().enumerate() {
            self.omega.push(body.inertia.inverse() * state.momentum(i));
            self.velocity
                .push(state.linear_momentum(i) / body.mass.unwrap_or(1.0));
        }
        self.rates.resize(lgvi.joints().rows(), 0.0);
        lgvi.joints().rates(
            lgvi.joint_rows(),
            &self.omega,
            &self.velocity,
            &mut self.rates,
        );
        max_norm(&self.rates)
    }

    /// Stores the state of `lgvi`; the error if the row cannot be written or the state is not
    /// finite.
    fn sample(&mut self, lgvi: &Stepper) -> Option<String> {
        let state = lgvi.state();
        let energy = invariants::energy(lgvi.system(), state);
        let residual = max_norm(&lgvi.joint_rows().values);
        self.row.clear();
        self.row.push(state.t);
        // Attitudes and body momenta of the bodies; a particle has none.
        for (i, body) in self.bodies.bodies.iter().enumerate() {
            if !body.particle {
                self.row
                    .extend_from_slice(&state.rotations[9 * i..9 * i + 9]);
            }
        }
        for (i, body) in self.bodies.bodies.iter().enumerate() {
            if !body.particle {
                self.row.extend_from_slice(&state.momenta[3 * i..3 * i + 3]);
            }
        }
        self.row.extend_from_slice(&state.positions);
        self.row.extend_from_slice(&state.linear_momenta);
        self.row.push(energy);
        self.row.push(residual);
        self.row.extend_from_slice(lgvi.multipliers());
        let rate = self.velocity_residual(lgvi);
        self.row.push(rate);
        if self.destination.with_velocity {
            for (i, body) in self.bodies.bodies.iter().enumerate() {
                let p = &state.linear_momenta[3 * i..3 * i + 3];
                self.row.extend(p.iter().map(|p| p / body.mass));
            }
        }
        self.diagnostics.energy.push(state.t, energy);
        self.diagnostics.push_residual(residual);
        self.diagnostics.push_velocity_residual(rate);
        let momentum = invariants::spatial_angular_momentum(state);
        for (stats, value) in self
            .monitor
            .angular_momentum
            .iter_mut()
            .zip(momentum.iter())
        {
            stats.push(*value);
        }
        let record = &mut self.monitor;
        if residual > record.max_joint_residual || residual.is_nan() {
            record.max_joint_residual = residual;
        }
        let defect = invariants::orthogonality(state);
        if defect > record.max_orthogonality_defect || defect.is_nan() {
            record.max_orthogonality_defect = defect;
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
