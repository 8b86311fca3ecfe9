//! Empirical order of convergence: run a method at several step sizes, compare with a
//! reference, fit the log–log slope.
//!
//! The global error of a method of order `p` behaves as `e(h) ≈ C hᵖ` until round-off takes
//! over (HLW06 §II.1; reference cases R5, R6). [`empirical_order`] fits `log e` against `log h`
//! by least squares over the points before round-off: starting from the largest `h`, points are
//! kept while the error is above a floor and still decreasing; the first point that breaks
//! either condition and all smaller `h` are dropped. [`measure_order`] runs a [`Problem`] with a
//! rule at each `h` and measures `|(q_N, p_N) − (q(T), p(T))|` (Euclidean), against a reference
//! from a closed form or from [`reference_solution`] (the extrapolation integrator of
//! [`crate::discrete::exact::flow`], converged to round-off). For constrained problems (the
//! flow has no constraints) [`constrained_reference`] runs constrained Lobatto IIIA–IIIB of
//! order 8 at small steps and says how far it is from converged.

use crate::discrete::exact::{EulerLagrangeFlow, FlowOptions};
use crate::discrete::rules::Rule;
use crate::error::Error;
use crate::mechanics::{Constraint, Force, Lagrangian};
use crate::numerics::newton::NewtonOptions;
use crate::run::{Problem, SolveOptions};
use crate::run::{RunOptions, TimeGrid};

/// One run of an order study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderPoint {
    /// Step size.
    pub h: f64,
    /// Number of steps.
    pub steps: usize,
    /// Error at the final time (`NaN` if the run failed).
    pub error: f64,
}

/// The result of an order study of one method.
#[derive(Debug, Clone, PartialEq)]
pub struct OrderStudy {
    /// The method's name.
    pub method: String,
    /// The order the method claims.
    pub expected: u32,
    /// The runs, largest `h` first.
    pub points: Vec<OrderPoint>,
    /// Slope between consecutive points (`log(e₁/e₂)/log(h₁/h₂)`), one fewer than the points.
    pub pairwise: Vec<f64>,
    /// Least-squares slope over the points kept (`None` if fewer than two were kept).
    pub order: Option<f64>,
    /// Number of leading points kept by the round-off filter.
    pub kept: usize,
}

/// Options of an order study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderOptions {
    /// Newton options of the runs (default: residual tolerance 1e-15, i.e. to round-off).
    pub newton: NewtonOptions,
    /// Errors below `round_off · max(1, |reference|)` are round-off and dropped (default
    /// 1e-12).
    pub round_off: f64,
}

impl Default for OrderOptions {
    fn default() -> Self {
        Self {
            newton: NewtonOptions {
                residual_tolerance: 1e-15,
                ..NewtonOptions::default()
            },
            round_off: 1e-12,
        }
    }
}

/// Least-squares log–log slope over the leading points before round-off: kept while
/// `error > floor` and decreasing (points sorted by decreasing `h`). Returns the slope (if at
/// least two points were kept) and the number kept.
pub fn empirical_order(hs: &[f64], errors: &[f64], floor: f64) -> (Option<f64>, usize) {
    let mut kept = 0;
    for (k, e) in errors.iter().enumerate() {
        let decreasing = k == 0 || *e < errors[k - 1];
        if !(e.is_finite() && *e > floor && decreasing) {
            break;
        }
        kept = k + 1;
    }
    if kept < 2 {
        return (None, kept);
    }
    let x: Vec<f64> = hs[..kept].iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = errors[..kept].iter().map(|e| e.ln()).collect();
    (
        Some(crate::analysis::diagnostics::least_squares_slope(&x, &y)),
        kept,
    )
}

/// The exact solution at `t_end` from the problem's start, by the Euler–Lagrange flow with
/// forces (converged to round-off; not for constrained problems): `(q(T), p(T))`.
pub fn reference_solution<L: Lagrangian, F: Force, C: Constraint>(
    problem: &Problem<L, F, C>,
    t_end: f64,
) -> Result<(Vec<f64>, Vec<f64>), Error> {
    let start = problem.start();
    let flow = EulerLagrangeFlow::new(problem.lagrangian())
        .with_force(problem.force())
        .with_options(FlowOptions::default())?;
    let end = flow.advance(
        start.t,
        t_end - start.t,
        &start.q,
        problem.initial_velocity(),
    )?;
    let mut p = vec![0.0; end.q.len()];
    crate::mechanics::momentum(problem.lagrangian(), t_end, &end.q, &end.v, &mut p);
    Ok((end.q, p))
}

