//! Constraint diagnostics: position residuals `‖φ(q_k)‖∞`, velocity residuals
//! `‖Dφ(q_k) · FH(t_k, q_k, p_k)‖∞` (the hidden constraint RATTLE enforces), and the multiplier
//! series.
//!
//! A SHAKE/RATTLE run keeps `φ(q_k) = 0` to the Newton tolerance at every step, with no drift
//! ([HLW06] §VII.1); with the RATTLE projection the velocity residual is at the projection's
//! tolerance too. Without the projection it is `O(h)` (SHAKE momenta are not tangent).
//!
//! [HLW06]: crate#references

use std::ops::ControlFlow;

use crate::error::Error;
use crate::mechanics;
use crate::mechanics::constraint_jacobian;
use crate::mechanics::{Constraint, Lagrangian};
use crate::numerics::dense::max_norm;
use crate::run::Trajectory;
use crate::run::{Observer, StepView};

/// Constraint residuals of a run, one entry per stored sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ConstraintReport {
    /// `‖φ(q_i)‖∞` for every sample.
    pub position: Vec<f64>,
    /// `‖Dφ(q_i) v_i‖∞` with `v_i = FH(t_i, q_i, p_i)` (empty from
    /// [`ConstraintReport::positions`]).
    pub velocity: Vec<f64>,
    /// Largest position residual.
    pub max_position: f64,
    /// Largest velocity residual (0 when not computed).
    pub max_velocity: f64,
}

/// `φ(q)`, `Dφ(q)` and both residual norms at one state.
#[derive(Debug, Clone, Default)]
struct Evaluator {
    phi: Vec<f64>,
    g: Vec<f64>,
    v: Vec<f64>,
}

impl Evaluator {
    fn position<C: Constraint>(&mut self, c: &C, q: &[f64]) -> f64 {
        let d = c.count();
        self.phi.resize(d, 0.0);
        self.g.resize(d * q.len(), 0.0);
        if d == 0 {
            return 0.0;
        }
        constraint_jacobian(c, q, &mut self.phi, &mut self.g);
        max_norm(&self.phi)
    }

    /// Velocity residual at the state whose `Dφ` was just computed by `position`.
    fn velocity<L: Lagrangian>(
        &mut self,
        l: &L,
        t: f64,
        q: &[f64],
        p: &[f64],
    ) -> Result<f64, Error> {
        let n = q.len();
        self.v.resize(n, 0.0);
        mechanics::velocity(l, t, q, p, &mut self.v)?;
        Ok(self
            .g
            .chunks_exact(n.max(1))
            .map(|row| {
                row.iter()
                    .zip(&self.v)
                    .map(|(a, b)| a * b)
                    .sum::<f64>()
                    .abs()
            })
            .fold(0.0, crate::numerics::dense::max_or_nan))
    }
}

impl ConstraintReport {
    /// Position and velocity residuals of every sample of `trajectory`.
    pub fn of<L: Lagrangian, C: Constraint>(
        lagrangian: &L,
        constraint: &C,
        trajectory: &Trajectory,
    ) -> Result<Self, Error> {
        let mut report = Self::default();
        let mut eval = Evaluator::default();
        for i in 0..trajectory.len() {
            let (t, q, p) = (trajectory.t(i), trajectory.q(i), trajectory.p(i));
            report.push_position(eval.position(constraint, q));
            let r = eval.velocity(lagrangian, t, q, p)?;
            report.max_velocity = report.max_velocity.max(r);
            report.velocity.push(r);
        }
        Ok(report)
    }

    /// Position residuals only (no Lagrangian needed).
    pub fn positions<C: Constraint>(constraint: &C, trajectory: &Trajectory) -> Self {
        let mut report = Self::default();
        let mut eval = Evaluator::default();
        for i in 0..trajectory.len() {
            report.push_position(eval.position(constraint, trajectory.q(i)));
        }
        report
    }

    fn push_position(&mut self, r: f64) {
        self.max_position = self.max_position.max(r);
        self.position.push(r);
    }
}

/// The SHAKE multipliers `λ_index` of every sample (NaN for the initial sample).
pub fn multiplier_series(trajectory: &Trajectory, index: usize) -> Vec<f64> {
    column(&trajectory.multipliers, trajectory.constraints, index)
}

/// The RATTLE projection multipliers `μ_index` of every sample (NaN where none ran).
pub fn projection_multiplier_series(trajectory: &Trajectory, index: usize) -> Vec<f64> {
    column(
        &trajectory.projection_multipliers,
        trajectory.constraints,
        index,
    )
}

/// `(‖φ(q)‖∞, ‖Dφ(q) v‖∞)` at one state given by its velocities (the hidden constraint).
pub fn residuals_at<C: Constraint>(constraint: &C, q: &[f64], v: &[f64]) -> (f64, f64) {
    let d = constraint.count();
    if d == 0 {
        return (0.0, 0.0);
    }
    let n = q.len();
    let (mut phi, mut g) = (vec![0.0; d], vec![0.0; d * n]);
    constraint_jacobian(constraint, q, &mut phi, &mut g);
    let rate = g
        .chunks_exact(n)
        .map(|row| row.iter().zip(v).map(|(a, b)| a * b).sum::<f64>().abs())
        .fold(0.0, crate::numerics::dense::max_or_nan);
    (max_norm(&phi), rate)
}

fn column(data: &[f64], width: usize, index: usize) -> Vec<f64> {
    if index >= width {
        return Vec::new();
    }
    data.chunks_exact(width).map(|row| row[index]).collect()
}

/// Streaming constraint monitor: an [`Observer`] that keeps the largest position and velocity
/// residuals of every step without storing the trajectory.
#[derive(Debug, Clone)]
pub struct ConstraintMonitor<L, C> {
    lagrangian: L,
    constraint: C,
    eval: Evaluator,
    max_position: f64,
    max_velocity: f64,
    steps: usize,
    error: Option<Error>,
}

impl<L: Lagrangian, C: Constraint> ConstraintMonitor<L, C> {
    /// A monitor for `L` and `φ`.
    pub fn new(lagrangian: L, constraint: C) -> Self {
        Self {
            lagrangian,
            constraint,
            eval: Evaluator::default(),
            max_position: 0.0,
            max_velocity: 0.0,
            steps: 0,
            error: None,
        }
    }

    /// `(max ‖φ(q_k)‖∞, max ‖Dφ(q_k) v_k‖∞)` so far, or the error that stopped the monitor.
    pub fn max_residuals(&self) -> Result<(f64, f64), &Error> {
        match &self.error {
            Some(e) => Err(e),
            None => Ok((self.max_position, self.max_velocity)),
        }
    }

    /// Number of states seen (including the initial one).
    pub fn samples(&self) -> usize {
        self.steps
    }

    fn record(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self.steps += 1;
        let r = self.eval.position(&self.constraint, view.q);
        self.max_position = self.max_position.max(r);
        match self.eval.velocity(&self.lagrangian, view.t, view.q, view.p) {
            Ok(r) => {
                self.max_velocity = self.max_velocity.max(r);
                ControlFlow::Continue(())
            }
            Err(e) => {
                self.error = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}

impl<L: Lagrangian, C: Constraint> Observer for ConstraintMonitor<L, C> {
    fn start(&mut self, initial: &StepView<'_>) {
        let _ = self.record(initial);
    }
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self.record(view)
    }
}
