//! Newton's method for the implicit equations of a step, with options and work statistics.
//!
//! Solves `R(z) = 0` for a [`NonlinearSystem`] that returns the residual and its Jacobian in one
//! evaluation (that is what one hyper-dual evaluation of a discrete Lagrangian gives). The
//! iteration stops when either
//!
//! * the residual is small: `‖R(z)‖∞ ≤ tol_R · scale_R`, where `scale_R` is the size of the
//!   terms the residual is made of (supplied by the system; for a step `max(|p_k|, |∂L_d/∂Q₀|)`),
//!   so the test is independent of units, or
//! * the Newton update is at round-off: `‖Δz‖∞ ≤ tol_z · scale_z` (for a step: the size of the
//!   positions and offsets), after which one more evaluation makes the returned residual
//!   consistent with `z`.
//!
//! An optional backtracking line search halves the update until `‖R‖∞` decreases (Armijo on
//! the max-norm, Dennis & Schnabel §6.3). Reference: Deuflhard, *Newton Methods for Nonlinear
//! Problems* (2011), ch. 2.

use crate::numerics::dense::{SingularMatrix, max_norm, solve_in_place};

/// Options of the Newton solver (one options struct per layer).
///
/// Discrete momentum maps are conserved exactly only by the exact solution of the step
/// equations; a residual `r` left in step k changes them by `⟨r, ξ_Q(q_k)⟩`, so over N steps they
/// drift by up to `N · tol · |ξ_Q|`. For conservation at round-off set `residual_tolerance` to
/// 1e-15: the iteration then usually ends on the update-size criterion (measured on Kepler
/// e = 0.6, h = 2π/1000, 10⁵ midpoint steps: angular momentum within 2.5e-13 at 1.05 Newton
/// iterations per step; 9.5e-13 at the default 1e-12).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NewtonOptions {
    /// Tolerance on the residual, max-norm, relative to the size of the terms it is made of
    /// (for a step: `max(|p_k|, |∂L_d/∂Q₀|)`, so it does not depend on units) (default: 1e-12).
    pub residual_tolerance: f64,
    /// Tolerance on the Newton update, relative to the size of the unknowns (for a step: of
    /// the positions and offsets) (default: 1e-15, i.e. converged to round-off).
    pub step_tolerance: f64,
    /// Maximum number of Newton iterations per step (default: 50).
    pub max_iterations: usize,
    /// Backtracking line search on the residual norm (default: false; plain Newton is
    /// fastest when the predictor is good).
    pub line_search: bool,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            residual_tolerance: 1e-12,
            step_tolerance: 1e-15,
            max_iterations: 50,
            line_search: false,
        }
    }
}

impl NewtonOptions {
    /// Checks that every option is in its valid range.
    pub fn validate(&self) -> Result<(), crate::error::Error> {
        let positive = |name, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(crate::error::Error::InvalidOption {
                    name,
                    value,
                    reason: "must be positive and finite",
                })
            }
        };
        positive("residual_tolerance", self.residual_tolerance)?;
        positive("step_tolerance", self.step_tolerance)?;
        if self.max_iterations == 0 {
            return Err(crate::error::Error::InvalidOption {
                name: "max_iterations",
                value: 0.0,
                reason: "must be at least 1",
            });
        }
        Ok(())
    }
}

/// A square nonlinear system `R(z) = 0` with its Jacobian.
pub trait NonlinearSystem {
    /// Number of unknowns (and equations).
    fn dim(&self) -> usize;
    /// Writes `R(z)` into `residual` and `∂R/∂z` (row-major) into `jacobian`.
    fn evaluate(&mut self, z: &[f64], residual: &mut [f64], jacobian: &mut [f64]);
    /// Size of the terms the residual is made of, so that the tolerance is relative and
    /// independent of units (default 1: absolute). Read after each evaluation.
    fn residual_scale(&self) -> f64 {
        1.0
    }
    /// Size of the unknowns' natural units, for the update criterion (default
    /// `max(1, ‖z‖∞)`).
    fn unknown_scale(&self, z: &[f64]) -> f64 {
        max_norm(z).max(1.0)
    }
}

/// How one Newton solve went.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonReport {
    /// Newton updates applied.
    pub iterations: usize,
    /// System evaluations (residual + Jacobian).
    pub evaluations: usize,
    /// Jacobians factored (one per update on the general path; fewer where a structured path
    /// reuses its Jacobian, [`crate::separable::alpha`]).
    pub factorizations: usize,
    /// Final residual, max-norm.
    pub residual: f64,
}

/// Why a Newton solve failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum NewtonFailure {
    /// Tolerance not reached within the iteration budget.
    NotConverged(NewtonReport),
    /// The Jacobian could not be factored.
    Singular {
        /// Iteration at which factorisation failed.
        iteration: usize,
        /// Pivot found.
        pivot: f64,
    },
    /// The residual or the iterate became NaN or infinite.
    NonFinite(NewtonReport),
}

/// Reusable buffers of the Newton solver (no allocation per solve once sized).
#[derive(Debug, Clone, Default)]
pub struct NewtonWorkspace {
    residual: Vec<f64>,
    jacobian: Vec<f64>,
    update: Vec<f64>,
    trial: Vec<f64>,
}

impl NewtonWorkspace {
    fn resize(&mut self, m: usize) {
        self.residual.resize(m, 0.0);
        self.jacobian.resize(m * m, 0.0);
        self.update.resize(m, 0.0);
        self.trial.resize(m, 0.0);
    }

    /// The residual at the last evaluation.
    pub fn residual(&self) -> &[f64] {
        &self.residual
    }
}

