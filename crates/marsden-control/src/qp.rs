//! The SQP subproblem, solved by Clarabel (a sparse interior-point solver for convex conic
//! programs):
//!
//! ```text
//!     minimise ½ dᵀ(H + δI + ρJ_EᵀJ_E)d + gᵀd
//!     subject to   J_E d = r_E,   J_I d ≤ r_I,   lo − z ≤ d ≤ hi − z,
//! ```
//!
//! with `E` the equality rows of the program and `I` its inequalities (the path constraints,
//! the last rows). The term `ρJ_EᵀJ_E` (an augmented Lagrangian's, [NW06] §17.3) is `ρ|r|²` on the feasible set, a
//! constant: it leaves the step unchanged and only shifts the multipliers (`λ = λ_ρ + ρJd`),
//! but it makes `P` positive semidefinite when `H` is positive definite on the null space of
//! `J` only, which an interior-point method for convex programs needs. That is the common case
//! with inner control points: the Lagrangian has no curvature of its own along them.
//!
//! in Clarabel's form `min ½dᵀPd + gᵀd, A d + s = b, s ∈ {0}^E × ℝ₊^(I + bounds)`, with `P`
//! the upper triangle in compressed sparse columns. Clarabel's duals `y` satisfy
//! `P d + g + Aᵀy = 0` (`y ≥ 0` on the nonnegative cone): the rows of `J` give the multipliers
//! `λ` of the Lagrangian `f + λᵀc` directly, nonnegative on the inequalities.
//!
//! Infeasibility is reported only with a checked Farkas certificate ([NW06] §12.2): `y` with
//! `y ≥ 0` on the inequality and bound rows, `Aᵀy ≈ 0` and `bᵀy < 0`. For any `d` meeting the constraints,
//! `yᵀ(b − Ad) = yᵀs ≥ 0`, so `bᵀy ≥ (Aᵀy)ᵀd ≥ −‖Aᵀy‖∞‖d‖₁`: no step with
//! `‖d‖₁ < |bᵀy| / ‖Aᵀy‖∞` (at least 10⁶ here) meets them. The certificate does not involve
//! the Hessian, so it holds whatever the regularisation.
//!
//! [NW06]: crate#references

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT,
};
use marsden::numerics::dense::max_or_nan;

/// The data of one subproblem (everything but the regularisation `δ`).
pub struct Subproblem<'a> {
    /// The upper triangle of `H` as `(row, column, value)`.
    pub hessian: &'a [(usize, usize, f64)],
    /// The cost gradient `g`.
    pub gradient: &'a [f64],
    /// The constraint Jacobian `J` as `(row, column, value)`.
    pub jacobian: &'a [(usize, usize, f64)],
    /// Number of rows of `J`.
    pub rows: usize,
    /// The last rows of `J` that are inequalities `J_I d ≤ r_I`.
    pub inequalities: usize,
    /// The right-hand side `r` (`−c` for the SQP step).
    pub rhs: &'a [f64],
    /// `(variable, upper)`: `d_i ≤ upper`.
    pub upper: &'a [(usize, f64)],
    /// `(variable, lower)`: `d_i ≥ lower`.
    pub lower: &'a [(usize, f64)],
}

/// What the solver returned.
#[derive(Debug, Clone)]
pub struct QpSolution {
    /// The step `d`.
    pub step: Vec<f64>,
    /// Multipliers of `J d = r`.
    pub lambda: Vec<f64>,
    /// Multipliers of the upper bounds (≥ 0), in the order of [`Subproblem::upper`].
    pub upper: Vec<f64>,
    /// Multipliers of the lower bounds (≥ 0), in the order of [`Subproblem::lower`].
    pub lower: Vec<f64>,
    /// Whether this is the elastic subproblem's solution.
    pub elastic: bool,
    /// `Σ (s⁺ + s⁻)` of the elastic subproblem (0 otherwise).
    pub elastic_violation: f64,
}

/// How a subproblem ended.
pub enum QpOutcome {
    /// Solved (to full or reduced accuracy).
    Solved(QpSolution),
    /// The constraints are inconsistent: Clarabel's certificate, checked.
    Infeasible(Certificate),
    /// Anything else, in the solver's words.
    Failed(String),
}

/// A checked certificate of primal infeasibility: which simple bounds it leans on.
#[derive(Debug, Clone, PartialEq)]
pub struct Certificate {
    /// The variables whose upper or lower bound carries a weight of the certificate (at least
    /// 10⁻⁶ of its largest weight), in increasing order.
    pub bounded: Vec<usize>,
    /// The inequality rows (counted from the first) that carry such a weight.
    pub inequalities: Vec<usize>,
}

