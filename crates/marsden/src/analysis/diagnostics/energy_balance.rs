//! The discrete energy balance of a forced run: energy change against the discrete work of the
//! forces, step by step.
//!
//! Continuous: `dE/dt = ⟨f_L, q̇⟩` along solutions of the forced Euler–Lagrange equations (for a
//! time-independent `L`), so `E(t₁) − E(t₀) = ∫ ⟨f_L, q̇⟩ dt`. Discrete: with the step's discrete
//! forces and the mean velocity `v̄_k = (q_{k+1} − q_k)/h`, the *discrete work* is
//!
//! ```text
//!     W_k = ⟨f_d⁻(q_k, q_{k+1}) + f_d⁺(q_k, q_{k+1}), v̄_k⟩,
//! ```
//!
//! the rule's own quadrature of `∫⟨f, q̇⟩ dt` (midpoint: `h⟨f(q̄, v̄), v̄⟩`; trapezoid:
//! `(h/2)⟨f(q_k, v̄) + f(q_{k+1}, v̄), v̄⟩`), and the *defect* is `D_k = E_{k+1} − E_k − W_k`.
//!
//! **What holds exactly.** For `L = ½ vᵀMv − V(q)` with constant `M`, the midpoint rule with
//! midpoint forces is `q_{k+1} = q_k + h M⁻¹ p̄`, `p_{k+1} = p_k − h∇V(q̄) + h f(q̄, v̄)` with
//! `p̄ = (p_k + p_{k+1})/2` ([conventions](crate#conventions), equivalences), hence, `E` being
//! `½pᵀM⁻¹p + V`,
//!
//! ```text
//!     D_k = V(q_{k+1}) − V(q_k) − ⟨∇V(q̄), q_{k+1} − q_k⟩ = (1/24) D³V(q̄)[Δq, Δq, Δq] + O(|Δq|⁵),
//! ```
//!
//! for *any* force `f(t, q, v)`. For quadratic `V` the defect vanishes: the balance is exact to
//! round-off, e.g. R12, `E_{k+1} − E_k = −c (q_{k+1} − q_k)²/h`.
//!
//! **What holds approximately.** In general `D_k = O(h³)` per step (both `E_{k+1} − E_k` and
//! `W_k` approximate the same integral to the local order of a second-order method, [FGG21]),
//! and the defect is the energy error the conservative part of the scheme would make in the same
//! step; for the midpoint rule it is exactly that (the bracket above). Its sum
//! `Σ D_k = E_N − E_0 − Σ W_k` is the energy not accounted for by the work.
//!
//! [FGG21]: crate#references

use crate::discrete::DiscreteForce;
use crate::discrete::rules::Rule;
use crate::error::Error;
use crate::error::InputError;
use crate::mechanics;
use crate::mechanics::{Force, Lagrangian};
use crate::run::Trajectory;

/// Per-step energy balance of a run (needs every step stored: stride 1).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EnergyBalance {
    /// `E_{k+1} − E_k`, one entry per step.
    pub delta_energy: Vec<f64>,
    /// Discrete work `W_k = ⟨f_d⁻ + f_d⁺, (q_{k+1} − q_k)/h⟩`.
    pub work: Vec<f64>,
    /// Defect `D_k = E_{k+1} − E_k − W_k`.
    pub defect: Vec<f64>,
    /// `max_k |D_k|`.
    pub max_defect: f64,
    /// `Σ_k D_k = E_N − E_0 − Σ W_k`.
    pub total_defect: f64,
    /// `Σ_k W_k`.
    pub total_work: f64,
}

impl EnergyBalance {
    /// The balance for the continuous force `force` discretised by `rule` (as the run did).
    pub fn of<L: Lagrangian, R: Rule, F: Force>(
        lagrangian: &L,
        rule: &R,
        force: &F,
        trajectory: &Trajectory,
    ) -> Result<Self, Error> {
        let discrete = rule.discretize_force(force, lagrangian.dof());
        Self::of_discrete(lagrangian, &discrete, trajectory)
    }

    /// The balance for two-point discrete forces `f_d^±` (the run's own, e.g. a
    /// [`crate::forces::TwoPoint`]).
    pub fn of_discrete<L: Lagrangian, F: DiscreteForce>(
        lagrangian: &L,
        force: &F,
        trajectory: &Trajectory,
    ) -> Result<Self, Error> {
        let n = trajectory.dof;
        let (mut v, mut delta, mut f) = (vec![0.0; n], vec![0.0; n], vec![0.0; 2 * n]);
        let energy = |i: usize, v: &mut [f64]| {
            let (t, q, p) = (trajectory.t(i), trajectory.q(i), trajectory.p(i));
            mechanics::energy_from_momentum(lagrangian, t, q, p, v)
        };
        let mut balance = Self::default();
        let mut e_prev = if trajectory.is_empty() {
            0.0
        } else {
            energy(0, &mut v)?
        };
        for i in 1..trajectory.len() {
            let (k0, k1) = (trajectory.step_indices[i - 1], trajectory.step_indices[i]);
            if k1 != k0 + 1 {
                return Err(Error::Input(InputError::InvalidOption {
                    name: "stride",
                    value: (k1 - k0) as f64,
                    reason: "the energy balance needs every step stored (stride 1)",
                }));
            }
            let (q0, q1, h) = (trajectory.q(i - 1), trajectory.q(i), trajectory.h);
            delta
                .iter_mut()
                .zip(q1.iter().zip(q0))
                .for_each(|(d, (a, b))| *d = a - b);
            force.discrete_force(trajectory.t(i - 1), h, q0, &delta, &mut f);
            let work: f64 = (0..n).map(|a| (f[a] + f[n + a]) * delta[a] / h).sum();
            let e = energy(i, &mut v)?;
            balance.push(e - e_prev, if force.is_active() { work } else { 0.0 });
            e_prev = e;
        }
        Ok(balance)
    }

    fn push(&mut self, delta_energy: f64, work: f64) {
        let defect = delta_energy - work;
        self.delta_energy.push(delta_energy);
        self.work.push(work);
        self.defect.push(defect);
        self.max_defect = self.max_defect.max(defect.abs());
        self.total_defect += defect;
        self.total_work += work;
    }
}
