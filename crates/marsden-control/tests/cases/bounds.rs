//! Control bounds: the double integrator of [`super::linear_quadratic`] with `|u| ≤ a`.
//!
//! Pontryagin's principle makes `u` the saturation of an affine function, `u = sat_a(c₁ + c₂t)`
//! ([BH75] §3.8), and the problem is symmetric under `t ↦ 1 − t`, `q ↦ 1 − q`, so
//! `u(t) = min(a, c(½ − t))` on `[0, ½]` and `u(1 − t) = −u(t)`. With `τ = ½ − t` and
//! `τ₁ = a/c` (where the bound is left), `q(1) = ∫₀^½ 2τ min(a, cτ) dτ = a/4 − aτ₁²/3 = 1`
//! gives `τ₁² = 3/4 − 3/a` (feasible for `a > 4`), and the cost is
//! `J = ∫₀^½ min(a, cτ)² dτ = a²(½ − 2τ₁/3)`.

use marsden::Midpoint;
use marsden::systems::FreeFall;
use marsden_control::{Boundary, Effort, InputMap, OptimalControl, SqpOptions, Status};

const BOUND: f64 = 4.5;

fn continuous_optimum() -> f64 {
    let tau = (0.75 - 3.0 / BOUND).sqrt();
    BOUND * BOUND * (0.5 - 2.0 * tau / 3.0)
}

#[test]
fn bounded_double_integrator_approaches_the_saturated_optimum() {
    let exact = continuous_optimum();
    let mut errors = Vec::new();
    for steps in [20, 40, 80] {
        let problem = OptimalControl::new(
            FreeFall { m: 1.0, g: 0.0 },
            InputMap::full(1),
            Effort::default(),
            (0.0, 1.0, steps),
            Boundary::rest(&[0.0]),
            Boundary::rest(&[1.0]),
        )
        .unwrap()
        .with_control_bounds(&[-BOUND], &[BOUND])
        .unwrap();
        let s = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
        assert_eq!(s.status, Status::Converged, "N = {steps}");
        let largest = s.u.iter().map(|u| u[0].abs()).fold(0.0, f64::max);
        let active = s.u.iter().filter(|u| BOUND - u[0].abs() <= 1e-7).count();
        let antisymmetry = (0..steps)
            .map(|k| (s.u[k][0] + s.u[steps - 1 - k][0]).abs())
            .fold(0.0, f64::max);
        println!(
            "N = {steps}: cost {:.6} (continuous {exact:.6}), {} iterations, {active} active, \
             max |u| {largest:.9}, antisymmetry {antisymmetry:.1e}",
            s.cost, s.iterations
        );
        assert!(largest <= BOUND + 1e-9);
        assert!(
            active >= 2 * (steps as f64 * 0.2) as usize,
            "{active} active"
        );
        assert!(antisymmetry <= 1e-7);
        errors.push((s.cost - exact).abs());
    }
    println!("errors {errors:?}");
    // Second order despite the kinks of u at the switching times: the ratios are ≈ 4.
    assert!(errors[2] <= 2e-3);
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.6..=4.4).contains(&ratio), "ratio {ratio}");
    }
}
