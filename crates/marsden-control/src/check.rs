//! Derivatives of the program against central finite differences (the `check_*` pattern of
//! trep: compare the analytic derivative with `(f(z + εe_j) − f(z − εe_j)) / 2ε`, column by
//! column; the error of the difference quotient is `O(ε²)` plus round-off `O(ε_mach/ε)`).

use marsden::{Lagrangian, Rule};

use crate::error::ControlError;
use crate::model::{ControlForce, FinalCost, PathConstraint, RunningCost};
use crate::problem::{OptimalControl, check_len};
use crate::stages::StagedControls;
use crate::transcription::Evaluation;
use marsden::numerics::dense::max_or_nan;

/// The largest differences between the AD derivatives of the program and central differences.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DerivativeCheck {
    /// `max_j |∂f/∂z_j − FD|` of the cost.
    pub gradient: f64,
    /// `max_{ij} |∂c_i/∂z_j − FD|` of the constraints.
    pub jacobian: f64,
    /// `max_{ij} |∂²ℒ/∂z_i∂z_j − FD of ∇ℒ|` of the Lagrangian `ℒ = f + λᵀc`.
    pub hessian: f64,
    /// The largest magnitude among the derivatives compared (for a relative reading).
    pub scale: f64,
}

impl<L, F, C, P, G> OptimalControl<L, F, C, P, G>
where
    L: Lagrangian,
    F: ControlForce,
    C: RunningCost,
    P: FinalCost,
    G: PathConstraint,
{
    /// The number of unknowns and of constraints of the program transcribed with `rule`.
    ///
    /// # Errors
    /// [`ControlError::UnsupportedRule`] as [`OptimalControl::solve`].
    pub fn sizes<R: Rule + StagedControls>(
        &self,
        rule: &R,
    ) -> Result<(usize, usize), ControlError> {
        self.with_program(rule, |program| (program.layout.unknowns(), program.rows))
    }

    /// Compares the gradient, constraint Jacobian and Hessian of the Lagrangian (multipliers
    /// `lambda`) of the program transcribed with `rule` at `z` with central differences of step
    /// `eps`.
    ///
    /// # Errors
    /// [`ControlError::Length`] when `z` or `lambda` do not fit [`OptimalControl::sizes`];
    /// [`ControlError::UnsupportedRule`] as [`OptimalControl::solve`].
    pub fn check_derivatives<R: Rule + StagedControls>(
        &self,
        rule: &R,
        z: &[f64],
        lambda: &[f64],
        eps: f64,
    ) -> Result<DerivativeCheck, ControlError> {
        let (unknowns, rows) = self.sizes(rule)?;
        check_len("z", z.len(), unknowns)?;
        check_len("lambda", lambda.len(), rows)?;
        self.with_program(rule, |program| {
            let e = program.evaluate(z);
            let jac = dense(&e.jacobian, rows, unknowns);
            let mut hess = vec![0.0; unknowns * unknowns];
            for (r, c, v) in program.hessian(z, lambda) {
                hess[r * unknowns + c] += v;
                if r != c {
                    hess[c * unknowns + r] += v;
                }
            }
            let lagrangian_gradient = |e: &Evaluation| {
                let mut g = e.gradient.clone();
                for &(r, c, v) in &e.jacobian {
                    g[c] += v * lambda[r];
                }
                g
            };
            let mut check = DerivativeCheck {
                gradient: 0.0,
                jacobian: 0.0,
                hessian: 0.0,
                scale: 0.0,
            };
            let mut zp = z.to_vec();
            for j in 0..unknowns {
                zp[j] = z[j] + eps;
                let plus = program.evaluate(&zp);
                zp[j] = z[j] - eps;
                let minus = program.evaluate(&zp);
                zp[j] = z[j];
                let fd = (plus.cost - minus.cost) / (2.0 * eps);
                check.gradient = max_or_nan(check.gradient, (fd - e.gradient[j]).abs());
                check.scale = max_or_nan(check.scale, e.gradient[j].abs());
                for i in 0..rows {
                    let fd = (plus.constraints[i] - minus.constraints[i]) / (2.0 * eps);
                    let exact = jac[i * unknowns + j];
                    check.jacobian = max_or_nan(check.jacobian, (fd - exact).abs());
                    check.scale = max_or_nan(check.scale, exact.abs());
                }
                let (gp, gm) = (lagrangian_gradient(&plus), lagrangian_gradient(&minus));
                for i in 0..unknowns {
                    let fd = (gp[i] - gm[i]) / (2.0 * eps);
                    let exact = hess[i * unknowns + j];
                    check.hessian = max_or_nan(check.hessian, (fd - exact).abs());
                    check.scale = max_or_nan(check.scale, exact.abs());
                }
            }
            check
        })
    }
}

/// A dense row-major matrix from `(row, column, value)` triplets (repeated entries added).
fn dense(triplets: &[(usize, usize, f64)], rows: usize, cols: usize) -> Vec<f64> {
    let mut out = vec![0.0; rows * cols];
    for &(r, c, v) in triplets {
        out[r * cols + c] += v;
    }
    out
}
