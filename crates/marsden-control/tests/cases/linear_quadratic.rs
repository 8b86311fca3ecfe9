//! Linear–quadratic problems with closed-form optima.
//!
//! Double integrator: `L = ½q̇²`, force `u`, cost `∫₀¹ ½u² dt`, rest to rest from `q = 0` to `q = 1` in `T = 1`.
//! Pontryagin's principle ([BH75] §2.8; `H = ½u² + λ₁v + λ₂u`, `λ̇₁ = 0`, `λ̇₂ = −λ₁`,
//! `u = −λ₂`) makes `u` affine, `u = a + bt`; then `q(t) = at²/2 + bt³/6`, and `q̇(1) = 0`,
//! `q(1) = 1` give `a = 6`, `b = −12`: `u(t) = 6 − 12t`, `J = ½∫₀¹(6 − 12t)² dt = 6`.
//!
//! Harmonic oscillator: `L = ½q̇² − ½q²`, the same force, cost and boundary data. Now
//! `λ̇₁ = λ₂`, `λ̇₂ = −λ₁`, so `u = −λ₂ = A cos t + B sin t`, and the resonant response from
//! rest is `q = (A t sin t − B t cos t + B sin t)/2`, `q̇ = (A(sin t + t cos t) + B t sin t)/2`;
//! `q(1) = 1`, `q̇(1) = 0` are two linear equations for `A`, `B`, and
//! `J = ½[A²(½ + sin 2/4) + B²(½ − sin 2/4) + AB sin²1]`.

use marsden::analysis::diagnostics::least_squares_slope;
use marsden::systems::{FreeFall, HarmonicOscillator};
use marsden::{Lagrangian, Midpoint, Rule, Trapezoid};
use marsden_control::{
    Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions, StagedControls,
};

const DOUBLE_INTEGRATOR: FreeFall = FreeFall { m: 1.0, g: 0.0 };

/// The continuous optimum: `u(t)` and `J`.
pub(super) struct Optimum {
    pub(super) control: fn(f64) -> f64,
    pub(super) cost: f64,
}

const DOUBLE_INTEGRATOR_OPTIMUM: Optimum = Optimum {
    control: |t| 6.0 - 12.0 * t,
    cost: 6.0,
};

/// `(A, B)` of the oscillator's optimal control `A cos t + B sin t` (Cramer's rule).
pub(super) fn oscillator_coefficients() -> (f64, f64) {
    let (s, c) = 1.0_f64.sin_cos();
    // q(1) = 1:  A s/2 + B (s − c)/2 = 1;   q̇(1) = 0:  A (s + c)/2 + B s/2 = 0.
    let (a11, a12, a21, a22) = (s / 2.0, (s - c) / 2.0, (s + c) / 2.0, s / 2.0);
    let det = a11 * a22 - a12 * a21;
    (a22 / det, -a21 / det)
}

pub(super) fn oscillator_optimum() -> Optimum {
    let (a, b) = oscillator_coefficients();
    let (s, s2) = (1.0_f64.sin(), 2.0_f64.sin());
    Optimum {
        control: |t| {
            let (a, b) = oscillator_coefficients();
            a * t.cos() + b * t.sin()
        },
        cost: 0.5 * (a * a * (0.5 + s2 / 4.0) + b * b * (0.5 - s2 / 4.0) + a * b * s * s),
    }
}

/// `(cost error, max |u_k − u(t_k + h/2)|)` of the discrete optimum with `steps` steps.
/// `system` with the force `u` and the cost `∫ ½u²`, from rest at 0 to rest at 1 in `T = 1`
/// with `steps` steps.
pub(super) fn rest_to_rest<L: Lagrangian>(
    system: L,
    steps: usize,
) -> OptimalControl<L, InputMap, Effort> {
    OptimalControl::new(
        system,
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 1.0,
            steps,
        },
        Boundary::rest(&[0.0]),
        Boundary::rest(&[1.0]),
    )
    .unwrap()
}

fn errors<L: Lagrangian, R: Rule + StagedControls>(
    system: L,
    optimum: &Optimum,
    rule: &R,
    steps: usize,
) -> (f64, f64) {
    let problem = rest_to_rest(system, steps);
    let solution = problem.solve(rule, &SqpOptions::default()).unwrap();
    assert!(solution.converged(), "{:?}", solution.status);
    let h = 1.0 / steps as f64;
    let control = (0..steps)
        .map(|k| (solution.u[k][0] - (optimum.control)((k as f64 + 0.5) * h)).abs())
        .fold(0.0, f64::max);
    ((solution.cost - optimum.cost).abs(), control)
}

/// The slopes of `log error` against `log h` over N = 10, 20, 40, 80.
fn slopes<L: Lagrangian + Copy, R: Rule + StagedControls>(
    system: L,
    optimum: &Optimum,
    rule: &R,
) -> (f64, f64) {
    let ns = [10, 20, 40, 80];
    let log_h: Vec<f64> = ns.iter().map(|&n| (1.0 / n as f64).ln()).collect();
    let (mut cost, mut control) = (Vec::new(), Vec::new());
    for n in ns {
        let (c, u) = errors(system, optimum, rule, n);
        println!(
            "{} N = {n}: |J − J*| = {c:.3e}, max |u − u*| = {u:.3e}",
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
    let (cost, control) = slopes(DOUBLE_INTEGRATOR, &DOUBLE_INTEGRATOR_OPTIMUM, &Midpoint);
    println!("midpoint slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}

/// The same with the trapezoid rule.
#[test]
fn trapezoid_double_integrator_converges_at_order_two() {
    let (cost, control) = slopes(DOUBLE_INTEGRATOR, &DOUBLE_INTEGRATOR_OPTIMUM, &Trapezoid);
    println!("trapezoid slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}

/// The harmonic oscillator: midpoint converges at order 2 to the resonant optimum.
#[test]
fn midpoint_oscillator_converges_at_order_two() {
    let optimum = oscillator_optimum();
    println!("oscillator: continuous cost {:.10}", optimum.cost);
    let oscillator = HarmonicOscillator { m: 1.0, k: 1.0 };
    let (cost, control) = slopes(oscillator, &optimum, &Midpoint);
    println!("oscillator midpoint slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}

/// The same with the trapezoid rule (a different discrete problem: the potential is sampled
/// at the ends).
#[test]
fn trapezoid_oscillator_converges_at_order_two() {
    let optimum = oscillator_optimum();
    let oscillator = HarmonicOscillator { m: 1.0, k: 1.0 };
    let (cost, control) = slopes(oscillator, &optimum, &Trapezoid);
    println!("oscillator trapezoid slopes: cost {cost:.4}, control {control:.4}");
    assert!((cost - 2.0).abs() <= 0.1, "cost slope {cost}");
    assert!((control - 2.0).abs() <= 0.1, "control slope {control}");
}
