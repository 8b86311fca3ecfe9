//! The forced Noether balance of a run, step by step while it runs: what `summary.json` reports
//! as `noether_balance` for every declared symmetry of a forced run.
//!
//! With forces, the discrete momentum map `J_k = ⟨p_k, ξ_Q(q_k)⟩` is not conserved; by the
//! discrete forced Noether theorem ([MW01] §3.2, Thm 3.2.1 with forces; the core's
//! [`marsden::analysis::diagnostics::balance`]) its change over one step is the discrete
//! impulse of the step's own discrete forces `f_d^±` along the generator,
//!
//! ```text
//!     J_{k+1} − J_k = ⟨f_d⁻(q_k, q_{k+1}), ξ_Q(q_k)⟩ + ⟨f_d⁺(q_k, q_{k+1}), ξ_Q(q_{k+1})⟩ =: I_k,
//! ```
//!
//! exactly when `L_d` is invariant. The defect `D_k = J_{k+1} − J_k − I_k` is then at round-off
//! plus the Newton residual; for a declared action that is not a symmetry of `L_d` it is the
//! change the forces do not account for. Like the energy balance ([`crate::balance`]) this
//! applies to two-point rules only and sees every step (the core's
//! [`BalanceMonitor`], wrapped around the run's own observer).
//!
//! [MW01]: marsden#references

use std::ops::ControlFlow;

use marsden::analysis::diagnostics::{BalanceMonitor, BalanceReport, MonitorCarry};
use marsden::discrete::DiscreteForce;
use marsden::symmetry::GroupAction;
use marsden::{Observer, StepView, TimeGrid};
use serde::Serialize;

/// `noether_balance { <symmetry>: { … } }` of `summary.json`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct NoetherBalance {
    /// `Σ_k I_k`, the discrete impulse of the forces along the generator over the run.
    pub total_impulse: f64,
    /// `J_N − J_0`, accumulated step by step.
    pub momentum_change: f64,
    /// `max_k |D_k|`.
    pub max_defect: f64,
    /// The same relative to `max(|J_k|, |J_{k+1}|, |I_k|)` of the worst step.
    pub max_rel_defect: f64,
    /// `Σ_k D_k = J_N − J_0 − Σ_k I_k`, the change the impulse does not account for.
    pub total_defect: f64,
    /// Steps in the balance (every step of the run).
    pub steps: usize,
}

impl NoetherBalance {
    /// The summary of the core's report (first component of the Lie algebra: a problem file's
    /// symmetries are one-parameter groups).
    fn of(report: &BalanceReport) -> Self {
        let first = |v: &[f64]| v.first().copied().unwrap_or(0.0);
        let (change, impulse) = (first(&report.total_change), first(&report.total_impulse));
        Self {
            total_impulse: impulse,
            momentum_change: change,
            max_defect: report.max_residual,
            max_rel_defect: report.max_rel_residual,
            total_defect: change - impulse,
            steps: report.steps,
        }
    }
}

/// An observer that checks the forced Noether balance of every action at every step and hands
/// every step on to the run's own observer.
pub struct NoetherBalanced<'o, G, F, O: ?Sized> {
    monitors: Vec<(String, BalanceMonitor<'o, G, F>)>,
    inner: &'o mut O,
}

impl<'o, G: GroupAction, F: DiscreteForce, O: Observer + ?Sized> NoetherBalanced<'o, G, F, O> {
    /// The balances of `actions` (named by `names`) under the two-point discrete force `force`
    /// on the steps of `grid`, around `inner`.
    pub fn new(
        names: Vec<String>,
        actions: &'o [G],
        force: &'o F,
        grid: &TimeGrid,
        inner: &'o mut O,
    ) -> Self {
        let monitors = names
            .into_iter()
            .zip(actions)
            .map(|(name, g)| (name, BalanceMonitor::on_grid(g, force, grid)))
            .collect();
        Self { monitors, inner }
    }

    /// What each action's monitor carries to the next step, for a checkpoint of the run.
    pub fn carried(&self) -> Vec<MonitorCarry> {
        self.monitors.iter().map(|(_, m)| m.carried()).collect()
    }

    /// Restores what [`NoetherBalanced::carried`] gave.
    ///
    /// # Errors
    /// A checkpoint of another number of symmetries.
    pub fn restore(&mut self, carried: &[MonitorCarry]) -> Result<(), String> {
        if carried.len() != self.monitors.len() {
            return Err(format!(
                "the checkpoint has the Noether balances of {} symmetries, the run {}",
                carried.len(),
                self.monitors.len()
            ));
        }
        for ((_, m), c) in self.monitors.iter_mut().zip(carried) {
            m.restore(c);
        }
        Ok(())
    }

    /// The observer it hands every step on to.
    pub fn inner(&self) -> &O {
        self.inner
    }

    /// The observer it hands every step on to.
    pub fn inner_mut(&mut self) -> &mut O {
        self.inner
    }

    /// One balance per action, by name; an action the core refused (it does not fit the
    /// system) has none.
    pub fn balances(&self) -> Vec<(String, NoetherBalance)> {
        self.monitors
            .iter()
            .filter_map(|(name, m)| {
                m.report()
                    .ok()
                    .map(|r| (name.clone(), NoetherBalance::of(r)))
            })
            .collect()
    }
}

impl<G: GroupAction, F: DiscreteForce, O: Observer + ?Sized> Observer
    for NoetherBalanced<'_, G, F, O>
{
    fn start(&mut self, initial: &StepView<'_>) {
        for (_, m) in &mut self.monitors {
            m.start(initial);
        }
        self.inner.start(initial);
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        for (_, m) in &mut self.monitors {
            // A monitor that stopped (its action was refused) keeps its error; the run goes on.
            let _ = m.observe(view);
        }
        self.inner.observe(view)
    }

    fn every_step(&self) -> bool {
        true
    }

    /// The steps aside go to the inner observer alone (they are not steps of the run).
    fn landing(&self, step: usize, t: f64, next: f64) -> Option<f64> {
        self.inner.landing(step, t, next)
    }

    fn landed(&mut self, reached: Result<&StepView<'_>, &marsden::Error>) -> ControlFlow<()> {
        self.inner.landed(reached)
    }

    /// The inner observer's reason (an event that stopped the run, or failed to be located).
    fn termination(&self) -> Option<marsden::Termination> {
        self.inner.termination()
    }
}
