//! A short SQP iteration ([NW06] ch. 18) around the Clarabel subproblem ([`crate::qp`]).
//!
//! * Hessian: the exact Hessian of the Lagrangian `f + λᵀc` from automatic differentiation,
//!   plus `δI`. Each iteration tries `δ = 0` first (with `P = H`, then `H + ρJᵀJ` for a few `ρ`:
//!   the same step, [`crate::qp`]), then (as IPOPT does) a third of the last
//!   nonzero `δ`, growing eightfold, until Clarabel solves the subproblem and the step has
//!   positive curvature `dᵀ(H + δI)d ≥ κ dᵀd`. Near a strict local minimum `δ = 0`
//!   passes, so the steps are Newton steps on the KKT conditions (fast local convergence).
//! * Globalisation: the ℓ1 merit `φ = f + μ(‖c_E‖₁ + ‖max(0, c_I)‖₁)` with `μ ≥ ‖λ‖∞ + ρ`, Armijo backtracking,
//!   and one second-order correction when the full step is refused (against the Maratos
//!   effect, [NW06] §15.6).
//! * Inconsistent linearisations: when a subproblem has no solution (a checked certificate),
//!   the iteration continues in elastic mode ([`crate::qp::Subproblem::solve_elastic`]), each
//!   step minimising the linearised violation plus the cost; it stops as infeasible, naming
//!   the bounds of the first certificate, once a step cannot reduce the violation (a local
//!   minimum of it: for dynamics linear in `(q, u)`, a proof).
//! * Stopping: at iterate `z` with the subproblem's multipliers, the KKT residual
//!   `max(‖g + Jᵀλ + ∂bounds‖∞, max |μ_i slack_i|, max |λ_i g_i|)` and the violation
//!   (`|c_i|` of an equality, `max(0, g_i)` of a path inequality) below their tolerances.
//!   Bounds are linear, so every iterate keeps them; path inequalities are met at the limit.
//!
//! [NW06]: crate#references

use marsden::numerics::dense::max_or_nan;

use crate::qp::{Certificate, Convexify, QpOutcome, QpSolution, Subproblem};
use crate::solution::{Failure, Infeasibility, Iteration, Status};
use crate::transcription::Evaluation;

/// What the SQP iteration needs of a program.
pub trait Program {
    /// Values and first derivatives at `z`.
    fn evaluate(&self, z: &[f64]) -> Evaluation;
    /// The upper triangle of the Hessian of `f + λᵀc`.
    fn hessian(&self, z: &[f64], lambda: &[f64]) -> Vec<(usize, usize, f64)>;
    /// Number of constraints.
    fn rows(&self) -> usize;
}

/// Options of the SQP iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SqpOptions {
    /// Tolerance on the KKT residual (default 1e-8).
    pub kkt_tolerance: f64,
    /// Tolerance on `max |c_i|` (default 1e-10).
    pub constraint_tolerance: f64,
    /// Iteration budget (default 200).
    pub max_iterations: usize,
}

impl Default for SqpOptions {
    fn default() -> Self {
        Self {
            kkt_tolerance: 1e-8,
            constraint_tolerance: 1e-10,
            max_iterations: 200,
        }
    }
}

/// The end of an SQP iteration: status, last iterate and its multipliers.
pub struct SqpOutcome {
    /// How it ended.
    pub status: Status,
    /// The last iterate.
    pub z: Vec<f64>,
    /// The multipliers of the constraints at it.
    pub lambda: Vec<f64>,
    /// The program's values there.
    pub evaluation: Evaluation,
    /// KKT residual there.
    pub kkt: f64,
    /// One record per iteration.
    pub history: Vec<Iteration>,
    /// The checked certificate of an infeasible subproblem (status `Infeasible`).
    pub certificate: Option<Certificate>,
}

/// Simple bounds on the unknowns, `lower ≤ z ≤ upper` (infinite: none).
pub struct VariableBounds {
    /// Lower bounds.
    pub lower: Vec<f64>,
    /// Upper bounds.
    pub upper: Vec<f64>,
}

const ARMIJO: f64 = 1e-4;
const MIN_STEP: f64 = 1e-12;
const CURVATURE: f64 = 1e-10;
const MAX_DELTA: f64 = 1e12;

