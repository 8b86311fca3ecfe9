//! The implicit midpoint rule on Hamilton's equations,
//!
//! ```text
//!     z₁ = z₀ + h X_H(t₀ + h/2, (z₀ + z₁)/2),      z = (q, p),
//! ```
//!
//! symplectic and symmetric of order 2 for every `H` ([HLW06] §VI.3, Thm VI.3.5; it is the
//! one-stage Gauss method). For `H = ½pᵀM⁻¹p + V(q)` with constant `M` it coincides with the
//! midpoint variational integrator of `L = ½vᵀMv − V` (the crate's
//! [conventions](crate#conventions), equivalences).
//!
//! Solved by Newton's method ([`crate::numerics::newton`]) for the increment `Δ = z₁ − z₀`, with residual
//! `Δ/h − X_H(z₀ + Δ/2)` and Jacobian `I/h − ½DX_H`, `DX_H = J∇²H` by AD. The residual is in the
//! units of the vector field (velocities and forces) and scaled by `‖X_H(z₀)‖`, like the
//! momentum residual of the variational step; a residual `r` moves `z₁` by only `h·r`. The step map's
//! Jacobian follows from the implicit function theorem at the converged `Δ`:
//! `∂z₁/∂z₀ = I + (I − (h/2)DX_H)⁻¹ h DX_H`.
//!
//! [HLW06]: crate#references

use super::{Hamiltonian, HamiltonianMethod, PhaseJet, vector_field};
use crate::error::Error;
use crate::error::{StepError, StepFailure};
use crate::integrator::StepReport;
use crate::mechanics::State;
use crate::numerics::dense::{Lu, max_norm};
use crate::numerics::newton::{
    self, NewtonFailure, NewtonOptions, NewtonWorkspace, NonlinearSystem,
};

/// Implicit midpoint rule for a [`Hamiltonian`] (symplectic, order 2).
#[derive(Debug, Clone, Default)]
pub struct ImplicitMidpoint {
    options: NewtonOptions,
    workspace: NewtonWorkspace,
    jet: PhaseJet,
    z0: Vec<f64>,
    delta: Vec<f64>,
}

impl ImplicitMidpoint {
    /// The method with the given Newton options (validated).
    pub fn new(options: NewtonOptions) -> Result<Self, Error> {
        options.validate()?;
        Ok(Self {
            options,
            ..Self::default()
        })
    }

    /// Solves the step from `state` for `Δ = z₁ − z₀` (left in `self.delta`).
    fn solve<H: Hamiltonian>(
        &mut self,
        ham: &H,
        state: &State,
        h: f64,
    ) -> Result<StepReport, Error> {
        let n = ham.dof();
        self.z0.clear();
        self.z0.extend(state.q.iter().chain(&state.p));
        // Predictor: explicit Euler, Δ = h X_H(z₀).
        self.delta.resize(2 * n, 0.0);
        let (dq, dp) = self.delta.split_at_mut(n);
        vector_field(ham, state.t, &state.q, &state.p, dq, dp);
        let scale = max_norm(&self.delta);
        if !scale.is_finite() {
            return Err(Error::Step(StepFailure {
                step: 0,
                t: state.t,
                cause: StepError::NonFinite {
                    what: "Hamilton's vector field",
                },
            }));
        }
        self.delta.iter_mut().for_each(|d| *d *= h);
        let mut system = MidpointSystem {
            ham,
            t: state.t + 0.5 * h,
            h,
            scale,
            z0: &self.z0,
            jet: &mut self.jet,
            x: vec![0.0; 2 * n],
        };
        let result = newton::solve(
            &mut system,
            &mut self.delta,
            &self.options,
            &mut self.workspace,
        );
        let report = result.map_err(|failure| newton_error(failure, state.t, &self.options))?;
        if !self.delta.iter().all(|d| d.is_finite()) {
            return Err(Error::Step(StepFailure {
                step: 0,
                t: state.t,
                cause: StepError::NonFinite {
                    what: "the new state",
                },
            }));
        }
        Ok(StepReport {
            iterations: report.iterations,
            residual: report.residual,
        })
    }

    fn accept(&self, state: &mut State, h: f64) {
        let n = state.q.len();
        state
            .q
            .iter_mut()
            .zip(&self.delta[..n])
            .for_each(|(q, d)| *q += d);
        state
            .p
            .iter_mut()
            .zip(&self.delta[n..])
            .for_each(|(p, d)| *p += d);
        state.t += h;
    }
}

