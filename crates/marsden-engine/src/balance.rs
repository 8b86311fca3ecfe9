//! The discrete energy balance of a forced run, step by step while it runs: what `summary.json`
//! reports as `energy_balance` instead of an "energy error" (energy is not conserved there).
//!
//! With the step's own discrete forces `f_d^±` (the rule's discretisation of the file's
//! forces) and the mean velocity `v̄_k = (q_{k+1} − q_k)/h`, the discrete work of step `k` is
//! `W_k = ⟨f_d⁻ + f_d⁺, v̄_k⟩` and its defect `D_k = E_{k+1} − E_k − W_k`; the defect vanishes
//! to round-off for a quadratic potential with the midpoint rule (R12) and is `O(h³)` per step
//! otherwise. This is the core's [`marsden::analysis::diagnostics::EnergyBalance`] (which needs
//! the whole trajectory in memory), computed in bounded memory as an [`Observer`] wrapped
//! around the run's own observer; it applies to two-point rules (forces on `q_k` and `q_{k+1}`
//! only), the others report no balance.
//!
//! A Lagrangian depending on `t` changes the energy by itself, `dE/dt = ⟨f, q̇⟩ − ∂L/∂t`
//! ([MW01] §3.1 extended to forces). Its discrete counterpart is the derivative of the step's
//! discrete Lagrangian in its start time, `∂L_d/∂t₀(q_k, q_{k+1})`: for a rule that samples `L`
//! at the nodes `(t₀ + c_j h, q_{c_j}, v̄)` with weights `w_j`, `∂L_d/∂t₀ = Σ_j w_j ∂L/∂t` at
//! the nodes. It is computed with the rule's own force quadrature applied to the "force"
//! `(∂L/∂t, 0, …, 0)` ([`TimeDerivative`]; the weights `ℓ_j(c_i)` of a node sum to one over
//! the end points), `∂L/∂t` by automatic differentiation. The balance then reads
//! `D_k = E_{k+1} − E_k − W_k + ∂L_d/∂t₀`. For the midpoint rule and
//! `L = ½q̇ᵀMq̇ − V(t, q)`, `D_k = V(t_{k+1}, q_{k+1}) − V(t_k, q_k) − ∇_qV·Δq − h ∂_tV` at
//! `(t_k + h/2, (q_k + q_{k+1})/2)`: zero (to round-off) when `V` is a quadratic in `q` plus a
//! term bilinear in `(t, q)` (e.g. `V = ½kq² − a t q`), `O(h³)` per step otherwise.
//!
//! [MW01]: marsden#references

use std::ops::ControlFlow;

use marsden::discrete::DiscreteForce;
use marsden::numerics::ad::{MultiFunction, nested_gradient};
use marsden::{Force, Lagrangian, Observer, Scalar, StepView, TimeGrid, mechanics};
use serde::{Deserialize, Serialize};

/// File name of the energy-balance plot, drawn instead of the energy-error plot.
pub const ENERGY_BALANCE_PNG: &str = "energy_balance.png";

/// `energy_balance { … }` of `summary.json`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct BalanceSummary {
    /// `Σ_k W_k`, the discrete work of the forces over the run.
    pub total_work: f64,
    /// `max_k |D_k|`.
    pub max_defect: f64,
    /// `Σ_k D_k = E_N − E_0 − Σ_k W_k`, the energy change the work does not account for.
    pub total_defect: f64,
    /// `E_N − E_0`.
    pub energy_change: f64,
    /// Steps in the balance (every step of the run).
    pub steps: usize,
    /// For a Lagrangian depending on `t`: `Σ_k −∂L_d/∂t₀`, the energy its explicit time
    /// dependence puts in (absent for an autonomous Lagrangian); then
    /// `energy_change = total_work + total_time_work + total_defect`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub total_time_work: Option<f64>,
}

impl BalanceSummary {
    /// Adds a step whose energy changed by `delta_energy`, with the forces' work `work` and,
    /// for a time-dependent Lagrangian, `time_work = −∂L_d/∂t₀`.
    pub(crate) fn push(&mut self, delta_energy: f64, work: f64, time_work: Option<f64>) {
        let defect = delta_energy - work - time_work.unwrap_or(0.0);
        self.steps += 1;
        self.total_work += work;
        if let Some(w) = time_work {
            *self.total_time_work.get_or_insert(0.0) += w;
        }
        self.total_defect += defect;
        self.energy_change += delta_energy;
        // NaN sticks: a broken step does not report a perfect balance.
        if defect.abs() > self.max_defect || defect.is_nan() {
            self.max_defect = defect.abs();
        }
    }
}

/// The balance at the stored steps, for the plot: `t`, `E − E₀` and the accumulated work,
/// in bounded memory (past [`BalanceSeries::CAP`] points every other one is dropped and the
/// stride doubles).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct BalanceSeries {
    /// Times.
    pub t: Vec<f64>,
    /// `E(t) − E₀`.
    pub change: Vec<f64>,
    /// `Σ W_k` up to `t` (with `Σ −∂L_d/∂t₀` for a time-dependent Lagrangian).
    pub work: Vec<f64>,
    stride: usize,
    total: usize,
}