/// The state of the iteration: the iterate, its multipliers and values, the record so far.
struct Iterate {
    z: Vec<f64>,
    lambda: Vec<f64>,
    e: Evaluation,
    kkt: f64,
    history: Vec<Iteration>,
}

impl Iterate {
    fn finish(self, status: Status) -> SqpOutcome {
        self.finish_with(status, None)
    }

    /// Stops at a point whose linearised constraints cannot be met and whose violation the
    /// elastic steps could not reduce: infeasible, located by the first certificate.
    fn infeasible(self, elastic: &Elastic) -> SqpOutcome {
        let status = Status::Infeasible(Infeasibility {
            iteration: elastic.iteration,
            elastic_steps: elastic.steps,
            ..Infeasibility::default()
        });
        self.finish_with(status, Some(elastic.certificate.clone()))
    }

    fn finish_with(self, status: Status, certificate: Option<Certificate>) -> SqpOutcome {
        SqpOutcome {
            certificate,
            status,
            z: self.z,
            lambda: self.lambda,
            evaluation: self.e,
            kkt: self.kkt,
            history: self.history,
        }
    }
}

/// Runs SQP from `z` (projected into the bounds first).
pub fn solve<P: Program>(
    program: &P,
    mut z: Vec<f64>,
    bounds: &VariableBounds,
    options: &SqpOptions,
) -> SqpOutcome {
    for (zi, (&lo, &hi)) in z.iter_mut().zip(bounds.lower.iter().zip(&bounds.upper)) {
        *zi = zi.clamp(lo, hi);
    }
    let mut it = Iterate {
        e: program.evaluate(&z),
        z,
        lambda: vec![0.0; program.rows()],
        kkt: f64::INFINITY,
        history: Vec::new(),
    };
    let mut memory = Memory::default();
    // Since the first subproblem without a solution (elastic mode).
    let mut elastic: Option<Elastic> = None;
    for _ in 0..options.max_iterations {
        let hessian = program.hessian(&it.z, &it.lambda);
        if !it.e.is_finite() || hessian.iter().any(|h| !h.2.is_finite()) {
            return it.finish(Status::Failed(Failure::NonFinite));
        }
        let (upper, lower) = step_bounds(&it.z, bounds);
        let rhs: Vec<f64> = it.e.constraints.iter().map(|c| -c).collect();
        let sub = Subproblem {
            hessian: &hessian,
            gradient: &it.e.gradient,
            jacobian: &it.e.jacobian,
            rows: program.rows(),
            inequalities: it.e.inequalities,
            rhs: &rhs,
            upper: &upper,
            lower: &lower,
        };
        let (qp, shape) = match regularised_step(&sub, &mut memory) {
            Ok(step) => step,
            Err(Stop::Infeasible(certificate)) => {
                let first = elastic.get_or_insert(Elastic {
                    iteration: it.history.len(),
                    certificate,
                    steps: 0,
                });
                match elastic_step(&sub, &mut memory.delta, &it) {
                    Some(step) => step,
                    None => return it.infeasible(first),
                }
            }
            // In elastic mode a subproblem the solver cannot solve (nor prove infeasible) is
            // stepped over elastically as well.
            Err(Stop::Failed(failure)) => match elastic.as_mut() {
                None => return it.finish(Status::Failed(failure)),
                Some(first) => match elastic_step(&sub, &mut memory.delta, &it) {
                    Some(step) => step,
                    None => return it.infeasible(first),
                },
            },
        };
        it.lambda.clone_from(&qp.lambda);
        it.kkt = kkt_residual(&it.e, &qp, (&upper, &lower));
        let violation = it.e.max_violation();
        let mut record = Iteration {
            cost: it.e.cost,
            violation,
            kkt: it.kkt,
            step: 0.0,
            regularization: shape.delta,
        };
        if it.kkt <= options.kkt_tolerance && violation <= options.constraint_tolerance {
            it.history.push(record);
            return it.finish(Status::Converged);
        }
        let mu = penalty(&it.e, &qp, &hessian, shape.delta);
        let accepted = line_search(program, &it.z, &it.e, &qp.step, &sub, shape, mu);
        match accepted {
            Ok((step, z, e)) => {
                if let (Some(first), true) = (elastic.as_mut(), qp.elastic) {
                    first.steps += 1;
                }
                record.step = step;
                it.history.push(record);
                (it.z, it.e) = (z, e);
            }
            Err(step) => {
                it.history.push(record);
                // No decrease of the merit from an iterate whose linearisation had no solution:
                // the violation could not be reduced further.
                if let (Some(first), true) = (&elastic, qp.elastic) {
                    return it.infeasible(first);
                }
                return it.finish(Status::Failed(Failure::LineSearch { step }));
            }
        }
    }
    it.finish(Status::IterationLimit)
}

