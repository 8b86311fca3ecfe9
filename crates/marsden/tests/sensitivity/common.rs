//! Helpers of the sensitivity tests: whole runs, central differences, relative distances.

use crate::common::tight;
use marsden::sensitivity::{SensitiveStep, TangentOptions, tangent};
use marsden::{DiscreteAction, Integrator, State, TimeGrid};

pub fn state(q: &[f64], p: &[f64]) -> State {
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

/// A tightly converged integrator of `action`.
pub fn integrator<A: DiscreteAction>(action: A) -> Integrator<A> {
    Integrator::new(action).with_options(tight()).unwrap()
}

/// The final `(q, p)` of a plain run of a fresh stepper from `make()`.
pub fn final_state<D: SensitiveStep>(
    make: &impl Fn() -> D,
    start: &State,
    grid: &TimeGrid,
) -> Vec<f64> {
    run_to_end(make(), start, grid)
}

/// The final `(q, p)` of a plain run of `stepper` from `start` over `grid`.
pub fn run_to_end<D: SensitiveStep>(mut stepper: D, start: &State, grid: &TimeGrid) -> Vec<f64> {
    let mut s = start.clone();
    for k in 0..grid.steps {
        stepper.step(&mut s, grid.h).unwrap();
        s.t = grid.time(k + 1);
    }
    s.q.iter().chain(&s.p).copied().collect()
}

/// The tangent run's final Jacobian (row-major 2n × columns).
pub fn tangent_jacobian<D: SensitiveStep>(
    make: &impl Fn() -> D,
    start: &State,
    grid: &TimeGrid,
) -> Vec<f64> {
    tangent(&mut make(), start.clone(), grid, &TangentOptions::default())
        .unwrap()
        .jacobian
}

/// Central differences `(x_K(x₀ + εe_c) − x_K(x₀ − εe_c))/2ε` of whole runs for the 2n state
/// columns, row-major 2n × 2n.
pub fn central_differences<D: SensitiveStep>(
    make: &impl Fn() -> D,
    start: &State,
    grid: &TimeGrid,
    eps: f64,
) -> Vec<f64> {
    let n = start.q.len();
    let m = 2 * n;
    let mut fd = vec![0.0; m * m];
    for c in 0..m {
        let shifted = |sign: f64| {
            let mut s = start.clone();
            if c < n {
                s.q[c] += sign * eps;
            } else {
                s.p[c - n] += sign * eps;
            }
            final_state(make, &s, grid)
        };
        let (plus, minus) = (shifted(1.0), shifted(-1.0));
        for r in 0..m {
            fd[r * m + c] = (plus[r] - minus[r]) / (2.0 * eps);
        }
    }
    fd
}

/// `max |a − b| / max |b|`.
pub fn relative_distance(a: &[f64], b: &[f64]) -> f64 {
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let scale = b.iter().map(|y| y.abs()).fold(0.0, f64::max);
    diff / scale
}
