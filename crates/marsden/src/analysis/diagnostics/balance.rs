//! Noether's theorem with forces, discrete and exact: the momentum balance of every step.
//!
//! Concept of the notes (MW01): *(Lagrangian) Noether's theorem with forces* —
//! `J_L(T) − J_L(0) = ∫ ⟨f_L, ξ_Q⟩ dt` — and *discrete variational mechanics with forces*. With the
//! forced discrete Legendre transforms ([conventions](crate#conventions)) `p_k = −D₁L_d − f_d⁻` and
//! `p_{k+1} = D₂L_d + f_d⁺` of the step `(q_k, q_{k+1})`,
//!
//! ```text
//!     ⟨p_{k+1}, ξ_Q(q_{k+1})⟩ − ⟨p_k, ξ_Q(q_k)⟩
//!         = ⟨D₁L_d, ξ_Q(q_k)⟩ + ⟨D₂L_d, ξ_Q(q_{k+1})⟩ + ⟨f_d⁻, ξ_Q(q_k)⟩ + ⟨f_d⁺, ξ_Q(q_{k+1})⟩
//!         = ⟨dL_d, ξ_{Q×Q}⟩ + ⟨f_d⁻, ξ_Q(q_k)⟩ + ⟨f_d⁺, ξ_Q(q_{k+1})⟩.
//! ```
//!
//! If `L_d` is invariant, `⟨dL_d, ξ_{Q×Q}⟩ = 0` and the change of the discrete momentum map in
//! one step is *exactly* the discrete impulse of the forces along the generator ([MW01] §3.2.3):
//!
//! ```text
//!     J_{k+1} − J_k = ⟨f_d⁻(q_k, q_{k+1}), ξ_Q(q_k)⟩ + ⟨f_d⁺(q_k, q_{k+1}), ξ_Q(q_{k+1})⟩,
//! ```
//!
//! the discrete counterpart of `∫⟨f_L, ξ_Q⟩ dt`. (With SHAKE constraints the constraint impulse
//! `h Dφ(q_k)ᵀλ_k` adds `−h⟨λ_k, Dφ(q_k)ξ_Q(q_k)⟩`, which vanishes for invariant constraints.)
//! This module checks the identity step by step; the residual is at round-off plus the Newton
//! residual. It applies to two-point rules (discrete forces on `q_k` and `q_{k+1}` only).
//!
//! [MW01]: crate#references

use std::ops::ControlFlow;

use crate::discrete::DiscreteForce;
use crate::error::Error;
use crate::run::{Observer, StepView};
use crate::run::{TimeGrid, Trajectory};
use crate::symmetry::{GroupAction, momentum_map, validate};

/// The per-step momentum balance of one group action over a run.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BalanceReport {
    /// Name of the group action.
    pub symmetry: String,
    /// Steps checked (consecutive stored samples).
    pub steps: usize,
    /// `max_k max_a |(J_{k+1} − J_k)_a − I_k,a|`, with `I_k` the discrete impulse.
    pub max_residual: f64,
    /// The same relative to `max(|J_k|, |J_{k+1}|, |I_k|)` of the worst step.
    pub max_rel_residual: f64,
    /// Step (index of `k`) with the largest residual.
    pub worst_step: usize,
    /// Accumulated change `Σ_k (J_{k+1} − J_k)`.
    pub total_change: Vec<f64>,
    /// Accumulated impulse `Σ_k I_k`.
    pub total_impulse: Vec<f64>,
}

/// What a [`BalanceMonitor`] carries from one step to the next: the last state, the report so
/// far, and why it refused its action (if it did).
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct MonitorCarry {
    previous: Option<(f64, Vec<f64>, Vec<f64>)>,
    report: BalanceReport,
    refused: Option<String>,
}

/// Evaluates the balance of consecutive states.
struct Balance<'a, G, F> {
    action: &'a G,
    force: &'a F,
    h: f64,
    report: BalanceReport,
    scratch: Scratch,
}

#[derive(Default)]
struct Scratch {
    delta: Vec<f64>,
    forces: Vec<f64>,
    xi: Vec<f64>,
    j0: Vec<f64>,
    j1: Vec<f64>,
}

impl<G: GroupAction, F: DiscreteForce> Balance<'_, G, F> {
    fn new<'a>(action: &'a G, force: &'a F, h: f64) -> Balance<'a, G, F> {
        let m = action.algebra_dim();
        Balance {
            action,
            force,
            h,
            report: BalanceReport {
                symmetry: action.name(),
                total_change: vec![0.0; m],
                total_impulse: vec![0.0; m],
                ..BalanceReport::default()
            },
            scratch: Scratch::default(),
        }
    }

    /// Checks the step `k` from `(t, q0, p0)` to `(q1, p1)`.
    fn step(&mut self, k: usize, t: f64, q0: &[f64], p0: &[f64], q1: &[f64], p1: &[f64]) {
        let (n, m) = (q0.len(), self.action.algebra_dim());
        let s = &mut self.scratch;
        s.delta.clear();
        s.delta.extend(q1.iter().zip(q0).map(|(b, a)| b - a));
        s.forces.resize(2 * n, 0.0);
        self.force
            .discrete_force(t, self.h, q0, &s.delta, &mut s.forces);
        s.j0.resize(m, 0.0);
        s.j1.resize(m, 0.0);
        momentum_map(self.action, q0, p0, &mut s.j0);
        momentum_map(self.action, q1, p1, &mut s.j1);
        s.xi.resize(n, 0.0);
        for a in 0..m {
            self.action.generator(a, q0, &mut s.xi);
            let minus: f64 = s.forces[..n].iter().zip(&s.xi).map(|(f, x)| f * x).sum();
            self.action.generator(a, q1, &mut s.xi);
            let plus: f64 = s.forces[n..].iter().zip(&s.xi).map(|(f, x)| f * x).sum();
            let (change, impulse) = (s.j1[a] - s.j0[a], minus + plus);
            let r = &mut self.report;
            r.total_change[a] += change;
            r.total_impulse[a] += impulse;
            let residual = (change - impulse).abs();
            if residual > r.max_residual {
                r.max_residual = residual;
                r.worst_step = k;
                let scale = s.j0[a].abs().max(s.j1[a].abs()).max(impulse.abs());
                r.max_rel_residual = residual / scale.max(f64::MIN_POSITIVE);
            }
        }
        self.report.steps += 1;
    }
}