/// Why no step was found.
enum Stop {
    /// The subproblem's constraints are inconsistent (a checked certificate).
    Infeasible(Certificate),
    /// Anything else.
    Failed(Failure),
}

/// How the last iteration's subproblem was solved ([`regularised_step`] tries it first).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
enum Worked {
    /// With `P = H` (or nothing solved yet).
    #[default]
    Plain,
    /// With `P = H + ρJᵀJ`, this `ρ`.
    Convexified(f64),
    /// With `P = H + δI`, `δ > 0`.
    Regularised,
}

/// What the last iterations' subproblems needed.
#[derive(Debug, Clone, Copy, Default)]
struct Memory {
    /// The last nonzero regularisation `δ` (0: none needed yet).
    delta: f64,
    /// How the last subproblem was solved.
    worked: Worked,
}

/// The subproblem's step, tried in this order, each accepted if solved with positive
/// curvature:
///
/// 1. what solved the last iteration's subproblem, if it was `P = H + ρJᵀJ`;
/// 2. the Newton step with `P = H`;
/// 3. the Newton step with `P = H + ρJᵀJ`, `ρ = 10⁴ ‖H‖_max / ‖J‖²_max`, unless the last
///    iteration needed `δ` ([`crate::qp`]: the same step, a convex `P` when `H` is positive
///    definite on the null space of `J` — the inner control points of Gauss and Lobatto steps
///    have no curvature of their own; the scale keeps `ρJᵀJ` within a few orders of `H`);
/// 4. `P = H + δI` with `δ` a third of the last nonzero one (at least 1e-6), growing eightfold
///    up to `MAX_DELTA` — no longer a Newton step.
///
/// An interior-point solver on an indefinite `P` takes up to its iteration budget before it
/// gives up, so what worked is tried first (BENCHMARKS.md has the solve times). A checked
/// infeasibility certificate stops the search at once: feasibility does not depend on the
/// Hessian, and a larger `δ` only degrades the solver's scaling until it can no longer tell.
fn regularised_step(
    sub: &Subproblem<'_>,
    memory: &mut Memory,
) -> Result<(QpSolution, Convexify), Stop> {
    let largest = |m: &[(usize, usize, f64)]| m.iter().fold(0.0, |a, e| max_or_nan(a, e.2.abs()));
    let (h, j) = (largest(sub.hessian), largest(sub.jacobian));
    let rho = if h > 0.0 && j > 0.0 {
        1e4 * h / (j * j)
    } else {
        1.0
    };
    let mut shapes = Vec::with_capacity(3);
    if let Worked::Convexified(last) = memory.worked {
        shapes.push((
            Convexify {
                delta: 0.0,
                rho: last,
            },
            memory.worked,
        ));
    }
    shapes.push((Convexify::default(), Worked::Plain));
    if memory.worked != Worked::Regularised {
        shapes.push((Convexify { delta: 0.0, rho }, Worked::Convexified(rho)));
    }
    for (shape, worked) in shapes {
        match sub.solve_with(shape) {
            QpOutcome::Solved(s) if curvature_ok(sub.hessian, 0.0, &s.step) => {
                memory.worked = worked;
                return Ok((s, shape));
            }
            QpOutcome::Infeasible(certificate) => return Err(Stop::Infeasible(certificate)),
            _ => {}
        }
    }
    let mut delta = 0.0;
    loop {
        delta = next_delta(delta, memory.delta);
        memory.delta = delta;
        let outcome = sub.solve(delta);
        match &outcome {
            QpOutcome::Solved(s) if curvature_ok(sub.hessian, delta, &s.step) => {
                memory.worked = Worked::Regularised;
                return Ok((s.clone(), Convexify { delta, rho: 0.0 }));
            }
            QpOutcome::Infeasible(certificate) => {
                return Err(Stop::Infeasible(certificate.clone()));
            }
            _ if delta < MAX_DELTA => continue,
            _ => {}
        }
        let status = match outcome {
            QpOutcome::Failed(status) => status,
            _ => "negative curvature".to_string(),
        };
        return Err(Stop::Failed(Failure::Subproblem {
            status,
            regularization: delta,
        }));
    }
}

