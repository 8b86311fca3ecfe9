//! The double integrator with a closed-form optimum.
//!
//! `L = ½q̇²`, force `u`, cost `∫₀¹ ½u² dt`, rest to rest from `q = 0` to `q = 1` in `T = 1`.
//! Pontryagin's principle ([BH75] §2.8; `H = ½u² + λ₁v + λ₂u`, `λ̇₁ = 0`, `λ̇₂ = −λ₁`,
//! `u = −λ₂`) makes `u` affine, `u = a + bt`; then `q(t) = at²/2 + bt³/6`, and `q̇(1) = 0`,
//! `q(1) = 1` give `a = 6`, `b = −12`: `u(t) = 6 − 12t`, `J = ½∫₀¹(6 − 12t)² dt = 6`.

use marsden::analysis::diagnostics::least_squares_slope;
use marsden::systems::FreeFall;
use marsden::{Midpoint, Rule, Trapezoid};
use marsden_control::{Boundary, Effort, InputMap, OptimalControl, SqpOptions};

const DOUBLE_INTEGRATOR: FreeFall = FreeFall { m: 1.0, g: 0.0 };

/// `(cost error, max |u_k − u(t_k + h/2)|)` of the discrete optimum with `steps` steps.
fn errors<R: Rule>(rule: &R, steps: usize) -> (f64, f64) {
    let problem = OptimalControl::new(
        DOUBLE_INTEGRATOR,
        InputMap::full(1),
        Effort::default(),
        (0.0, 1.0, steps),
        Boundary::rest(&[0.0]),
        Boundary::rest(&[1.0]),
    )
    .unwrap();
    let solution = problem.solve(rule, &SqpOptions::default()).unwrap();
    assert!(solution.converged(), "{:?}", solution.status);
    let h = 1.0 / steps as f64;
    let control = (0..steps)
        .map(|k| (solution.u[k][0] - (6.0 - 12.0 * (k as f64 + 0.5) * h)).abs())
        .fold(0.0, f64::max);
    ((solution.cost - 6.0).abs(), control)
}

/// The slopes of `log error` against `log h` over N = 10, 20, 40, 80.
fn slopes<R: Rule>(rule: &R) -> (f64, f64) {
    let ns = [10, 20, 40, 80];
    let log_h: Vec<f64> = ns.iter().map(|&n| (1.0 / n as f64).ln()).collect();
    let (mut cost, mut control) = (Vec::new(), Vec::new());
    for n in ns {
        let (c, u) = errors(rule, n);
        println!(
            "{} N = {n}: |J − 6| = {c:.3e}, max |u − u*| = {u:.3e}",
            rule.name()
        );
        cost.push(c.ln());
        control.push(u.ln());
    }
    (
        least_squares_slope(&log_h, &cost),
        least_squares_slope(&log_h, &control),
    )
}

/// DMOC with the midpoint rule converges at order 2 to the closed-form optimum ([OJM11] §4:
/// the order of the discrete Lagrangian).
#[test]
fn midpoint_double_integrator_converges_at_order_two() {
    let (cost, control) = slopes(&Midpoint);
    println!("midpoint slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}

/// The same with the trapezoid rule.
#[test]
fn trapezoid_double_integrator_converges_at_order_two() {
    let (cost, control) = slopes(&Trapezoid);
    println!("trapezoid slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}