/// The smallest `|bᵀy| / ‖Aᵀy‖∞` accepted: no step shorter than this (in ℓ1) is feasible.
const CERTIFIED_RADIUS: f64 = 1e6;

/// How the Hessian of a subproblem is made convex: `H + δI + ρJᵀJ`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Convexify {
    /// `δ`: changes the step (a regularisation).
    pub delta: f64,
    /// `ρ`: leaves the step unchanged.
    pub rho: f64,
}

impl Subproblem<'_> {
    /// Solves the subproblem with `H + δI`.
    pub fn solve(&self, delta: f64) -> QpOutcome {
        self.solve_with(Convexify { delta, rho: 0.0 })
    }

    /// The rows of `J` that are equalities.
    fn equalities(&self) -> usize {
        self.rows - self.inequalities
    }

    /// The upper triangle of `ρJ_EᵀJ_E` as triplets (repeated entries of `J` added).
    fn gram(&self, rho: f64) -> Vec<(usize, usize, f64)> {
        let mut by_row = vec![Vec::new(); self.equalities()];
        for &(r, c, v) in self.jacobian {
            if let Some(row) = by_row.get_mut(r) {
                row.push((c, v));
            }
        }
        let mut out = Vec::new();
        for row in &by_row {
            for (i, &(a, va)) in row.iter().enumerate() {
                out.push((a, a, rho * va * va));
                for &(b, vb) in &row[i + 1..] {
                    let v = rho * va * vb;
                    out.push(match a.cmp(&b) {
                        std::cmp::Ordering::Equal => (a, a, 2.0 * v),
                        std::cmp::Ordering::Less => (a, b, v),
                        std::cmp::Ordering::Greater => (b, a, v),
                    });
                }
            }
        }
        out
    }

    /// Solves the subproblem with `H + δI + ρJᵀJ`; the multipliers returned are those of `H + δI`.
    pub fn solve_with(&self, convexify: Convexify) -> QpOutcome {
        self.solve_general(convexify, None)
    }

    /// The elastic subproblem (SNOPT's elastic mode, [GMS05]; inconsistent linearisations,
    /// [NW06] §18.3): the rows
    /// of `J d = r` relaxed by slacks `s⁺, s⁻ ≥ 0` priced at `μ`,
    ///
    /// ```text
    ///     minimise ½ dᵀ(H + δI)d + gᵀd + μ Σ_i (s⁺_i + s⁻_i)   s.t.   J d + s⁺ − s⁻ = r,  bounds,
    /// ```
    ///
    /// always feasible (`d = 0` meets the bounds of an iterate inside them). Its step decreases
    /// the ℓ1 merit `f + μ‖c‖₁` of a problem whose linearisation has no solution;
    /// [`QpSolution::elastic_violation`] is `Σ (s⁺ + s⁻)`, the violation the step leaves in the
    /// linearised constraints. An inequality row `J_I d + s⁺ − s⁻ ≤ r_I` has both slacks too:
    /// `s⁺` only tightens it, so it is zero at the optimum, and `s⁻` is the row's violation.
    ///
    /// [GMS05]: crate#references
    pub fn solve_elastic(&self, delta: f64, mu: f64) -> QpOutcome {
        self.solve_general(Convexify { delta, rho: 0.0 }, Some(mu))
    }

    fn solve_general(&self, convexify: Convexify, elastic: Option<f64>) -> QpOutcome {
        let Convexify { delta, rho } = convexify;
        let nx = self.gradient.len();
        let slacks = if elastic.is_some() { 2 * self.rows } else { 0 };
        let nv = nx + slacks;
        let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
        let gram = if rho > 0.0 {
            self.gram(rho)
        } else {
            Vec::new()
        };
        for &(r, c, v) in self.hessian.iter().chain(&gram) {
            rows.push(r);
            cols.push(c);
            vals.push(v);
        }
        for i in 0..nx {
            rows.push(i);
            cols.push(i);
            vals.push(delta);
        }
        let p = CscMatrix::new_from_triplets(nv, nv, rows, cols, vals);
        let mut q = self.gradient.to_vec();
        q.extend(std::iter::repeat_n(elastic.unwrap_or(0.0), slacks));
        let bound_rows = self.upper.len() + self.lower.len();
        let (mut rows, mut cols, mut vals) = (Vec::new(), Vec::new(), Vec::new());
        for &(r, c, v) in self.jacobian {
            rows.push(r);
            cols.push(c);
            vals.push(v);
        }
        let mut b = self.rhs.to_vec();
        for (j, &(i, hi)) in self.upper.iter().enumerate() {
            rows.push(self.rows + j);
            cols.push(i);
            vals.push(1.0);
            b.push(hi);
        }
        for (j, &(i, lo)) in self.lower.iter().enumerate() {
            rows.push(self.rows + self.upper.len() + j);
            cols.push(i);
            vals.push(-1.0);
            b.push(-lo);
        }
        // The slacks: `+s⁺ − s⁻` in each equality row, and `−s ≤ 0` as rows of the cone.
        for k in 0..slacks {
            rows.push(k % self.rows);
            cols.push(nx + k);
            vals.push(if k < self.rows { 1.0 } else { -1.0 });
            rows.push(self.rows + bound_rows + k);
            cols.push(nx + k);
            vals.push(-1.0);
            b.push(0.0);
        }
        let a = CscMatrix::new_from_triplets(self.rows + bound_rows + slacks, nv, rows, cols, vals);
        let mut cones = Vec::with_capacity(2);
        if self.equalities() > 0 {
            cones.push(ZeroConeT(self.equalities()));
        }
        if self.inequalities + bound_rows + slacks > 0 {
            cones.push(NonnegativeConeT(self.inequalities + bound_rows + slacks));
        }
        let settings = DefaultSettings {
            verbose: false,
            max_iter: 200,
            tol_gap_abs: 1e-12,
            tol_gap_rel: 1e-12,
            tol_feas: 1e-12,
            tol_ktratio: 1e-9,
            ..DefaultSettings::default()
        };
        let mut solver = match DefaultSolver::new(&p, &q, &a, &b, &cones, settings) {
            Ok(solver) => solver,
            Err(e) => return QpOutcome::Failed(e.to_string()),
        };
        solver.solve();
        let s = &solver.solution;
        match s.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                let (lambda, bounds) = s.z.split_at(self.rows);
                let (upper, lower) = bounds[..bound_rows].split_at(self.upper.len());
                let (step, slack) = s.x.split_at(nx);
                QpOutcome::Solved(QpSolution {
                    step: step.to_vec(),
                    lambda: self.unshifted(lambda, step, rho),
                    upper: upper.to_vec(),
                    lower: lower.to_vec(),
                    elastic: elastic.is_some(),
                    elastic_violation: slack.iter().sum(),
                })
            }
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                match self.certificate(&a, &b, &s.z) {
                    Some(certificate) => QpOutcome::Infeasible(certificate),
                    None => {
                        QpOutcome::Failed(format!("{:?} (certificate not confirmed)", s.status))
                    }
                }
            }
            status => QpOutcome::Failed(format!("{status:?}")),
        }
    }
}