/// The regularisation after `delta` failed: from 0, a third of the last nonzero one `last` (at
/// least 1e-6, as IPOPT does); else eightfold.
fn next_delta(delta: f64, last: f64) -> f64 {
    match (delta, last) {
        (0.0, 0.0) => 1e-6,
        (0.0, last) => (last / 3.0).max(1e-6),
        (d, _) => 8.0 * d,
    }
}

/// Where elastic mode began, and how many elastic steps it has taken.
struct Elastic {
    /// The iteration of the first subproblem without a solution.
    iteration: usize,
    /// Its checked certificate (which bounds it uses).
    certificate: Certificate,
    /// Elastic steps taken.
    steps: usize,
}

/// The elastic subproblem's step ([`Subproblem::solve_elastic`]) with the regularisation of
/// [`regularised_step`], if it reduces the linearised ℓ1 violation by at least 0.1 %: else the
/// iterate is a stationary point of the violation (locally infeasible), `None`.
///
/// The price of the slacks, `10³ max(1, ‖g‖∞, ‖λ‖∞)`, exceeds the multipliers the problem has
/// near a feasible point, so that the ℓ1 merit's minimisers are its KKT points ([NW06] §17.2).
fn elastic_step(
    sub: &Subproblem<'_>,
    last_delta: &mut f64,
    it: &Iterate,
) -> Option<(QpSolution, Convexify)> {
    let mu = 1e3 * max_abs(&it.e.gradient).max(max_abs(&it.lambda)).max(1.0);
    let violation = it.e.l1_violation();
    let mut delta = 0.0;
    loop {
        if let QpOutcome::Solved(s) = sub.solve_elastic(delta, mu)
            && curvature_ok(sub.hessian, delta, &s.step)
        {
            let reduces = s.elastic_violation < 0.999 * violation;
            return reduces.then_some((s, Convexify { delta, rho: 0.0 }));
        }
        if delta >= MAX_DELTA {
            return None;
        }
        delta = next_delta(delta, *last_delta);
        *last_delta = delta;
    }
}

/// The ℓ1 penalty of this iteration: at least `‖λ‖∞` (exactness of the merit at a KKT point)
/// and at least `(gᵀd + ½dᵀ(H + δI)d) / ((1 − ρ)‖c‖₁)` with `ρ = ½` ([NW06] (18.36)), so that
/// `d` descends the merit. Not kept monotone: a large penalty from a first step far from the
/// solution would otherwise hold the later steps short.
fn penalty(e: &Evaluation, qp: &QpSolution, hessian: &[(usize, usize, f64)], delta: f64) -> f64 {
    let d = &qp.step;
    let c1 = e.l1_violation();
    let by_multipliers = 1.1 * max_abs(&qp.lambda) + 1e-8;
    if c1 == 0.0 {
        return by_multipliers;
    }
    let quadratic = 0.5 * (quadratic_form(hessian, d) + delta * dot(d, d));
    by_multipliers.max((dot(&e.gradient, d) + quadratic) / (0.5 * c1))
}

/// `dᵀHd` with `H` given by its upper triangle.
fn quadratic_form(hessian: &[(usize, usize, f64)], d: &[f64]) -> f64 {
    hessian
        .iter()
        .map(|&(r, c, v)| {
            if r == c {
                v * d[r] * d[r]
            } else {
                2.0 * v * d[r] * d[c]
            }
        })
        .sum()
}

/// The bounds of the step `d` at `z`: `d_i ≤ hi_i − z_i`, `d_i ≥ lo_i − z_i` (finite ones).
fn step_bounds(z: &[f64], bounds: &VariableBounds) -> (Vec<Bound>, Vec<Bound>) {
    let upper = (0..z.len())
        .filter(|&i| bounds.upper[i].is_finite())
        .map(|i| (i, bounds.upper[i] - z[i]))
        .collect();
    let lower = (0..z.len())
        .filter(|&i| bounds.lower[i].is_finite())
        .map(|i| (i, bounds.lower[i] - z[i]))
        .collect();
    (upper, lower)
}