/// The exact solution at `t_end` computed twice — over the whole interval at once (the adaptive
/// flow picks its own substeps), and in [`REFERENCE_PIECES`] consecutive pieces (other substeps,
/// other round-off) — with their difference as its accuracy estimate: a reference that diverged
/// or lost its accuracy shows as a large difference instead of passing for the exact solution.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidatedReference {
    /// `q(T)` (the whole-interval computation).
    pub q: Vec<f64>,
    /// `p(T)`.
    pub p: Vec<f64>,
    /// `max |(q, p)_whole − (q, p)_pieces|`, NaN if either is not finite.
    pub difference: f64,
}

/// The pieces of the second computation of [`validated_reference`].
pub const REFERENCE_PIECES: usize = 8;

/// [`reference_solution`] validated against a second computation in [`REFERENCE_PIECES`]
/// pieces (see [`ValidatedReference`]).
///
/// # Errors
/// The flow's errors, from either computation.
pub fn validated_reference<L: Lagrangian, F: Force, C: Constraint>(
    problem: &Problem<L, F, C>,
    t_end: f64,
) -> Result<ValidatedReference, Error> {
    let (q, p) = reference_solution(problem, t_end)?;
    let start = problem.start();
    let flow = EulerLagrangeFlow::new(problem.lagrangian())
        .with_force(problem.force())
        .with_options(FlowOptions::default())?;
    let (mut t, mut y, mut v) = (
        start.t,
        start.q.clone(),
        problem.initial_velocity().to_vec(),
    );
    let piece = (t_end - start.t) / REFERENCE_PIECES as f64;
    for k in 0..REFERENCE_PIECES {
        let next = match k + 1 == REFERENCE_PIECES {
            true => t_end,
            false => start.t + piece * (k + 1) as f64,
        };
        let end = flow.advance(t, next - t, &y, &v)?;
        (t, y, v) = (next, end.q, end.v);
    }
    let mut p_pieces = vec![0.0; y.len()];
    crate::mechanics::momentum(problem.lagrangian(), t_end, &y, &v, &mut p_pieces);
    let difference = q
        .iter()
        .zip(&y)
        .chain(p.iter().zip(&p_pieces))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, crate::numerics::dense::max_or_nan);
    Ok(ValidatedReference { q, p, difference })
}

/// A reference of a constrained problem computed by a constrained method of high order.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstrainedReference {
    /// `q(T)` (from the finer run).
    pub q: Vec<f64>,
    /// `p(T)`.
    pub p: Vec<f64>,
    /// The steps of the finer run.
    pub steps: usize,
    /// `|(q, p)_N − (q, p)_{2N}|`: the coarser run's error to leading order; the finer run's
    /// is about `2⁻⁸` of it.
    pub difference: f64,
}

/// The method of [`constrained_reference`]: `lobatto-5`, constrained Lobatto IIIA–IIIB of order
/// 8 ([`crate::discrete::DiscreteAction::constrained_stages`]).
pub const CONSTRAINED_REFERENCE_METHOD: &str = "lobatto-5";

