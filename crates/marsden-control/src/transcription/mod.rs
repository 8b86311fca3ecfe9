//! The nonlinear program of DMOC ([OJM11] §3): unknowns, constraints, cost and their
//! derivatives.
//!
//! Unknowns in time order, `z = (q_0, u_0, Q_0, q_1, u_1, Q_1, …, u_{N−1}, Q_{N−1}, q_N)`, so
//! that step `k` reads the contiguous block `(q_k, u_k, Q_k, q_{k+1})` and every matrix is
//! banded in `k`; `u_k` holds the step's control values (one, or one per stage:
//! [`crate::stages`]) and `Q_k` the rule's inner control points (none for a two-point rule).
//! With `m_k = D₁L_d + f_d⁻_k` and `P_k = D₂L_d + f_d⁺_k` (the derivatives at the step's first
//! and last control points) the constraints are, in this row order,
//!
//! ```text
//!     q_0,i − a_i = 0                       (fixed start positions)
//!     −m_0,i − p⁰_i = 0                     (fixed start momenta; p⁰ = ∂L/∂v(t_0, q_0, v⁰) for velocities)
//!     P_{k−1} + m_k = 0,     k = 1 … N−1    (forced DEL: the core's step equations)
//!     q_N,i − b_i = 0                       (fixed end positions)
//!     P_{N−1},i − p^N_i = 0                 (fixed end momenta)
//!     D_jL_d + f_j = 0,     j = 1 … s−1     (each step's inner points, step by step)
//!     g(t, q(τ_i), q̇(τ_i), u_{k,i}) ≤ 0        (the path inequalities, step by step: [`path`])
//! ```
//!
//! — the inequalities last, so that the equality rows come first in every matrix
//! ([`Evaluation::inequalities`]).
//!
//! and the cost is `Σ_k C_d,k + Φ(q_N, P_{N−1})`. The multipliers of the DEL rows are the
//! discrete costates.
//!
//! [OJM11]: crate#references

pub mod path;
pub mod step;

use marsden::numerics::ad::{self, HessianParts, MultiFunction};
use marsden::numerics::dense::max_or_nan;
use marsden::{DiscreteAction, DiscreteForce, Lagrangian, TimeGrid};

use crate::model::{FinalCost, PathConstraint};
use crate::problem::{Boundary, Rate};
use crate::stages::{ControlStages, PathPoints};
use path::PathFunction;
use step::{BoundaryMomentum, StepFunction, StepParts, Weighted};

/// Where the unknowns sit in `z`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Degrees of freedom `n`.
    pub n: usize,
    /// Controls `m`.
    pub m: usize,
    /// Steps `N`.
    pub steps: usize,
    /// Control values per step `σ`.
    pub stages: usize,
    /// Inner control points per step `s − 1`.
    pub inner: usize,
}

impl Layout {
    /// Unknowns per step before the next node: `q_k`, `σ` controls, `s − 1` inner points.
    pub fn stride(&self) -> usize {
        self.n + self.stages * self.m + self.inner * self.n
    }
    /// Index of `q_k`.
    pub fn q(&self, k: usize) -> usize {
        k * self.stride()
    }
    /// Index of `u_k` (its `σ m` control values, stage by stage).
    pub fn u(&self, k: usize) -> usize {
        k * self.stride() + self.n
    }
    /// Index of the inner control points of step `k`.
    pub fn inner_points(&self, k: usize) -> usize {
        self.u(k) + self.stages * self.m
    }
    /// Length of `z`.
    pub fn unknowns(&self) -> usize {
        self.steps * self.stride() + self.n
    }
    /// Length of a step's block `(q_k, u_k, Q_k, q_{k+1})`.
    pub fn block(&self) -> usize {
        self.stride() + self.n
    }
    /// What unknown `i` is.
    pub fn unknown(&self, i: usize) -> Unknown {
        let within = i % self.stride();
        let controls = self.stages * self.m;
        match within {
            w if w < self.n => Unknown::Coordinate(w),
            w if w < self.n + controls => Unknown::Control((w - self.n) % self.m),
            w => Unknown::Inner((w - self.n - controls) % self.n),
        }
    }
}