impl<H: Hamiltonian> HamiltonianMethod<H> for ImplicitMidpoint {
    fn name(&self) -> String {
        "implicit midpoint".into()
    }

    fn is_symplectic(&self) -> bool {
        true
    }

    fn step(&mut self, ham: &H, state: &mut State, h: f64) -> Result<StepReport, Error> {
        let report = self.solve(ham, state, h)?;
        self.accept(state, h);
        Ok(report)
    }

    fn step_with_jacobian(
        &mut self,
        ham: &H,
        state: &mut State,
        h: f64,
        jac: &mut [f64],
    ) -> Result<StepReport, Error> {
        let report = self.solve(ham, state, h)?;
        let m = self.z0.len();
        let x: Vec<f64> = self
            .z0
            .iter()
            .zip(&self.delta)
            .map(|(z, d)| z + 0.5 * d)
            .collect();
        self.jet.eval(ham, state.t + 0.5 * h, &x);
        let mut dx = vec![0.0; m * m];
        self.jet.vector_field_jacobian(&mut dx);
        // A = I − (h/2) DX; DF = I + A⁻¹ (h DX).
        let a: Vec<f64> = (0..m * m)
            .map(|k| f64::from(u8::from(k / m == k % m)) - 0.5 * h * dx[k])
            .collect();
        let mut lu = Lu::new();
        lu.factor(&a, m).map_err(|e| {
            Error::Step(StepFailure {
                step: 0,
                t: state.t,
                cause: StepError::SingularJacobian {
                    iteration: report.iterations,
                    pivot: e.pivot,
                },
            })
        })?;
        let (mut col, mut scratch) = (vec![0.0; m], Vec::with_capacity(m));
        for j in 0..m {
            (0..m).for_each(|i| col[i] = h * dx[i * m + j]);
            lu.solve(&mut col, &mut scratch);
            (0..m).for_each(|i| jac[i * m + j] = f64::from(u8::from(i == j)) + col[i]);
        }
        self.accept(state, h);
        Ok(report)
    }
}

/// Residual `Δ/h − X_H(z₀ + Δ/2)` and Jacobian `I/h − ½DX_H`.
struct MidpointSystem<'a, H> {
    ham: &'a H,
    t: f64,
    h: f64,
    /// `‖X_H(z₀)‖∞`, the scale of the residual.
    scale: f64,
    z0: &'a [f64],
    jet: &'a mut PhaseJet,
    x: Vec<f64>,
}

impl<H: Hamiltonian> NonlinearSystem for MidpointSystem<'_, H> {
    fn dim(&self) -> usize {
        self.z0.len()
    }

    fn residual_scale(&self) -> f64 {
        self.scale.max(1.0)
    }

    fn evaluate(&mut self, delta: &[f64], r: &mut [f64], jac: &mut [f64]) {
        let m = self.z0.len();
        for ((x, z), d) in self.x.iter_mut().zip(self.z0).zip(delta) {
            *x = z + 0.5 * d;
        }
        self.jet.eval(self.ham, self.t, &self.x);
        self.jet.vector_field(r);
        self.jet.vector_field_jacobian(jac);
        for (ri, d) in r.iter_mut().zip(delta) {
            *ri = d / self.h - *ri;
        }
        for (k, j) in jac.iter_mut().enumerate() {
            *j = f64::from(u8::from(k / m == k % m)) / self.h - 0.5 * *j;
        }
    }
}

/// The typed error of a failed Newton solve (the step index is filled in by the integrator).
pub(super) fn newton_error(failure: NewtonFailure, t: f64, options: &NewtonOptions) -> Error {
    match failure {
        NewtonFailure::NotConverged(r) => Error::Step(StepFailure {
            step: 0,
            t,
            cause: StepError::NewtonDidNotConverge {
                iterations: r.iterations,
                residual: r.residual,
                tolerance: options.residual_tolerance,
            },
        }),
        NewtonFailure::Singular { iteration, pivot } => Error::Step(StepFailure {
            step: 0,
            t,
            cause: StepError::SingularJacobian { iteration, pivot },
        }),
        NewtonFailure::NonFinite(_) => Error::Step(StepFailure {
            step: 0,
            t,
            cause: StepError::NonFinite {
                what: "the Newton residual",
            },
        }),
    }
}