impl Subproblem<'_> {
    /// The multipliers of `H + δI` from those of `H + δI + ρJᵀJ`: `λ = λ_ρ + ρJd`.
    fn unshifted(&self, lambda: &[f64], d: &[f64], rho: f64) -> Vec<f64> {
        let mut out = lambda.to_vec();
        if rho > 0.0 {
            let equalities = self.equalities();
            for &(r, c, v) in self.jacobian.iter().filter(|e| e.0 < equalities) {
                out[r] += rho * v * d[c];
            }
        }
        out
    }

    /// Checks Clarabel's certificate `y` against `A` and `b` (see the module's doc).
    fn certificate(&self, a: &CscMatrix<f64>, b: &[f64], y: &[f64]) -> Option<Certificate> {
        // NaN-propagating maxima: a NaN anywhere must not pass as a certificate.
        let weight = y.iter().map(|v| v.abs()).fold(0.0, max_or_nan);
        let bty: f64 = b.iter().zip(y).map(|(b, y)| b * y).sum();
        let signed = &y[self.equalities()..];
        if !(weight > 0.0 && bty < 0.0) || signed.iter().any(|&v| v < -1e-9 * weight) {
            return None;
        }
        // Aᵀy, column by column of the compressed sparse columns.
        let aty = (0..a.n).map(|c| {
            (a.colptr[c]..a.colptr[c + 1])
                .map(|i| a.nzval[i] * y[a.rowval[i]])
                .sum::<f64>()
        });
        let residual = aty.map(f64::abs).fold(0.0, max_or_nan);
        if residual.is_nan() || residual * CERTIFIED_RADIUS > -bty {
            return None;
        }
        let (rows, bounds) = signed.split_at(self.inequalities);
        let inequalities = (rows.iter().enumerate())
            .filter(|(_, w)| **w >= 1e-6 * weight)
            .map(|(i, _)| i)
            .collect();
        let (upper, lower) = bounds.split_at(self.upper.len());
        let mut bounded: Vec<usize> = (self.upper.iter().zip(upper))
            .chain(self.lower.iter().zip(lower))
            .filter(|(_, w)| **w >= 1e-6 * weight)
            .map(|((i, _), _)| *i)
            .collect();
        bounded.sort_unstable();
        bounded.dedup();
        Some(Certificate {
            bounded,
            inequalities,
        })
    }
}
