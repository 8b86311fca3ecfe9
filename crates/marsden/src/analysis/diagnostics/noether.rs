//! Noether diagnostics: momentum maps along a run, and how far they drift.
//!
//! Concept of the notes (MW01): *Noether's theorem* and *discrete Lagrangian Noether's theorem*. If
//! `L_d` is invariant under a group action, the discrete momentum map
//! `J_k = J_H(q_k, p_k) = ⟨p_k, ξ_Q(q_k)⟩` (with the discrete momenta `p_k = F^±L_d`, which are
//! exactly what a trajectory stores) is constant along discrete trajectories ([MW01] Thm 1.3.3;
//! [conventions](crate#conventions)) — up to the Newton residual left in each step, which moves it
//! by `⟨r_k, ξ_Q(q_k)⟩`. This module reports the series `J_k` of every declared momentum map and
//! its maximum drift, in batch from a [`Trajectory`] or streaming as an [`Observer`]; see
//! [`super::balance`] for forced systems.
//!
//! [MW01]: crate#references

use std::ops::ControlFlow;

use crate::error::Error;
use crate::run::Trajectory;
use crate::run::{Observer, StepView};
use crate::symmetry::{GroupAction, momentum_map, validate};

/// Drift of one momentum map over a run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NoetherReport {
    /// Name of the group action.
    pub symmetry: String,
    /// `J₀` (length m = dimension of the Lie algebra).
    pub initial: Vec<f64>,
    /// `J` at the last sample.
    pub last: Vec<f64>,
    /// `max_k |J_k,a − J₀,a|` for each component `a`.
    pub component_drift: Vec<f64>,
    /// `max_k ‖J_k − J₀‖₂`.
    pub max_drift: f64,
    /// `max_drift / ‖J₀‖₂` (relative to 1 when `J₀ = 0`).
    pub max_rel_drift: f64,
    /// Number of samples.
    pub samples: usize,
}

impl NoetherReport {
    fn new(symmetry: String) -> Self {
        Self {
            symmetry,
            ..Self::default()
        }
    }

    fn push(&mut self, j: &[f64]) {
        if self.samples == 0 {
            self.initial = j.to_vec();
            self.component_drift = vec![0.0; j.len()];
        }
        self.samples += 1;
        self.last = j.to_vec();
        let mut d2 = 0.0;
        for (a, (x, x0)) in j.iter().zip(&self.initial).enumerate() {
            let d = x - x0;
            self.component_drift[a] = self.component_drift[a].max(d.abs());
            d2 += d * d;
        }
        self.max_drift = self.max_drift.max(d2.sqrt());
        let norm = self.initial.iter().map(|x| x * x).sum::<f64>().sqrt();
        self.max_rel_drift = self.max_drift / if norm > 0.0 { norm } else { 1.0 };
    }

    /// The report of `action`'s momentum map along `trajectory`.
    pub fn of<G: GroupAction>(action: &G, trajectory: &Trajectory) -> Result<Self, Error> {
        let series = momentum_series(action, trajectory)?;
        let mut report = Self::new(action.name());
        series
            .chunks_exact(action.algebra_dim().max(1))
            .for_each(|j| report.push(j));
        Ok(report)
    }

    /// One report per declared symmetry.
    pub fn all<G: GroupAction>(actions: &[G], trajectory: &Trajectory) -> Result<Vec<Self>, Error> {
        actions.iter().map(|g| Self::of(g, trajectory)).collect()
    }
}

/// The series `J_k = J_H(q_k, p_k)` at every stored sample, row-major `samples × m`.
///
/// Errors if the action does not fit the trajectory's system
/// ([`crate::error::InputError::SymmetryDimension`]) or its generators are not finite at the first
/// sample ([`crate::error::InputError::InvalidGenerator`]).
pub fn momentum_series<G: GroupAction>(
    action: &G,
    trajectory: &Trajectory,
) -> Result<Vec<f64>, Error> {
    let m = action.algebra_dim();
    let q0 = if trajectory.is_empty() {
        vec![0.0; trajectory.dof]
    } else {
        trajectory.q(0).to_vec()
    };
    validate(action, trajectory.dof, &q0)?;
    let mut out = vec![0.0; trajectory.len() * m];
    for (i, j) in out
        .chunks_exact_mut(m.max(1))
        .enumerate()
        .take(trajectory.len())
    {
        momentum_map(action, trajectory.q(i), trajectory.p(i), j);
    }
    Ok(out)
}

/// Streaming Noether monitor: an [`Observer`] that follows every declared momentum map step by
/// step without storing the trajectory.
#[derive(Debug, Clone)]
pub struct NoetherMonitor<G> {
    actions: Vec<G>,
    reports: Vec<NoetherReport>,
    buffer: Vec<f64>,
    error: Option<Error>,
}

impl<G: GroupAction> NoetherMonitor<G> {
    /// A monitor of the momentum maps of `actions` (e.g. a system's
    /// [`crate::symmetry::DeclaresSymmetries::symmetries`]).
    pub fn new(actions: Vec<G>) -> Self {
        let reports = actions
            .iter()
            .map(|g| NoetherReport::new(g.name()))
            .collect();
        Self {
            actions,
            reports,
            buffer: Vec::new(),
            error: None,
        }
    }

    /// The reports so far (one per action), or the error that stopped the monitor.
    pub fn reports(&self) -> Result<&[NoetherReport], &Error> {
        match &self.error {
            Some(e) => Err(e),
            None => Ok(&self.reports),
        }
    }

    fn record(&mut self, view: &StepView<'_>) {
        for (g, r) in self.actions.iter().zip(&mut self.reports) {
            self.buffer.resize(g.algebra_dim(), 0.0);
            momentum_map(g, view.q, view.p, &mut self.buffer);
            r.push(&self.buffer);
        }
    }
}

impl<G: GroupAction> Observer for NoetherMonitor<G> {
    fn start(&mut self, initial: &StepView<'_>) {
        let checked: Result<(), Error> = self
            .actions
            .iter()
            .try_for_each(|g| validate(g, initial.q.len(), initial.q));
        match checked {
            Ok(()) => self.record(initial),
            Err(e) => self.error = Some(e),
        }
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        if self.error.is_some() {
            return ControlFlow::Break(());
        }
        self.record(view);
        ControlFlow::Continue(())
    }
}