/// Checks the discrete balance law `J_{k+1} − J_k = ⟨f_d⁻, ξ_Q(q_k)⟩ + ⟨f_d⁺, ξ_Q(q_{k+1})⟩` on
/// every pair of consecutive stored samples of `trajectory` (store every step, stride 1, to check
/// them all). `force` is the rule's discrete force, e.g. `Midpoint.discretize_force(f, n)`.
pub fn force_balance<G: GroupAction, F: DiscreteForce>(
    action: &G,
    force: &F,
    trajectory: &Trajectory,
) -> Result<BalanceReport, Error> {
    let mut balance = Balance::new(action, force, trajectory.h);
    if trajectory.is_empty() {
        return Ok(balance.report);
    }
    validate(action, trajectory.dof, trajectory.q(0))?;
    for i in 1..trajectory.len() {
        let k = trajectory.step_indices[i - 1];
        if trajectory.step_indices[i] == k + 1 {
            balance.step(
                k,
                trajectory.t(i - 1),
                trajectory.q(i - 1),
                trajectory.p(i - 1),
                trajectory.q(i),
                trajectory.p(i),
            );
        }
    }
    Ok(balance.report)
}

/// Streaming form of [`force_balance`]: an [`Observer`] checking every step of a run.
pub struct BalanceMonitor<'a, G, F> {
    balance: Balance<'a, G, F>,
    previous: Option<(f64, Vec<f64>, Vec<f64>)>,
    error: Option<Error>,
    /// The run's grid, when its last step is shorter than `h` ([`BalanceMonitor::on_grid`]).
    grid: Option<TimeGrid>,
}

impl<'a, G: GroupAction, F: DiscreteForce> BalanceMonitor<'a, G, F> {
    /// A monitor of `action`'s momentum balance under `force` for steps of size `h`.
    pub fn new(action: &'a G, force: &'a F, h: f64) -> Self {
        Self {
            balance: Balance::new(action, force, h),
            previous: None,
            error: None,
            grid: None,
        }
    }

    /// A monitor of the steps of `grid`, each discretised with its own size
    /// ([`TimeGrid::step_size`]: `h`, or a shorter last step).
    pub fn on_grid(action: &'a G, force: &'a F, grid: &TimeGrid) -> Self {
        Self {
            grid: Some(*grid),
            ..Self::new(action, force, grid.h)
        }
    }

    /// What the monitor carries to the next step, for a checkpoint of the run
    /// ([`BalanceMonitor::restore`]).
    pub fn carried(&self) -> MonitorCarry {
        MonitorCarry {
            previous: self.previous.clone(),
            report: self.balance.report.clone(),
            refused: self.error.as_ref().map(ToString::to_string),
        }
    }

    /// Restores what [`BalanceMonitor::carried`] gave, into a monitor of the same action and
    /// force freshly built: the resumed run's balance goes on as the checkpointed one's (its
    /// [`Observer::start`] is not called again). A monitor that had refused its action stays
    /// refused, with the reason it gave.
    pub fn restore(&mut self, carried: &MonitorCarry) {
        self.previous.clone_from(&carried.previous);
        self.balance.report.clone_from(&carried.report);
        self.error = carried.refused.as_ref().map(|reason| {
            Error::Input(crate::error::InputError::Restored {
                reason: reason.clone(),
            })
        });
    }

    /// The report so far, or the error that stopped the monitor.
    pub fn report(&self) -> Result<&BalanceReport, &Error> {
        match &self.error {
            Some(e) => Err(e),
            None => Ok(&self.balance.report),
        }
    }
}

impl<G: GroupAction, F: DiscreteForce> Observer for BalanceMonitor<'_, G, F> {
    fn start(&mut self, initial: &StepView<'_>) {
        match validate(self.balance.action, initial.q.len(), initial.q) {
            Ok(()) => self.previous = Some((initial.t, initial.q.to_vec(), initial.p.to_vec())),
            Err(e) => self.error = Some(e),
        }
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        let Some((t, q, p)) = self.previous.as_mut() else {
            return ControlFlow::Break(());
        };
        if let Some(grid) = &self.grid {
            self.balance.h = grid.step_size(view.step - 1);
        }
        self.balance.step(
            view.step - 1,
            *t,
            q.as_slice(),
            p.as_slice(),
            view.q,
            view.p,
        );
        *t = view.t;
        q.copy_from_slice(view.q);
        p.copy_from_slice(view.p);
        ControlFlow::Continue(())
    }
}
