//! DMOC solve times: the pendulum swing-up and the cart-pole swing-up, midpoint rule, from the
//! default guess (`q` linear between the rest states, `u = 0`) to the default tolerances
//! (KKT 1e-8, constraints 1e-10).
//!
//! * `swing_up_n100`: `L = θ̇²/2 + cos θ`, torque `u`, rest at `θ = 0` to rest at `θ = π`,
//!   `T = 6`, cost `∫ u²/2`, N = 100.
//! * `swing_up`: the same for N = 100 … 1600 (the growth of the solve time with N).
//! * `swing_up_gauss2`: the same with `gauss-2` (two controls per step at the Gauss nodes, one
//!   inner control point per step: 5 unknowns per step instead of 2), N = 50 and 100.
//! * `cart_pole`: the catalog's cart-pole (`PendulumOnCart`: `M = 1`, `m = 0.1`, `l = 0.5`,
//!   `g = 9.8`, the parameters of Barto, Sutton & Anderson 1983), force `u` on the cart,
//!   rest at `(x, θ) = (0, 0)` to rest at `(0, π)` in `T = 2`, cost `∫ u²/2`, for
//!   N = 50, 100, 200, 400 (the growth of the solve time with N; N = 200 is the headline).
//! * `bryson_denham_bound`, `bryson_denham_path`: `ẍ = u`, `∫ u²/2`, from `(0, 1)` to `(0, −1)`
//!   in `T = 1` with `x ≤ 1/9` as a bound on the nodes or as the path inequality `x − 1/9 ≤ 0`
//!   at the midpoints (the cost of the inequality rows against simple bounds).
//!
//! Run: `cargo bench -p marsden-control`.

use std::f64::consts::PI;

use marsden::discrete::rules::Galerkin;
use marsden::systems::{FreeFall, Pendulum, PendulumOnCart};
use marsden::{Midpoint, Rule, Scalar};
use marsden_control::{
    Boundary, Effort, Horizon, InputMap, OptimalControl, PathConstraint, SqpOptions, StagedControls,
};

fn main() {
    divan::main();
}

/// The swing-up's cost with `steps` steps and `rule` (NaN if it could not be set up).
fn swing_up_cost<R: Rule + StagedControls>(steps: usize, rule: &R) -> f64 {
    let problem = OptimalControl::new(
        Pendulum::default(),
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 6.0,
            steps,
        },
        Boundary::rest(&[0.0]),
        Boundary::rest(&[PI]),
    );
    let solution = problem.and_then(|p| p.solve(rule, &SqpOptions::default()));
    solution.map_or(f64::NAN, |s| s.cost)
}

#[divan::bench(sample_count = 10)]
fn swing_up_n100() -> f64 {
    divan::black_box(swing_up_cost(100, &Midpoint))
}

#[divan::bench(args = [100, 200, 400, 800, 1600], sample_count = 5)]
fn swing_up(steps: usize) -> f64 {
    divan::black_box(swing_up_cost(steps, &Midpoint))
}

#[divan::bench(args = [50, 100], sample_count = 5)]
fn swing_up_gauss2(steps: usize) -> f64 {
    let cost = Galerkin::gauss(2).map_or(f64::NAN, |gauss2| swing_up_cost(steps, &gauss2));
    divan::black_box(cost)
}

#[divan::bench(args = [50, 100, 200, 400], sample_count = 5)]
fn cart_pole(steps: usize) -> f64 {
    let problem = OptimalControl::new(
        PendulumOnCart::default(),
        InputMap::new(&[0]),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 2.0,
            steps,
        },
        Boundary::rest(&[0.0, 0.0]),
        Boundary::rest(&[0.0, PI]),
    );
    let solution = problem.and_then(|p| p.solve(&Midpoint, &SqpOptions::default()));
    divan::black_box(solution.map_or(f64::NAN, |s| s.cost))
}

/// `x − 1/9 ≤ 0`.
struct Ceiling;

impl PathConstraint for Ceiling {
    fn count(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, _t: S, q: &[S], _v: &[S], _u: &[S], out: &mut [S]) {
        out[0] = q[0] - 1.0 / 9.0;
    }
}

/// The Bryson–Denham problem without its state constraint.
fn bryson_denham(
    steps: usize,
) -> Result<OptimalControl<FreeFall, InputMap, Effort>, marsden_control::ControlError> {
    OptimalControl::new(
        FreeFall { m: 1.0, g: 0.0 },
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 1.0,
            steps,
        },
        Boundary::velocity(&[0.0], &[1.0]),
        Boundary::velocity(&[0.0], &[-1.0]),
    )
}

#[divan::bench(args = [50, 100, 200, 400], sample_count = 5)]
fn bryson_denham_bound(steps: usize) -> f64 {
    let problem =
        bryson_denham(steps).and_then(|p| p.with_state_bounds(&[f64::NEG_INFINITY], &[1.0 / 9.0]));
    let solution = problem.and_then(|p| p.solve(&Midpoint, &SqpOptions::default()));
    divan::black_box(solution.map_or(f64::NAN, |s| s.cost))
}

#[divan::bench(args = [50, 100, 200, 400], sample_count = 5)]
fn bryson_denham_path(steps: usize) -> f64 {
    let problem = bryson_denham(steps).map(|p| p.with_path(Ceiling));
    let solution = problem.and_then(|p| p.solve(&Midpoint, &SqpOptions::default()));
    divan::black_box(solution.map_or(f64::NAN, |s| s.cost))
}
