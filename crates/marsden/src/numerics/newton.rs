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

use crate::error::InputError;
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
                Err(crate::error::Error::Input(InputError::InvalidOption {
                    name,
                    value,
                    reason: "must be positive and finite",
                }))
            }
        };
        positive("residual_tolerance", self.residual_tolerance)?;
        positive("step_tolerance", self.step_tolerance)?;
        if self.max_iterations == 0 {
            return Err(crate::error::Error::Input(InputError::InvalidOption {
                name: "max_iterations",
                value: 0.0,
                reason: "must be at least 1",
            }));
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

/// Newton's stopping rule, the one every Newton iteration of the crate uses (the general solve
/// below, the statically sized kernels, the separable steps, the RATTLE projection): after each
/// evaluation [`Convergence::check`] stops the iteration when
///
/// * the residual is non-finite (a failure: [`NewtonFailure::NonFinite`]),
/// * the residual is small relative to the size of its terms, `‖R‖∞ ≤ tol_R · scale_R`, or the
///   last update was at round-off, `‖Δz‖∞ ≤ tol_z · scale_z` (converged), or
/// * the iteration budget is spent ([`NewtonFailure::NotConverged`]).
///
/// The loops inline it: it is a few comparisons on copied numbers.
#[derive(Debug, Clone, Copy)]
pub struct Convergence {
    residual_tolerance: f64,
    step_tolerance: f64,
    max_iterations: usize,
    update_converged: bool,
}

impl Convergence {
    /// The rule of `options`, before any update.
    #[inline(always)]
    pub fn new(options: &NewtonOptions) -> Self {
        Self {
            residual_tolerance: options.residual_tolerance,
            step_tolerance: options.step_tolerance,
            max_iterations: options.max_iterations,
            update_converged: false,
        }
    }

    /// After an evaluation whose residual (in `report`) is made of terms of size `scale`:
    /// `Ok(true)` converged, `Ok(false)` iterate on, `Err` failed.
    #[inline(always)]
    pub fn check(&self, report: &NewtonReport, scale: f64) -> Result<bool, NewtonFailure> {
        self.check_gated(report, scale, true)
    }

    /// [`Convergence::check`] where a small residual counts only if `gate` holds (a reused
    /// Jacobian converges linearly: its residual test waits for a small estimated error).
    #[inline(always)]
    pub fn check_gated(
        &self,
        report: &NewtonReport,
        scale: f64,
        gate: bool,
    ) -> Result<bool, NewtonFailure> {
        if !report.residual.is_finite() {
            return Err(NewtonFailure::NonFinite(*report));
        }
        if (self.residual_small(report.residual, scale) && gate) || self.update_converged {
            return Ok(true);
        }
        if report.iterations >= self.max_iterations {
            return Err(NewtonFailure::NotConverged(*report));
        }
        Ok(false)
    }

    /// Whether `residual ≤ tol_R · scale`.
    #[inline(always)]
    pub fn residual_small(&self, residual: f64, scale: f64) -> bool {
        residual <= self.residual_tolerance * scale
    }

    /// Whether `residual` (finite or not) meets the rule after an update: small, or the update
    /// at round-off.
    #[inline(always)]
    pub fn converged(&self, residual: f64, scale: f64) -> bool {
        self.residual_small(residual, scale) || self.update_converged
    }

    /// Records an update of max-norm `size` to unknowns of size `scale`: at round-off when
    /// `size ≤ tol_z · scale`.
    #[inline(always)]
    pub fn record_update(&mut self, size: f64, scale: f64) {
        self.update_converged = size <= self.step_tolerance * scale;
    }

    /// The relative update tolerance `tol_z`.
    #[inline(always)]
    pub fn step_tolerance(&self) -> f64 {
        self.step_tolerance
    }
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
    let mut convergence = Convergence::new(options);
    system.evaluate(z, &mut ws.residual, &mut ws.jacobian);
    report.evaluations += 1;
    loop {
        report.residual = max_norm(&ws.residual);
        if convergence.check(&report, system.residual_scale())? {
            return Ok(report);
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
        convergence.record_update(size, system.unknown_scale(z));
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