/// What an unknown of `z` is ([`Layout::unknown`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unknown {
    /// Coordinate `i` of a node.
    Coordinate(usize),
    /// Control `j` (of some stage).
    Control(usize),
    /// Coordinate `i` of an inner control point.
    Inner(usize),
}

/// The fixed components of one boundary and the rows they occupy.
#[derive(Debug, Clone)]
struct End {
    /// `(component, value)` of the fixed positions.
    q: Vec<(usize, f64)>,
    /// `(component, value)` of the fixed rates.
    rate: Vec<(usize, f64)>,
    /// The rate is a velocity: the target momentum is `∂L/∂v(t, q, v)`.
    velocity: Option<Vec<f64>>,
    /// First row of the positions; the rates follow.
    row: usize,
}

impl End {
    fn of(boundary: &Boundary, row: usize) -> Self {
        let fixed = |values: &[Option<f64>]| -> Vec<(usize, f64)> {
            values
                .iter()
                .enumerate()
                .filter_map(|(i, v)| v.map(|v| (i, v)))
                .collect()
        };
        let rate = fixed(boundary.rate_values());
        let velocity = match &boundary.rate {
            Rate::Velocity(_) if !rate.is_empty() => Some(rate.iter().map(|&(_, v)| v).collect()),
            _ => None,
        };
        Self {
            q: fixed(&boundary.q),
            rate,
            velocity,
            row,
        }
    }
    fn rows(&self) -> usize {
        self.q.len() + self.rate.len()
    }
    /// The row of rate component `i`, if it is fixed.
    fn rate_row(&self, i: usize) -> Option<usize> {
        let start = self.row + self.q.len();
        self.rate
            .iter()
            .position(|&(c, _)| c == i)
            .map(|j| start + j)
    }
}

/// The program's values and first derivatives at a point.
#[derive(Debug, Clone, Default)]
pub struct Evaluation {
    /// The cost.
    pub cost: f64,
    /// Its gradient (dense).
    pub gradient: Vec<f64>,
    /// The constraints.
    pub constraints: Vec<f64>,
    /// Their Jacobian as `(row, column, value)`.
    pub jacobian: Vec<(usize, usize, f64)>,
    /// `m_k` and `P_k` of every step (`2n` per step), for the momenta of the result.
    pub momenta: Vec<f64>,
    /// The last rows of `constraints` that are inequalities `c_i ≤ 0` (the others are
    /// equalities `c_i = 0`).
    pub inequalities: usize,
}

impl Evaluation {
    /// Whether every value is finite.
    pub fn is_finite(&self) -> bool {
        self.cost.is_finite()
            && self.gradient.iter().all(|v| v.is_finite())
            && self.constraints.iter().all(|v| v.is_finite())
            && self.jacobian.iter().all(|e| e.2.is_finite())
    }

    /// The rows that are equalities.
    pub fn equalities(&self) -> usize {
        self.constraints.len() - self.inequalities
    }

    /// How far each constraint is from being met: `|c_i|` for an equality, `max(0, c_i)` for
    /// an inequality (NaN stays NaN).
    pub fn violations(&self) -> impl Iterator<Item = f64> + '_ {
        let equalities = self.equalities();
        (self.constraints.iter().enumerate()).map(move |(i, &c)| match i < equalities {
            true => c.abs(),
            false if c.is_nan() => c,
            false => c.max(0.0),
        })
    }

    /// The largest violation ([`Evaluation::violations`]; NaN if any is).
    pub fn max_violation(&self) -> f64 {
        self.violations().fold(0.0, max_or_nan)
    }

    /// The sum of the violations: the ℓ1 norm of the constraints' infeasibility.
    pub fn l1_violation(&self) -> f64 {
        self.violations().sum()
    }
}

/// The transcribed program.
pub struct Transcription<'a, L, A, FD, CD, P, G> {
    lagrangian: &'a L,
    parts: StepParts<'a, A, FD, CD, P>,
    /// The path inequalities and where they are imposed.
    path: (&'a G, PathPoints),
    /// The last step's parts (with `Φ`).
    last: StepParts<'a, A, FD, CD, P>,
    grid: TimeGrid,
    /// Where the unknowns sit.
    pub layout: Layout,
    start: End,
    end: End,
    /// First DEL row.
    del_row: usize,
    /// First row of the inner points' equations.
    inner_row: usize,
    /// First row of the path inequalities.
    path_row: usize,
    /// Number of constraints.
    pub rows: usize,
}