impl BalanceSeries {
    /// Most points kept.
    pub const CAP: usize = 8192;

    pub(crate) fn new(every: usize, total: usize) -> Self {
        Self {
            stride: every.max(1),
            total,
            ..Self::default()
        }
    }

    pub(crate) fn push(&mut self, step: usize, t: f64, s: &BalanceSummary) {
        if !step.is_multiple_of(self.stride) && step != self.total {
            return;
        }
        self.t.push(t);
        self.change.push(s.energy_change);
        self.work
            .push(s.total_time_work.map_or(s.total_work, |w| s.total_work + w));
        if self.t.len() > Self::CAP {
            for v in [&mut self.t, &mut self.change, &mut self.work] {
                let kept: Vec<f64> = v.iter().step_by(2).copied().collect();
                *v = kept;
            }
            self.stride *= 2;
        }
    }
}

/// `(∂L/∂t(t, q, v), 0, …, 0)`: discretised by a rule's force quadrature, the sum of its
/// `f_d⁻ + f_d⁺` is the rule's `∂L_d/∂t₀` (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub struct TimeDerivative<'l, L>(pub &'l L);

/// `L` over the inputs `[t, q, v]`, for differentiating in `t`.
struct OverTime<'l, L>(&'l L);

impl<L: Lagrangian> MultiFunction for OverTime<'_, L> {
    fn inputs(&self) -> usize {
        2 * self.0.dof() + 1
    }
    fn outputs(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
        let n = self.0.dof();
        out[0] = self.0.lagrangian(x[0], &x[1..=n], &x[n + 1..]);
    }
}

impl<L: Lagrangian> Force for TimeDerivative<'_, L> {
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        let x: Vec<S> = std::iter::once(t)
            .chain(q.iter().chain(v).copied())
            .collect();
        out.iter_mut().for_each(|f| *f = S::from(0.0));
        nested_gradient(&OverTime(self.0), &x, 0..1, &mut out[..1]);
    }
}

/// What a [`Balanced`] carries from one step to the next: the previous `(t_k, q_k, E_k)`, the
/// inverse Legendre transform's warm start, the balance so far and its stored series.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnergyBalanceCarry {
    previous: (f64, Vec<f64>, f64),
    velocity: Vec<f64>,
    summary: SummaryCarry,
    series: BalanceSeries,
}

/// [`BalanceSummary`] with every field written (its `total_time_work` is left out of
/// `summary.json` when absent, which a format that is not self-describing, as the checkpoint's,
/// cannot read back).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct SummaryCarry {
    total_work: f64,
    max_defect: f64,
    total_defect: f64,
    energy_change: f64,
    steps: usize,
    total_time_work: Option<f64>,
}

impl From<BalanceSummary> for SummaryCarry {
    fn from(s: BalanceSummary) -> Self {
        Self {
            total_work: s.total_work,
            max_defect: s.max_defect,
            total_defect: s.total_defect,
            energy_change: s.energy_change,
            steps: s.steps,
            total_time_work: s.total_time_work,
        }
    }
}

impl From<SummaryCarry> for BalanceSummary {
    fn from(s: SummaryCarry) -> Self {
        Self {
            total_work: s.total_work,
            max_defect: s.max_defect,
            total_defect: s.total_defect,
            energy_change: s.energy_change,
            steps: s.steps,
            total_time_work: s.total_time_work,
        }
    }
}

/// An observer that accumulates the energy balance of every step and hands every step on to
/// the run's own observer (which keeps its own sampling).
pub struct Balanced<'o, L, F, T, O: ?Sized> {
    lagrangian: &'o L,
    force: F,
    /// The rule's discretisation of [`TimeDerivative`], for a Lagrangian depending on `t`.
    time: Option<T>,
    /// The run's steps (`h`, perhaps a shorter last one).
    grid: TimeGrid,
    /// The size of the step being balanced.
    h: f64,
    inner: &'o mut O,
    /// State of the previous step: `t_k`, `q_k`, `E_k`.
    previous: (f64, Vec<f64>, f64),
    velocity: Vec<f64>,
    delta: Vec<f64>,
    f: Vec<f64>,
    /// The balance so far.
    pub summary: BalanceSummary,
    /// The balance at the stored steps.
    pub series: BalanceSeries,
}

impl<L, F, T, O: ?Sized> Balanced<'_, L, F, T, O> {
    /// The observer it hands every step on to.
    pub fn inner(&self) -> &O {
        self.inner
    }

    /// The observer it hands every step on to.
    pub fn inner_mut(&mut self) -> &mut O {
        self.inner
    }
}