/// `dᵀ(H + δI)d ≥ κ dᵀd`, with `H` given by its upper triangle.
fn curvature_ok(hessian: &[(usize, usize, f64)], delta: f64, d: &[f64]) -> bool {
    let dd: f64 = d.iter().map(|x| x * x).sum();
    let dhd: f64 = hessian
        .iter()
        .map(|&(r, c, v)| {
            if r == c {
                v * d[r] * d[r]
            } else {
                2.0 * v * d[r] * d[c]
            }
        })
        .sum();
    dhd + delta * dd >= CURVATURE * dd
}

/// `max(‖g + Jᵀλ + Σ μ⁺e_i − Σ μ⁻e_i‖∞, max |μ_i · slack_i|, max |λ_i c_i|)` at the
/// iterate, the last over the inequality rows (their multipliers are `≥ 0` by the subproblem).
fn kkt_residual(e: &Evaluation, qp: &QpSolution, (upper, lower): BoundsRef<'_>) -> f64 {
    let mut r = e.gradient.clone();
    for &(row, col, v) in &e.jacobian {
        r[col] += v * qp.lambda[row];
    }
    let equalities = e.equalities();
    let mut complementarity = (e.constraints[equalities..].iter())
        .zip(&qp.lambda[equalities..])
        .fold(0.0, |m, (c, l)| max_or_nan(m, (c * l).abs()));
    for (&(i, slack), &m) in upper.iter().zip(&qp.upper) {
        r[i] += m;
        complementarity = max_or_nan(complementarity, (m * slack).abs());
    }
    for (&(i, slack), &m) in lower.iter().zip(&qp.lower) {
        r[i] -= m;
        complementarity = max_or_nan(complementarity, (m * slack).abs());
    }
    max_abs(&r).max(complementarity)
}

/// `(variable, bound on the step)`.
type Bound = (usize, f64);

type BoundsRef<'a> = (&'a [Bound], &'a [Bound]);

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| max_or_nan(m, x.abs()))
}

/// Armijo backtracking on `φ = f + μ‖c‖₁` along `d`, with one second-order correction when
/// the full step is refused (its subproblem made convex as the step's was). `Ok((α, z⁺, e⁺))`,
/// or `Err(α)` with the last step tried.
fn line_search<P: Program>(
    program: &P,
    z: &[f64],
    e: &Evaluation,
    d: &[f64],
    sub: &Subproblem<'_>,
    shape: Convexify,
    mu: f64,
) -> Result<(f64, Vec<f64>, Evaluation), f64> {
    let merit = |e: &Evaluation| e.cost + mu * e.l1_violation();
    let phi0 = merit(e);
    let slope = dot(&e.gradient, d) - mu * e.l1_violation();
    let slope = slope.min(0.0);
    let at = |alpha: f64, d: &[f64]| -> Vec<f64> {
        z.iter().zip(d).map(|(zi, di)| zi + alpha * di).collect()
    };
    let trial = at(1.0, d);
    let e_trial = program.evaluate(&trial);
    if e_trial.is_finite() && merit(&e_trial) <= phi0 + ARMIJO * slope {
        return Ok((1.0, trial, e_trial));
    }
    // Second-order correction: J d̂ = J d − c(z + d), same Hessian and bounds.
    if e_trial.is_finite() {
        let mut rhs = vec![0.0; sub.rows];
        for &(row, col, v) in sub.jacobian {
            rhs[row] += v * d[col];
        }
        rhs.iter_mut()
            .zip(&e_trial.constraints)
            .for_each(|(r, c)| *r -= c);
        let corrected = Subproblem { rhs: &rhs, ..*sub };
        if let QpOutcome::Solved(s) = corrected.solve_with(shape) {
            let trial = at(1.0, &s.step);
            let e_soc = program.evaluate(&trial);
            if e_soc.is_finite() && merit(&e_soc) <= phi0 + ARMIJO * slope {
                return Ok((1.0, trial, e_soc));
            }
        }
    }
    let mut alpha = 0.5;
    while alpha >= MIN_STEP {
        let trial = at(alpha, d);
        let e_trial = program.evaluate(&trial);
        if e_trial.is_finite() && merit(&e_trial) <= phi0 + ARMIJO * alpha * slope {
            return Ok((alpha, trial, e_trial));
        }
        alpha *= 0.5;
    }
    Err(alpha)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