/// `(q(T), p(T))` of a constrained problem by `lobatto-5` with `steps` and `2·steps` steps
/// (the finer run is the reference, their difference its accuracy estimate). Validated against
/// the exact solution of the Cartesian pendulum (R7, `tests/constraints`).
///
/// # Errors
/// An invalid grid, or the first failed run's error.
pub fn constrained_reference<L: Lagrangian, F: Force, C: Constraint>(
    problem: &Problem<L, F, C>,
    t_end: f64,
    steps: usize,
    newton: NewtonOptions,
) -> Result<ConstrainedReference, Error>
where
    Problem<L, F, C>: Clone,
{
    let rule = crate::discrete::rules::Galerkin::lobatto(5)?;
    let t0 = problem.start().t;
    let solve = SolveOptions {
        newton,
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    };
    let mut ends = Vec::with_capacity(2);
    for n in [steps.max(1), 2 * steps.max(1)] {
        let grid = TimeGrid::new(t0, (t_end - t0) / n as f64, n)?;
        let run = problem
            .clone()
            .with_grid(grid)?
            .solve(&rule, &solve)
            .map_err(|failure| failure.error)?;
        let last = run.len() - 1;
        ends.push((run.q(last).to_vec(), run.p(last).to_vec()));
    }
    let (coarse, fine) = (&ends[0], &ends[1]);
    let difference = distance(&coarse.0, &coarse.1, &fine.0, &fine.1);
    let (q, p) = ends.swap_remove(1);
    Ok(ConstrainedReference {
        q,
        p,
        steps: 2 * steps.max(1),
        difference,
    })
}

/// Runs `problem` with `rule` over `[t₀, t_end]` with each number of `steps` (increasing) and
/// fits the order against the reference `(reference_q, reference_p) = (q(T), p(T))`.
///
/// # Errors
/// Only for an invalid grid; a failed run is a point with error `NaN` (which ends the fit).
pub fn measure_order<L: Lagrangian, F: Force, C: Constraint, R: Rule>(
    problem: &Problem<L, F, C>,
    rule: &R,
    t_end: f64,
    steps: &[usize],
    reference_q: &[f64],
    reference_p: &[f64],
    options: &OrderOptions,
) -> Result<OrderStudy, Error>
where
    Problem<L, F, C>: Clone,
{
    let t0 = problem.start().t;
    let solve = SolveOptions {
        newton: options.newton,
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    };
    let mut points = Vec::with_capacity(steps.len());
    for &n in steps {
        let h = (t_end - t0) / n as f64;
        let run = problem
            .clone()
            .with_grid(TimeGrid::new(t0, h, n)?)?
            .solve(rule, &solve);
        let error = match run {
            Ok(traj) if !traj.is_empty() => {
                let last = traj.len() - 1;
                distance(traj.q(last), traj.p(last), reference_q, reference_p)
            }
            _ => f64::NAN,
        };
        points.push(OrderPoint { h, steps: n, error });
    }
    Ok(study(
        rule.name(),
        rule.order(),
        points,
        reference_q,
        reference_p,
        options,
    ))
}

fn study(
    method: String,
    expected: u32,
    points: Vec<OrderPoint>,
    q: &[f64],
    p: &[f64],
    options: &OrderOptions,
) -> OrderStudy {
    let hs: Vec<f64> = points.iter().map(|pt| pt.h).collect();
    let errors: Vec<f64> = points.iter().map(|pt| pt.error).collect();
    let size = crate::numerics::dense::max_norm(q)
        .max(crate::numerics::dense::max_norm(p))
        .max(1.0);
    let (order, kept) = empirical_order(&hs, &errors, options.round_off * size);
    let pairwise = points
        .windows(2)
        .map(|w| (w[0].error / w[1].error).ln() / (w[0].h / w[1].h).ln())
        .collect();
    OrderStudy {
        method,
        expected,
        points,
        pairwise,
        order,
        kept,
    }
}

/// Euclidean distance of `(q, p)` from the reference.
fn distance(q: &[f64], p: &[f64], qr: &[f64], pr: &[f64]) -> f64 {
    q.iter()
        .zip(qr)
        .chain(p.iter().zip(pr))
        .map(|(a, b)| (a - b) * (a - b))
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_off_points_are_dropped() {
        let hs = [0.4, 0.2, 0.1, 0.05, 0.025];
        let errors = [1.6e-4, 1e-5, 6.25e-7, 1e-13, 3e-13];
        let (order, kept) = empirical_order(&hs, &errors, 1e-12);
        assert_eq!(kept, 3);
        assert!((order.unwrap() - 4.0).abs() < 1e-12);
        let (order, kept) = empirical_order(&hs[..1], &errors[..1], 1e-12);
        assert_eq!((order, kept), (None, 1));
    }
}
