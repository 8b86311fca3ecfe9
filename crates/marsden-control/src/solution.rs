//! What a solve returns: the status, the optimal (or last) trajectory, controls, momenta,
//! costates and the convergence history.

use crate::stages::ControlStages;

/// How a solve ended. Anything but [`Status::Converged`] comes with the last iterate.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// The KKT residual and the constraint violation are below their tolerances.
    Converged,
    /// The iteration stopped for the reason given.
    Failed(Failure),
    /// The linearised constraints have no solution within the bounds: the QP solver's
    /// certificate, checked ([`crate::qp`]). For dynamics linear in `(q, u)` this proves the
    /// problem infeasible; otherwise it is a statement about the iterate's linearisation.
    Infeasible(Infeasibility),
    /// The iteration budget was spent first.
    IterationLimit,
}

/// Where a subproblem was proved infeasible, and which bounds its certificate leans on.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Infeasibility {
    /// The SQP iteration whose subproblem it was (0: at the first iterate).
    pub iteration: usize,
    /// The elastic steps taken from there, each reducing the violation, before it could be
    /// reduced no further ([`crate::qp::Subproblem::solve_elastic`]).
    pub elastic_steps: usize,
    /// The controls (indices) whose bounds the certificate uses, at some step.
    pub controls: Vec<usize>,
    /// The coordinates (indices) whose bounds the certificate uses, at some node.
    pub coordinates: Vec<usize>,
    /// The path inequalities (indices) the certificate uses, at some step.
    pub path: Vec<usize>,
}

/// Why an iteration failed.
#[derive(Debug, Clone, PartialEq)]
pub enum Failure {
    /// A cost, constraint or derivative was not finite at the iterate.
    NonFinite,
    /// The line search found no decrease of the merit function down to the smallest step.
    LineSearch {
        /// The last step length tried.
        step: f64,
    },
    /// The QP solver did not solve a subproblem even with the largest regularisation.
    Subproblem {
        /// The solver's status, in its words.
        status: String,
        /// The regularisation of the Hessian tried last.
        regularization: f64,
    },
}

/// One SQP iteration, as recorded in [`Solution::history`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iteration {
    /// The cost at the iterate.
    pub cost: f64,
    /// The largest violation at the iterate: `|c_i|` of an equality, `max(0, g_i)` of a
    /// path inequality.
    pub violation: f64,
    /// The KKT (stationarity and complementarity) residual at the iterate with the
    /// subproblem's multipliers.
    pub kkt: f64,
    /// The step length the line search accepted (0 on the last, converged record).
    pub step: f64,
    /// The regularisation `δ` added to the Hessian of the subproblem.
    pub regularization: f64,
}

/// The result of a DMOC solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// How the solve ended.
    pub status: Status,
    /// The discrete cost `J_d` at the returned iterate.
    pub cost: f64,
    /// SQP iterations taken.
    pub iterations: usize,
    /// The KKT residual at the returned iterate.
    pub kkt_residual: f64,
    /// The largest violation at the returned iterate (`|c_i|`, `max(0, g_i)` of a path inequality).
    pub constraint_violation: f64,
    /// `t_0 … t_N`.
    pub t: Vec<f64>,
    /// `q_0 … q_N`.
    pub q: Vec<Vec<f64>>,
    /// `p_0 … p_N` by the forced discrete Legendre transforms: `p_0 = −D₁L_d(q_0, q_1) − f_d⁻_0`,
    /// `p_k = D₂L_d(q_{k−1}, q_k) + f_d⁺_{k−1}` for `k ≥ 1`.
    pub p: Vec<Vec<f64>>,
    /// The control values, step by step and stage by stage: `u_0 … u_{N−1}` (`u_k` on
    /// `[t_k, t_{k+1}]`) for a rule with one value per step, `u_{k,1} … u_{k,σ}` (at
    /// `t_k + c_i h`) for a rule with control stages ([`crate::stages`]).
    pub u: Vec<Vec<f64>>,
    /// The time of each row of [`Solution::u`]: `t_k`, or `t_k + c_i h` for control stages.
    pub control_times: Vec<f64>,
    /// How the rule's steps see the controls (the stage times `c_i`, the control points).
    pub stages: ControlStages,
    /// Each step's inner control points `Q_1 … Q_{s−1}` back to back (empty for a two-point
    /// rule).
    pub inner: Vec<Vec<f64>>,
    /// The multipliers of the DEL constraints at the nodes `k = 1 … N−1` (the discrete
    /// costates), with the sign of the Lagrangian `J_d + Σ λᵀ c`.
    pub costates: Vec<Vec<f64>>,
    /// The multipliers of the fixed start components (positions, then rates).
    pub start_multipliers: Vec<f64>,
    /// The multipliers of the fixed end components (positions, then rates).
    pub end_multipliers: Vec<f64>,
    /// The path inequalities' values `g` (`≤ 0` where met), step by step: `σ n_g` per step,
    /// point by point ([`crate::stages::PathPoints`]).
    pub path_values: Vec<Vec<f64>>,
    /// The path inequalities' multipliers (`≥ 0`; positive where a constraint is active), step
    /// by step: `σ n_g` per step, point by point.
    pub path_multipliers: Vec<Vec<f64>>,
    /// One record per iteration.
    pub history: Vec<Iteration>,
}

impl Solution {
    /// Whether the solve converged.
    pub fn converged(&self) -> bool {
        self.status == Status::Converged
    }
}
