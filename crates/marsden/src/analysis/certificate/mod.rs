//! Certificates of structure: is the computed step map symplectic?
//!
//! Concept of the notes (MW01): *discrete Lagrangian time evolution* (`F_{L_d}` preserves the discrete symplectic form)
//! and *Hamiltonian mechanics* (the flow preserves `Ω = dq ∧ dp`). A map `F: (q, p) ↦ (q₁, p₁)`
//! of `ℝ²ⁿ` is symplectic iff its Jacobian satisfies
//!
//! ```text
//!     DFᵀ J DF = J,        J = [[0, I], [−I, 0]]        ([HLW06] Def. VI.2.2).
//! ```
//!
//! The certificate computes `DF` of the step actually taken — exactly, by automatic
//! differentiation through the converged step (the implicit function theorem for implicit
//! steps, [`variational`]), not by finite differences — and reports the relative defect
//!
//! ```text
//!     δ = ‖DFᵀ J DF − J‖_max / ‖DF‖²_max,
//! ```
//!
//! whose round-off floor is about `n·ε` (the scale of `DFᵀJDF` is `‖DF‖²`). A variational
//! integrator gives `δ ≈ 1e-15` for every rule; the explicit RK2 comparison map
//! ([`crate::hamiltonian::ExplicitMidpoint`]) gives `δ = O(h³)`.
//!
//! Anything implementing [`DifferentiableStep`] can be certified: the variational
//! [`crate::integrator::Integrator`] (unconstrained; forces are allowed and make the defect non-zero, as they
//! should — a forced flow is not symplectic) and every [`crate::hamiltonian::HamiltonianIntegrator`].
//!
//! [HLW06]: crate#references

pub mod variational;

use crate::error::Error;
use crate::hamiltonian::{Hamiltonian, HamiltonianIntegrator, HamiltonianMethod};
use crate::integrator::StepReport;
use crate::mechanics::State;
use crate::numerics::dense::max_norm;
use crate::run::TimeGrid;

/// A one-step map that can report its exact Jacobian.
pub trait DifferentiableStep {
    /// Degrees of freedom `n` (the Jacobian is 2n × 2n).
    fn dof(&self) -> usize;

    /// One step of size `h` from `state` (advanced in place).
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error>;

    /// One step, also writing `∂(q₁, p₁)/∂(q₀, p₀)` (row-major 2n × 2n) into `jac`.
    fn step_with_jacobian(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error>;
}

impl<H: Hamiltonian, M: HamiltonianMethod<H>> DifferentiableStep for HamiltonianIntegrator<H, M> {
    fn dof(&self) -> usize {
        self.hamiltonian().dof()
    }
    fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        HamiltonianIntegrator::step(self, state, h)
    }
    fn step_with_jacobian(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        HamiltonianIntegrator::step_with_jacobian(self, state, h, jac)
    }
}

/// The symplecticity defect of a Jacobian `DF` (row-major 2n × 2n): `(absolute, relative)` =
/// `(‖DFᵀJDF − J‖_max, ‖DFᵀJDF − J‖_max / ‖DF‖²_max)`.
pub fn symplectic_defect(jac: &[f64], n: usize) -> (f64, f64) {
    let m = 2 * n;
    // J·DF: rows 0..n are the p-rows of DF, rows n..2n minus the q-rows.
    let mut jdf = vec![0.0; m * m];
    for i in 0..n {
        for k in 0..m {
            jdf[i * m + k] = jac[(n + i) * m + k];
            jdf[(n + i) * m + k] = -jac[i * m + k];
        }
    }
    let mut worst: f64 = 0.0;
    for r in 0..m {
        for c in 0..m {
            let s: f64 = (0..m).map(|l| jac[l * m + r] * jdf[l * m + c]).sum();
            let j = if c == r + n {
                1.0
            } else if r == c + n {
                -1.0
            } else {
                0.0
            };
            worst = worst.max((s - j).abs());
        }
    }
    let scale = max_norm(jac);
    (worst, worst / (scale * scale).max(f64::MIN_POSITIVE))
}

/// The certificate of a run: the symplecticity defect at sampled steps.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SymplecticReport {
    /// Steps whose Jacobian was examined.
    pub checked: usize,
    /// Largest relative defect `‖DFᵀJDF − J‖ / ‖DF‖²`.
    pub max_relative: f64,
    /// Largest absolute defect `‖DFᵀJDF − J‖_max`.
    pub max_absolute: f64,
    /// Index of the step (0-based) with the largest relative defect.
    pub worst_step: usize,
}

impl SymplecticReport {
    /// Adds the defect of one step.
    pub fn record(&mut self, step: usize, absolute: f64, relative: f64) {
        self.checked += 1;
        self.max_absolute = self.max_absolute.max(absolute);
        // A NaN defect counts as the worst possible.
        let relative = if relative.is_nan() {
            f64::INFINITY
        } else {
            relative
        };
        if relative > self.max_relative || self.checked == 1 {
            self.max_relative = relative;
            self.worst_step = step;
        }
    }

    /// Whether every examined step is symplectic to the relative tolerance `tol`.
    pub fn is_symplectic(&self, tol: f64) -> bool {
        self.checked > 0 && self.max_relative <= tol
    }
}

/// Runs `stepper` from `start` over `grid` and certifies every `every`-th step (the first step
/// always); returns the report and the final state.
pub fn certify<D: DifferentiableStep + ?Sized>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    every: usize,
) -> Result<(SymplecticReport, State), Error> {
    let n = stepper.dof();
    let every = every.max(1);
    let mut jac = vec![0.0; 4 * n * n];
    let mut report = SymplecticReport::default();
    let mut state = start;
    for k in 0..grid.steps {
        if k % every == 0 {
            stepper.step_with_jacobian(&mut state, grid.step_size(k), &mut jac)?;
            let (absolute, relative) = symplectic_defect(&jac, n);
            report.record(k, absolute, relative);
        } else {
            stepper.step(&mut state, grid.step_size(k))?;
        }
        state.t = grid.time(k + 1);
    }
    Ok((report, state))
}
