//! A free end with a final cost `Φ(q_N, p_N)`: the double integrator from rest at 0, cost
//! `∫₀¹ ½u² dt + (w/2)[(q(1) − 1)² + v(1)²]`, `w = 10`.
//!
//! Pontryagin ([BH75] §2.3): `λ₁ = w e` (`e = q(1) − 1`) is constant, `λ₂(t) = w v(1) +
//! λ₁(1 − t)`, `u = −λ₂ = a + bt` with `a = −w(v(1) + e)`, `b = w e`. From rest,
//! `q(1) = a/2 + b/6` and `v(1) = a + b/2`, which give `v(1) = −w e / (2(1 + w))` and
//! `e (w² / (4(1 + w)) − w/3 − 1) = 1`; the cost is `½(a² + ab + b²/3) + (w/2)(e² + v(1)²)`.
//! The discrete final cost sees `p_N = D₂L_d + f_d⁺`, here `v(1)` to second order.
//!
//! Also the path of the default guess that simulates the free run (the end is not fixed).

use marsden::analysis::diagnostics::least_squares_slope;
use marsden::systems::FreeFall;
use marsden::{Midpoint, Scalar};
use marsden_control::{
    Boundary, Effort, FinalCost, Horizon, InputMap, OptimalControl, SqpOptions, Status,
};

const W: f64 = 10.0;

struct Soft;

impl FinalCost for Soft {
    fn cost<S: Scalar>(&self, q: &[S], p: &[S]) -> S {
        let e = q[0] - 1.0;
        (e * e + p[0] * p[0]) * (0.5 * W)
    }
}

fn continuous_cost() -> f64 {
    let e = 1.0 / (W * W / (4.0 * (1.0 + W)) - W / 3.0 - 1.0);
    let v = -W * e / (2.0 * (1.0 + W));
    let (a, b) = (-W * (v + e), W * e);
    0.5 * (a * a + a * b + b * b / 3.0) + 0.5 * W * (e * e + v * v)
}

#[test]
fn final_cost_on_a_free_end_converges_at_order_two() {
    let exact = continuous_cost();
    let ns = [10, 20, 40, 80];
    let mut log_errors = Vec::new();
    for steps in ns {
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
            Boundary::free(1),
        )
        .unwrap()
        .with_final_cost(Soft);
        let s = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
        assert_eq!(s.status, Status::Converged);
        assert!(s.end_multipliers.is_empty());
        let error = (s.cost - exact).abs();
        println!(
            "N = {steps}: cost {:.8} (continuous {exact:.8}), error {error:.3e}",
            s.cost
        );
        log_errors.push(error.ln());
    }
    let log_h: Vec<f64> = ns.iter().map(|&n| (1.0 / n as f64).ln()).collect();
    let slope = least_squares_slope(&log_h, &log_errors);
    println!("slope {slope:.4}");
    assert!((slope - 2.0).abs() <= 0.1, "slope {slope}");
}