/// Solves `R(z) = 0` starting from `z` (overwritten with the solution).
pub fn solve<Sys: NonlinearSystem>(
    system: &mut Sys,
    z: &mut [f64],
    options: &NewtonOptions,
    ws: &mut NewtonWorkspace,
) -> Result<NewtonReport, NewtonFailure> {
    let m = system.dim();
    ws.resize(m);
    let mut report = NewtonReport::default();
    let mut update_converged = false;
    system.evaluate(z, &mut ws.residual, &mut ws.jacobian);
    report.evaluations += 1;
    loop {
        report.residual = max_norm(&ws.residual);
        if !report.residual.is_finite() {
            return Err(NewtonFailure::NonFinite(report));
        }
        let tol = options.residual_tolerance * system.residual_scale();
        if report.residual <= tol || update_converged {
            return Ok(report);
        }
        if report.iterations >= options.max_iterations {
            return Err(NewtonFailure::NotConverged(report));
        }
        newton_update(ws, m, report.iterations)?;
        report.iterations += 1;
        report.factorizations += 1;
        let size = max_norm(&ws.update);
        if options.line_search {
            report.evaluations += line_search(system, z, ws, report.residual);
        } else {
            for (zi, d) in z.iter_mut().zip(&ws.update) {
                *zi += d;
            }
            system.evaluate(z, &mut ws.residual, &mut ws.jacobian);
            report.evaluations += 1;
        }
        update_converged = size <= options.step_tolerance * system.unknown_scale(z);
    }
}

/// Writes the Newton update `−J⁻¹R` into `ws.update` (the Jacobian buffer is consumed; the next
/// evaluation rewrites it).
fn newton_update(
    ws: &mut NewtonWorkspace,
    m: usize,
    iteration: usize,
) -> Result<(), NewtonFailure> {
    for (u, r) in ws.update.iter_mut().zip(&ws.residual) {
        *u = -r;
    }
    solve_in_place(&mut ws.jacobian, &mut ws.update, m)
        .map_err(|SingularMatrix { pivot, .. }| NewtonFailure::Singular { iteration, pivot })
}

/// Backtracking: halve the update until the residual norm decreases; returns evaluations used.
fn line_search<Sys: NonlinearSystem>(
    system: &mut Sys,
    z: &mut [f64],
    ws: &mut NewtonWorkspace,
    r0: f64,
) -> usize {
    let mut alpha = 1.0;
    let mut evaluations = 0;
    loop {
        for ((t, zi), d) in ws.trial.iter_mut().zip(z.iter()).zip(&ws.update) {
            *t = zi + alpha * d;
        }
        system.evaluate(&ws.trial, &mut ws.residual, &mut ws.jacobian);
        evaluations += 1;
        let r = max_norm(&ws.residual);
        if r.is_finite() && r <= (1.0 - 1e-4 * alpha) * r0 || alpha < 1e-3 {
            z.copy_from_slice(&ws.trial);
            for d in ws.update.iter_mut() {
                *d *= alpha;
            }
            return evaluations;
        }
        alpha *= 0.5;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// R(z) = (z0² + z1² − 4, z0 − z1): solution (√2, √2) from (1, 0.5).
    struct Circle;
    impl NonlinearSystem for Circle {
        fn dim(&self) -> usize {
            2
        }
        fn evaluate(&mut self, z: &[f64], r: &mut [f64], j: &mut [f64]) {
            r[0] = z[0] * z[0] + z[1] * z[1] - 4.0;
            r[1] = z[0] - z[1];
            j.copy_from_slice(&[2.0 * z[0], 2.0 * z[1], 1.0, -1.0]);
        }
    }

    #[test]
    fn converges_quadratically_to_round_off() {
        let mut z = [1.0, 0.5];
        let report = solve(
            &mut Circle,
            &mut z,
            &NewtonOptions::default(),
            &mut NewtonWorkspace::default(),
        )
        .unwrap();
        assert!((z[0] - 2f64.sqrt()).abs() < 1e-15 && (z[1] - 2f64.sqrt()).abs() < 1e-15);
        assert!(report.residual <= 1e-12);
        // Quadratic convergence from a distance of ~0.9: six updates at most.
        assert!(report.iterations <= 6, "{report:?}");
    }

    #[test]
    fn reports_exhausted_budget_with_residual() {
        let options = NewtonOptions {
            max_iterations: 1,
            ..NewtonOptions::default()
        };
        let err = solve(
            &mut Circle,
            &mut [1.0, 0.5],
            &options,
            &mut NewtonWorkspace::default(),
        )
        .unwrap_err();
        match err {
            NewtonFailure::NotConverged(r) => {
                assert_eq!(r.iterations, 1);
                assert!(r.residual > 1e-3);
            }
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn line_search_rescues_a_far_start() {
        // atan has a tiny basin for plain Newton: from z = 3 it diverges.
        struct Atan;
        impl NonlinearSystem for Atan {
            fn dim(&self) -> usize {
                1
            }
            fn evaluate(&mut self, z: &[f64], r: &mut [f64], j: &mut [f64]) {
                r[0] = z[0].atan();
                j[0] = 1.0 / (1.0 + z[0] * z[0]);
            }
        }
        let plain = NewtonOptions::default();
        let plain_result = solve(
            &mut Atan,
            &mut [3.0],
            &plain,
            &mut NewtonWorkspace::default(),
        );
        assert!(plain_result.is_err());
        let with_search = NewtonOptions {
            line_search: true,
            ..plain
        };
        let mut z = [3.0];
        solve(
            &mut Atan,
            &mut z,
            &with_search,
            &mut NewtonWorkspace::default(),
        )
        .unwrap();
        assert!(z[0].abs() < 1e-12);
    }
}