/// What the transcription is made of besides the steps: the system, the final cost, the path
/// inequalities, the grid and the boundaries.
pub struct Ingredients<'a, L, P, G> {
    /// The system (for boundary velocities).
    pub lagrangian: &'a L,
    /// `Φ(q_N, p_N)`.
    pub final_cost: &'a P,
    /// `g(t, q, q̇, u) ≤ 0`.
    pub path: &'a G,
    /// The time grid.
    pub grid: TimeGrid,
    /// The conditions at the start and at the end.
    pub ends: (&'a Boundary, &'a Boundary),
}

impl<'a, L, A, FD, CD, P, G> Transcription<'a, L, A, FD, CD, P, G>
where
    L: Lagrangian,
    A: DiscreteAction,
    FD: DiscreteForce,
    CD: DiscreteAction,
    P: FinalCost,
    G: PathConstraint,
{
    /// The program of `parts` with `ingredients`.
    pub fn new(parts: StepParts<'a, A, FD, CD, P>, ingredients: Ingredients<'a, L, P, G>) -> Self {
        let Ingredients {
            lagrangian,
            final_cost,
            path,
            grid,
            ends: (start, end),
        } = ingredients;
        let layout = Layout {
            n: parts.n,
            m: parts.m,
            steps: grid.steps,
            stages: parts.stages.count(),
            inner: parts.stages.inner(),
        };
        let start = End::of(start, 0);
        let del_row = start.rows();
        let end = End::of(end, del_row + (grid.steps - 1) * parts.n);
        let inner_row = end.row + end.rows();
        let path_row = inner_row + grid.steps * layout.inner * parts.n;
        let rows = path_row + grid.steps * layout.stages * path.count();
        let mut last = parts;
        last.final_cost = Some(final_cost);
        let mut parts = parts;
        parts.final_cost = None;
        Self {
            lagrangian,
            parts,
            path: (path, parts.stages.path_points()),
            last,
            grid,
            layout,
            start,
            end,
            del_row,
            inner_row,
            path_row,
            rows,
        }
    }

    /// The number of path inequalities (the last rows).
    pub fn inequalities(&self) -> usize {
        self.rows - self.path_row
    }

    /// Step `k`'s path inequalities, if there are any.
    fn path_step(&self, k: usize) -> Option<PathFunction<'_, G>> {
        (self.path.0.count() > 0).then(|| PathFunction {
            path: self.path.0,
            points: &self.path.1,
            t0: self.grid.time(k),
            h: self.grid.h,
            n: self.layout.n,
            m: self.layout.m,
        })
    }

    /// The first row of step `k`'s path inequalities.
    fn path_rows(&self, k: usize) -> usize {
        self.path_row + k * self.layout.stages * self.path.0.count()
    }

    /// How the steps see their controls.
    pub fn stages(&self) -> &'a ControlStages {
        self.parts.stages
    }

    /// The row and sign of output `out` of step `k` ([`StepFunction`]), `None` for the cost and
    /// for a free boundary component.
    fn output_row(&self, k: usize, out: usize) -> Option<(usize, f64)> {
        let n = self.layout.n;
        match out {
            o if o < n => self.minus_row(k, o),
            o if o < 2 * n => self.plus_row(k, o - n),
            o if o == 2 * n => None,
            o => Some((
                self.inner_row + k * self.layout.inner * n + o - 2 * n - 1,
                1.0,
            )),
        }
    }

    fn step(&self, k: usize) -> StepFunction<'a, A, FD, CD, P> {
        let parts = if k + 1 == self.grid.steps {
            self.last
        } else {
            self.parts
        };
        StepFunction {
            parts,
            t0: self.grid.time(k),
            h: self.grid.h,
        }
    }

    /// The row and sign of component `i` of `m_k` (start momentum or the DEL at node `k`).
    fn minus_row(&self, k: usize, i: usize) -> Option<(usize, f64)> {
        if k == 0 {
            self.start.rate_row(i).map(|r| (r, -1.0))
        } else {
            Some((self.del_row + (k - 1) * self.layout.n + i, 1.0))
        }
    }

    /// The row and sign of component `i` of `P_k` (the DEL at node `k + 1` or end momentum).
    fn plus_row(&self, k: usize, i: usize) -> Option<(usize, f64)> {
        if k + 1 == self.grid.steps {
            self.end.rate_row(i).map(|r| (r, 1.0))
        } else {
            Some((self.del_row + k * self.layout.n + i, 1.0))
        }
    }

    /// The two boundaries with their node and time.
    fn ends(&self) -> [(&End, usize, f64); 2] {
        [
            (&self.start, 0, self.grid.t0),
            (&self.end, self.grid.steps, self.grid.t_end()),
        ]
    }

    /// Values and first derivatives at `z`.
    pub fn evaluate(&self, z: &[f64]) -> Evaluation {
        let Layout { n, .. } = self.layout;
        let b = self.layout.block();
        let mut e = Evaluation {
            cost: 0.0,
            gradient: vec![0.0; z.len()],
            constraints: vec![0.0; self.rows],
            jacobian: Vec::with_capacity(self.grid.steps * 2 * n * b + 4 * n * n),
            momenta: vec![0.0; 2 * n * self.grid.steps],
            inequalities: self.inequalities(),
        };
        let outputs = 2 * n + 1 + self.layout.inner * n;
        let (mut values, mut jac) = (vec![0.0; outputs], vec![0.0; outputs * b]);
        for k in 0..self.grid.steps {
            let col = self.layout.q(k);
            ad::jacobian(&self.step(k), &z[col..col + b], 0..b, &mut values, &mut jac);
            e.momenta[2 * n * k..2 * n * (k + 1)].copy_from_slice(&values[..2 * n]);
            for out in 0..outputs {
                if let Some((row, sign)) = self.output_row(k, out) {
                    e.constraints[row] += sign * values[out];
                    let entries = jac[out * b..(out + 1) * b].iter();
                    e.jacobian
                        .extend(entries.enumerate().map(|(j, &d)| (row, col + j, sign * d)));
                }
            }
            e.cost += values[2 * n];
            let grad = &jac[2 * n * b..(2 * n + 1) * b];
            e.gradient[col..col + b]
                .iter_mut()
                .zip(grad)
                .for_each(|(g, d)| *g += d);
            self.evaluate_path(k, z, &mut e);
        }
        for (end, node, t) in self.ends() {
            let col = self.layout.q(node);
            for (j, &(i, a)) in end.q.iter().enumerate() {
                e.constraints[end.row + j] = z[col + i] - a;
                e.jacobian.push((end.row + j, col + i, 1.0));
            }
            self.rate_targets(end, t, &z[col..col + n], col, &mut e);
        }
        e
    }

    /// Step `k`'s path inequalities and their Jacobian.
    fn evaluate_path(&self, k: usize, z: &[f64], e: &mut Evaluation) {
        let Some(path) = self.path_step(k) else {
            return;
        };
        let (b, rows) = (self.layout.block(), path.outputs());
        let (mut values, mut jac) = (vec![0.0; rows], vec![0.0; rows * b]);
        let (col, first) = (self.layout.q(k), self.path_rows(k));
        ad::jacobian(&path, &z[col..col + b], 0..b, &mut values, &mut jac);
        e.constraints[first..first + rows].copy_from_slice(&values);
        for (r, row) in jac.chunks_exact(b).enumerate() {
            let entries = row.iter().enumerate().filter(|e| *e.1 != 0.0);
            e.jacobian
                .extend(entries.map(|(j, &d)| (first + r, col + j, d)));
        }
    }

    /// Subtracts the target momenta of the fixed rate components (and their derivatives in `q`
    /// for velocities).
    fn rate_targets(&self, end: &End, t: f64, q: &[f64], col: usize, e: &mut Evaluation) {
        let n = self.layout.n;
        let first = end.row + end.q.len();
        match &end.velocity {
            None => {
                for (j, &(_, p)) in end.rate.iter().enumerate() {
                    e.constraints[first + j] -= p;
                }
            }
            Some(v) => {
                let momentum = BoundaryMomentum {
                    lagrangian: self.lagrangian,
                    t,
                    v: v.clone(),
                };
                let (mut p, mut dp) = (vec![0.0; n], vec![0.0; n * n]);
                ad::jacobian(&momentum, q, 0..n, &mut p, &mut dp);
                for i in 0..n {
                    e.constraints[first + i] -= p[i];
                    let row = dp[i * n..(i + 1) * n].iter().enumerate();
                    e.jacobian
                        .extend(row.map(|(j, &d)| (first + i, col + j, -d)));
                }
            }
        }
    }

    /// The upper triangle of the Hessian of `cost + λᵀ constraints` at `z`, as
    /// `(row, column, value)` with `row ≤ column`.
    pub fn hessian(&self, z: &[f64], lambda: &[f64]) -> Vec<(usize, usize, f64)> {
        let Layout { n, .. } = self.layout;
        let b = self.layout.block();
        let mut parts = HessianParts::default();
        let mut out = Vec::with_capacity(self.grid.steps * b * (b + 1) / 2);
        let mut weights = vec![0.0; 2 * n + 1 + self.layout.inner * n];
        for k in 0..self.grid.steps {
            for (i, w) in weights.iter_mut().enumerate() {
                *w = self
                    .output_row(k, i)
                    .map_or(0.0, |(row, sign)| sign * lambda[row]);
            }
            weights[2 * n] = 1.0;
            let step = self.step(k);
            let weighted = Weighted {
                f: &step,
                weights: &weights,
            };
            let col = self.layout.q(k);
            ad::partial_hessian(&weighted, &z[col..col + b], 0..b, 0..b, &mut parts);
            push_upper(&parts.hess, b, col, &mut out);
            if let Some(path) = self.path_step(k) {
                let first = self.path_rows(k);
                let weights = &lambda[first..first + path.outputs()];
                if weights.iter().any(|&w| w != 0.0) {
                    let weighted = Weighted { f: &path, weights };
                    ad::partial_hessian(&weighted, &z[col..col + b], 0..b, 0..b, &mut parts);
                    push_upper(&parts.hess, b, col, &mut out);
                }
            }
        }
        for (end, node, t) in self.ends() {
            let Some(v) = &end.velocity else { continue };
            let first = end.row + end.q.len();
            let w: Vec<f64> = (0..n).map(|i| -lambda[first + i]).collect();
            let momentum = BoundaryMomentum {
                lagrangian: self.lagrangian,
                t,
                v: v.clone(),
            };
            let weighted = Weighted {
                f: &momentum,
                weights: &w,
            };
            let col = self.layout.q(node);
            ad::partial_hessian(&weighted, &z[col..col + n], 0..n, 0..n, &mut parts);
            push_upper(&parts.hess, n, col, &mut out);
        }
        out
    }

    /// The DEL rows' multipliers (the discrete costates), node by node (`N − 1` nodes).
    pub fn costates(&self, lambda: &[f64]) -> Vec<Vec<f64>> {
        let n = self.layout.n;
        (1..self.grid.steps)
            .map(|k| lambda[self.del_row + (k - 1) * n..self.del_row + k * n].to_vec())
            .collect()
    }

    /// The multipliers of the start rows and of the end rows.
    pub fn boundary_multipliers(&self, lambda: &[f64]) -> (Vec<f64>, Vec<f64>) {
        (
            lambda[..self.del_row].to_vec(),
            lambda[self.end.row..self.inner_row].to_vec(),
        )
    }

    /// The path inequalities' rows of `rows` (their values or their multipliers), step by
    /// step (`σ n_g` per step).
    pub fn path_rows_by_step(&self, rows: &[f64]) -> Vec<Vec<f64>> {
        (0..self.grid.steps)
            .map(|k| rows[self.path_rows(k)..self.path_rows(k + 1)].to_vec())
            .collect()
    }
}

/// Appends the upper triangle of a dense `b × b` block placed at `(col, col)`.
fn push_upper(hess: &[f64], b: usize, col: usize, out: &mut Vec<(usize, usize, f64)>) {
    for r in 0..b {
        for c in r..b {
            let v = hess[r * b + c];
            if v != 0.0 {
                out.push((col + r, col + c, v));
            }
        }
    }
}