impl<'o, L, F, T, O> Balanced<'o, L, F, T, O>
where
    L: Lagrangian,
    F: DiscreteForce,
    T: DiscreteForce,
    O: Observer + ?Sized,
{
    /// The balance of a run of `lagrangian` with the two-point discrete force `force`, the
    /// discretised [`TimeDerivative`] `time` of a Lagrangian depending on `t`, on the steps of
    /// `grid`, around `inner`; the series keeps every `every`-th step.
    pub fn new(
        lagrangian: &'o L,
        force: F,
        time: Option<T>,
        grid: &TimeGrid,
        every: usize,
        inner: &'o mut O,
    ) -> Self {
        let n = lagrangian.dof();
        Self {
            lagrangian,
            force,
            time,
            grid: *grid,
            h: grid.h,
            inner,
            previous: (0.0, vec![0.0; n], f64::NAN),
            velocity: vec![0.0; n],
            delta: vec![0.0; n],
            f: vec![0.0; 2 * n],
            summary: BalanceSummary::default(),
            series: BalanceSeries::new(every, grid.steps),
        }
    }

    fn energy(&mut self, t: f64, q: &[f64], p: &[f64]) -> f64 {
        match mechanics::energy_from_momentum(self.lagrangian, t, q, p, &mut self.velocity) {
            Ok(e) => e,
            Err(_) => {
                // A failed inverse Legendre transform leaves a poor guess behind.
                self.velocity.fill(0.0);
                f64::NAN
            }
        }
    }

    /// `W_k = ⟨f_d⁻ + f_d⁺, (q_{k+1} − q_k)/h⟩` of the step from the previous state to `q1`.
    fn work(&mut self, q1: &[f64]) -> f64 {
        let (t0, q0, _) = &self.previous;
        let n = q0.len();
        self.delta
            .iter_mut()
            .zip(q1.iter().zip(q0))
            .for_each(|(d, (a, b))| *d = a - b);
        self.force
            .discrete_force(*t0, self.h, q0, &self.delta, &mut self.f);
        (0..n)
            .map(|a| (self.f[a] + self.f[n + a]) * self.delta[a] / self.h)
            .sum()
    }

    /// `−∂L_d/∂t₀` of the step from the previous state (the displacement set by
    /// [`Balanced::work`]), for a time-dependent Lagrangian.
    fn time_work(&mut self) -> Option<f64> {
        let time = self.time.as_ref()?;
        let (t0, q0, _) = &self.previous;
        time.discrete_force(*t0, self.h, q0, &self.delta, &mut self.f);
        Some(-self.f.iter().sum::<f64>())
    }

    /// What the balance carries to the next step, for a checkpoint of the run.
    pub fn carried(&self) -> EnergyBalanceCarry {
        EnergyBalanceCarry {
            previous: self.previous.clone(),
            velocity: self.velocity.clone(),
            summary: SummaryCarry::from(self.summary),
            series: self.series.clone(),
        }
    }

    /// Restores what [`Balanced::carried`] gave (the resumed run's [`Observer::start`] is not
    /// called again).
    ///
    /// # Errors
    /// A checkpoint of another number of coordinates.
    pub fn restore(&mut self, carried: &EnergyBalanceCarry) -> Result<(), String> {
        let n = self.velocity.len();
        if carried.previous.1.len() != n || carried.velocity.len() != n {
            return Err(format!(
                "the checkpoint's energy balance has {} coordinates, the run {n}",
                carried.velocity.len()
            ));
        }
        self.previous.clone_from(&carried.previous);
        self.velocity.clone_from(&carried.velocity);
        self.summary = carried.summary.into();
        self.series.clone_from(&carried.series);
        Ok(())
    }

    fn remember(&mut self, t: f64, q: &[f64], e: f64) {
        self.previous.0 = t;
        self.previous.1.copy_from_slice(q);
        self.previous.2 = e;
    }
}

impl<L, F, T, O> Observer for Balanced<'_, L, F, T, O>
where
    L: Lagrangian,
    F: DiscreteForce,
    T: DiscreteForce,
    O: Observer + ?Sized,
{
    fn start(&mut self, initial: &StepView<'_>) {
        let e = self.energy(initial.t, initial.q, initial.p);
        self.remember(initial.t, initial.q, e);
        self.series.push(0, initial.t, &self.summary);
        self.inner.start(initial);
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self.h = self.grid.step_size(view.step - 1);
        let e = self.energy(view.t, view.q, view.p);
        let work = self.work(view.q);
        let time_work = self.time_work();
        self.summary.push(e - self.previous.2, work, time_work);
        self.remember(view.t, view.q, e);
        self.series.push(view.step, view.t, &self.summary);
        self.inner.observe(view)
    }

    fn every_step(&self) -> bool {
        true
    }

    /// The steps aside go to the inner observer alone: they are not steps of the run, and
    /// do no work in its balance.
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

/// Draws the energy balance of a forced run's `series` in `dir` ([`ENERGY_BALANCE_PNG`]; such a
/// run gets no energy-error plot); adds it to the list of `written` files.
///
/// # Errors
/// The plot cannot be written, as text.
pub fn draw(
    dir: &std::path::Path,
    series: &BalanceSeries,
    written: &mut Vec<String>,
) -> Result<(), String> {
    let opts = marsden_io::PlotOptions::default();
    let path = dir.join(ENERGY_BALANCE_PNG);
    marsden_io::plot_energy_balance(&path, &series.t, &series.change, &series.work, &opts)
        .map_err(|e| e.to_string())?;
    written.push(ENERGY_BALANCE_PNG.to_owned());
    Ok(())
}
