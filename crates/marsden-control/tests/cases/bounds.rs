//! Control bounds: the double integrator of [`super::linear_quadratic`] with `|u| ≤ a`; state
//! bounds: the Bryson–Denham problem (at the end).
//!
//! Pontryagin's principle makes `u` the saturation of an affine function, `u = sat_a(c₁ + c₂t)`
//! ([BH75] §3.8), and the problem is symmetric under `t ↦ 1 − t`, `q ↦ 1 − q`, so
//! `u(t) = min(a, c(½ − t))` on `[0, ½]` and `u(1 − t) = −u(t)`. With `τ = ½ − t` and
//! `τ₁ = a/c` (where the bound is left), `q(1) = ∫₀^½ 2τ min(a, cτ) dτ = a/4 − aτ₁²/3 = 1`
//! gives `τ₁² = 3/4 − 3/a` (feasible for `a > 4`), and the cost is
//! `J = ∫₀^½ min(a, cτ)² dτ = a²(½ − 2τ₁/3)`.

use marsden::Midpoint;
use marsden::systems::FreeFall;
use marsden_control::{Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions, Status};

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
            Horizon {
                t0: 0.0,
                duration: 1.0,
                steps,
            },
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

/// State bounds: the Bryson–Denham problem ([BH75] §3.11; a standard benchmark of direct
/// methods): `ẍ = u`, `J = ∫₀¹ ½u²`, from `(x, v) = (0, 1)` to `(0, −1)` with `x ≤ ℓ`. For
/// `ℓ ≤ 1/6` the optimum rides the bound on a middle arc and costs `J = 4/(9ℓ)`: 4 for
/// `ℓ = 1/9` (SNOPT through TOMLAB's collocation: 4.00002). The discrete optimum approaches it,
/// the bound holds at every node, and it is active on the middle arc
/// `t ∈ [3ℓ, 1 − 3ℓ] = [⅓, ⅔]`.
#[test]
fn bryson_denham_state_bound_approaches_four() {
    let ell = 1.0 / 9.0;
    let mut errors = Vec::new();
    for steps in [30, 60, 120] {
        let problem = OptimalControl::new(
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
        .unwrap()
        .with_state_bounds(&[f64::NEG_INFINITY], &[ell])
        .unwrap();
        let s = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
        assert_eq!(s.status, Status::Converged, "N = {steps}");
        let highest = s.q.iter().map(|q| q[0]).fold(f64::NEG_INFINITY, f64::max);
        assert!(highest <= ell + 1e-12, "x reaches {highest}");
        let active: Vec<f64> = (s.t.iter().zip(&s.q))
            .filter(|(_, q)| ell - q[0] <= 1e-9)
            .map(|(&t, _)| t)
            .collect();
        let (first, last) = (active[0], active[active.len() - 1]);
        println!(
            "Bryson–Denham N = {steps}: cost {:.6}, {} iterations, bound active on [{first:.3}, \
             {last:.3}]",
            s.cost, s.iterations
        );
        let h = 1.0 / steps as f64;
        assert!((first - 1.0 / 3.0).abs() <= 2.0 * h && (last - 2.0 / 3.0).abs() <= 2.0 * h);
        errors.push((s.cost - 4.0).abs());
    }
    println!("Bryson–Denham |J − 4|: {errors:?}");
    // Order 2: each halving of h divides the error by about 4.
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.6..4.4).contains(&ratio), "{errors:?}");
    }
}
