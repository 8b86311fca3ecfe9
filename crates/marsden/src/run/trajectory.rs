//! The solution of a run: stored samples of `(t, q, p)`, multipliers, per-step reports, the work
//! statistics and why the run ended.

use crate::error::Error;
use crate::integrator::{Statistics, StepReport};

/// Why a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Termination {
    /// All requested steps were taken.
    Completed,
    /// An observer asked to stop after this many steps.
    Stopped {
        /// Steps completed.
        steps: usize,
    },
    /// A step failed; the trajectory holds everything up to the last good state.
    Failed(Error),
    /// A stopping event fired ([`crate::run::events`]): the run ends with the step inside
    /// which the event was located; the event's own record holds the located state.
    Event {
        /// Index of the event in the detector's list.
        event: usize,
        /// Steps completed (the event lies inside the last one).
        steps: usize,
        /// The located time of the event (`t_{steps−1} ≤ t ≤ t_steps`).
        t: f64,
    },
}

/// The multipliers of the step that ended at a sample ([`Trajectory::push_sample`]): `λ` of
/// the constrained discrete Euler–Lagrange equations and `μ` of the momentum projection, each
/// of length d; a slice of another length (e.g. empty: none computed) is stored as NaN.
#[derive(Debug, Clone, Copy)]
pub struct StepMultipliers<'a> {
    /// `λ` (length d).
    pub lambda: &'a [f64],
    /// `μ` (length d).
    pub mu: &'a [f64],
}

/// Stored samples of a run (every `stride`-th step, plus the first and the last state).
///
/// Samples are row-major: sample `i` has positions `q(i)` (length n), momenta `p(i)`,
/// multipliers `multipliers(i)` (length d: the SHAKE multipliers `λ` of the step that ended at
/// sample `i`; NaN for the initial sample) and `projection_multipliers(i)` (length d: the RATTLE
/// multipliers `μ` of that step, `p_{k+1} = p̃_{k+1} − h Dφ(q_{k+1})ᵀμ_k`; NaN for the initial
/// sample and when no projection ran; see [`crate::holonomic`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// Degrees of freedom n.
    pub dof: usize,
    /// Number of constraints d.
    pub constraints: usize,
    /// Time step.
    pub h: f64,
    /// Sample times.
    pub times: Vec<f64>,
    /// Positions, `len() × n`.
    pub positions: Vec<f64>,
    /// Momenta, `len() × n`.
    pub momenta: Vec<f64>,
    /// Multipliers `λ`, `len() × d`.
    pub multipliers: Vec<f64>,
    /// Projection multipliers `μ`, `len() × d`.
    pub projection_multipliers: Vec<f64>,
    /// Report of the step that ended at each sample (default for the initial sample).
    pub reports: Vec<StepReport>,
    /// Index of the step that ended at each sample (0 for the initial state).
    pub step_indices: Vec<usize>,
    /// Steps completed.
    pub steps: usize,
    /// Work counters of the whole run.
    pub statistics: Statistics,
    /// Why the run ended.
    pub termination: Termination,
}

/// A run that failed, with everything computed up to the failure.
#[derive(Debug, Clone, PartialEq)]
pub struct RunFailure {
    /// What went wrong.
    pub error: Error,
    /// The trajectory up to the last good state.
    pub trajectory: Trajectory,
}

impl std::fmt::Display for RunFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ({} steps completed, last good state at t = {})",
            self.error,
            self.trajectory.steps,
            self.trajectory.times.last().copied().unwrap_or(f64::NAN)
        )
    }
}

impl std::error::Error for RunFailure {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl Trajectory {
    /// An empty trajectory for a system with `dof` coordinates and `constraints` constraints.
    pub fn new(dof: usize, constraints: usize, h: f64) -> Self {
        Self {
            dof,
            constraints,
            h,
            times: Vec::new(),
            positions: Vec::new(),
            momenta: Vec::new(),
            multipliers: Vec::new(),
            projection_multipliers: Vec::new(),
            reports: Vec::new(),
            step_indices: Vec::new(),
            steps: 0,
            statistics: Statistics::default(),
            termination: Termination::Completed,
        }
    }

    /// Number of stored samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether no sample is stored.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Time of sample `i`.
    pub fn t(&self, i: usize) -> f64 {
        self.times[i]
    }

    /// Positions of sample `i`.
    pub fn q(&self, i: usize) -> &[f64] {
        &self.positions[i * self.dof..(i + 1) * self.dof]
    }

    /// Momenta of sample `i`.
    pub fn p(&self, i: usize) -> &[f64] {
        &self.momenta[i * self.dof..(i + 1) * self.dof]
    }

    /// Multipliers of the step that ended at sample `i`.
    pub fn multipliers(&self, i: usize) -> &[f64] {
        &self.multipliers[i * self.constraints..(i + 1) * self.constraints]
    }

    /// Projection multipliers `μ` of the step that ended at sample `i`.
    pub fn projection_multipliers(&self, i: usize) -> &[f64] {
        &self.projection_multipliers[i * self.constraints..(i + 1) * self.constraints]
    }

    /// Appends a sample (without projection multipliers: stored as NaN).
    pub fn push(
        &mut self,
        step: usize,
        t: f64,
        q: &[f64],
        p: &[f64],
        lambda: &[f64],
        report: StepReport,
    ) {
        let multipliers = StepMultipliers { lambda, mu: &[] };
        self.push_sample(step, t, q, p, multipliers, report);
    }

    /// Appends a sample `(t, q, p)` with the multipliers of the step that ended there.
    pub fn push_sample(
        &mut self,
        step: usize,
        t: f64,
        q: &[f64],
        p: &[f64],
        multipliers: StepMultipliers<'_>,
        report: StepReport,
    ) {
        let StepMultipliers { lambda, mu } = multipliers;
        self.step_indices.push(step);
        self.times.push(t);
        self.positions.extend_from_slice(q);
        self.momenta.extend_from_slice(p);
        for (store, x) in [
            (&mut self.multipliers, lambda),
            (&mut self.projection_multipliers, mu),
        ] {
            if x.len() == self.constraints {
                store.extend_from_slice(x);
            } else {
                store.extend(std::iter::repeat_n(f64::NAN, self.constraints));
            }
        }
        self.reports.push(report);
    }

    /// Whether the run completed all its steps.
    pub fn is_complete(&self) -> bool {
        self.termination == Termination::Completed
    }

    /// `Ok(self)` unless the run failed, in which case the error comes with the trajectory.
    pub fn into_result(self) -> Result<Trajectory, Box<RunFailure>> {
        match &self.termination {
            Termination::Failed(error) => Err(Box::new(RunFailure {
                error: error.clone(),
                trajectory: self,
            })),
            _ => Ok(self),
        }
    }
}
