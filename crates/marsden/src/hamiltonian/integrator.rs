//! Stepping a Hamiltonian with a one-step method, and running it over a time grid.
//!
//! The Hamiltonian counterpart of [`crate::integrator::Integrator`], run by the same loop ([`crate::run::simulate()`]): a
//! [`HamiltonianMethod`] advances `(t, q, p)` by one step of `H` (and, on request, returns the
//! Jacobian of the step map for the symplecticity certificate); a [`HamiltonianIntegrator`] owns
//! the Hamiltonian and the method and produces the same [`Trajectory`] as the Lagrangian side,
//! so all diagnostics apply to both.

use super::Hamiltonian;
use crate::error::Error;
use crate::error::InputError;
use crate::integrator::StepReport;
use crate::mechanics::State;
use crate::run::{Observer, RunOptions, Stepper, TimeGrid, Trajectory, simulate};

/// A one-step method for Hamilton's equations of `H`.
pub trait HamiltonianMethod<H> {
    /// A short name, e.g. `"implicit midpoint"`.
    fn name(&self) -> String;

    /// Whether the method is symplectic (what the certificate should find).
    fn is_symplectic(&self) -> bool;

    /// Advances `state` by one step of size `h`. On error `state` is left unchanged.
    fn step(&mut self, ham: &H, state: &mut State, h: f64) -> Result<StepReport, Error>;

    /// Like [`HamiltonianMethod::step`], and writes the Jacobian `∂(q₁, p₁)/∂(q₀, p₀)` of the
    /// step map (row-major 2n × 2n, exact derivatives, no finite differences) into `jac`.
    fn step_with_jacobian(
        &mut self,
        ham: &H,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error>;
}

/// A Hamiltonian `H` and a method to step it.
///
/// ```
/// use marsden::State;
/// use marsden::hamiltonian::{HamiltonianIntegrator, ImplicitMidpoint};
/// use marsden::systems::HarmonicOscillator;
///
/// let mut integrator = HamiltonianIntegrator::new(HarmonicOscillator::default(), ImplicitMidpoint::default());
/// let mut state = State { t: 0.0, q: vec![1.0], p: vec![0.0] };
/// integrator.step(&mut state, 0.1).unwrap();
/// // Reference case R1: the midpoint map of the unit oscillator is [[399, 40], [−40, 399]]/401.
/// assert!((state.q[0] - 399.0 / 401.0).abs() < 1e-15 && (state.p[0] + 40.0 / 401.0).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct HamiltonianIntegrator<H, M> {
    ham: H,
    method: M,
    steps: usize,
}

impl<H: Hamiltonian, M: HamiltonianMethod<H>> HamiltonianIntegrator<H, M> {
    /// Steps `ham` with `method`.
    pub fn new(ham: H, method: M) -> Self {
        Self {
            ham,
            method,
            steps: 0,
        }
    }

    /// The Hamiltonian.
    pub fn hamiltonian(&self) -> &H {
        &self.ham
    }

    /// The method.
    pub fn method(&self) -> &M {
        &self.method
    }

    fn check(&self, state: &State, h: f64) -> Result<(), Error> {
        let n = self.ham.dof();
        Error::check_len("q", &state.q, n)?;
        Error::check_len("p", &state.p, n)?;
        if h == 0.0 || !h.is_finite() {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        Ok(())
    }

    /// One step of size `h` from `state` (advanced in place).
    pub fn step(&mut self, state: &mut State, h: f64) -> Result<StepReport, Error> {
        self.check(state, h)?;
        let k = self.steps;
        let report = self
            .method
            .step(&self.ham, state, h)
            .map_err(|e| at_step(e, k))?;
        self.steps += 1;
        Ok(report)
    }

    /// One step, also writing the step map's Jacobian (row-major 2n × 2n) into `jac`.
    pub fn step_with_jacobian(
        &mut self,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        self.check(state, h)?;
        let n = self.ham.dof();
        Error::check_len("jacobian", jac, 4 * n * n)?;
        let k = self.steps;
        let report = self
            .method
            .step_with_jacobian(&self.ham, state, h, jac)
            .map_err(|e| at_step(e, k))?;
        self.steps += 1;
        Ok(report)
    }

    /// Runs from `start` over `grid`, storing every `options.stride`-th state and showing each
    /// step to `observer`, by the run loop of the Lagrangian side ([`crate::run::simulate()`]). A
    /// failing step ends the run with [`crate::run::Termination::Failed`] and the trajectory up to the last
    /// good state.
    pub fn solve<O: Observer>(
        &mut self,
        start: State,
        grid: &TimeGrid,
        options: &RunOptions,
        observer: &mut O,
    ) -> Trajectory {
        simulate(self, start, grid, options, observer)
    }
}

impl<H: Hamiltonian, M: HamiltonianMethod<H>> Stepper for HamiltonianIntegrator<H, M> {
    fn dims(&self) -> (usize, usize) {
        (self.ham.dof(), 0)
    }
    fn advance(&mut self, state: &mut State, h: f64, steps: usize) -> Result<StepReport, Error> {
        let t0 = state.t;
        let mut report = StepReport::default();
        for k in 1..=steps {
            report = self.step(state, h)?;
            state.t = t0 + k as f64 * h;
        }
        Ok(report)
    }
    fn steps_done(&self) -> usize {
        self.steps
    }
}

/// Sets the step index of a run-time error raised by a method (which does not know it).
fn at_step(mut e: Error, k: usize) -> Error {
    if let Error::Step(failure) = &mut e {
        failure.step = k;
    }
    e
}
