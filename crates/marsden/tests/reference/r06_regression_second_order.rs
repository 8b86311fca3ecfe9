//! Reference case R6 (the second-order rows): midpoint and trapezoid on the pendulum at
//! h = 0.1, N = 100 against the regression table, and the orders from N = 10 … 80.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, run};
use marsden::systems::Pendulum;
use marsden::{Midpoint, Rule, Trapezoid};

#[test]
fn r6_midpoint_and_trapezoid_regression_values_at_t10() {
    let p = Pendulum::default();
    let mid = run(Midpoint.discretize(p), &[1.5], &[0.0], 0.1, 100);
    assert_close(mid.q[0], -1.050881405153385, 1e-11, "midpoint q_100");
    assert_close(mid.p[0], -0.923194845294426, 1e-11, "midpoint p_100");
    let trap = run(Trapezoid.discretize(p), &[1.5], &[0.0], 0.1, 100);
    assert_close(trap.q[0], -1.056937687332870, 1e-11, "trapezoid q_100");
    assert_close(trap.p[0], -0.916909286877726, 1e-11, "trapezoid p_100");
    let h0 = p.energy(1.5, 0.0);
    assert!((p.energy(mid.q[0], mid.p[0]) - h0 - 7.526e-5).abs() < 1e-8);
    assert!((p.energy(trap.q[0], trap.p[0]) - h0 + 4.427e-4).abs() < 1e-7);
}

#[test]
fn r6_error_table_for_p1_rows() {
    let exact = (-0.6247457443050779, 1.2168604323725019);
    let rows: [(&str, [f64; 4]); 2] = [
        ("midpoint", [4.914e-2, 1.225e-2, 3.059e-3, 7.647e-4]),
        ("trapezoid", [4.293e-2, 1.051e-2, 2.615e-3, 6.529e-4]),
    ];
    for (name, table) in rows {
        for (i, n) in [10usize, 20, 40, 80].into_iter().enumerate() {
            let h = 5.0 / n as f64;
            let s = match name {
                "midpoint" => run(
                    Midpoint.discretize(Pendulum::default()),
                    &[1.5],
                    &[0.0],
                    h,
                    n,
                ),
                _ => run(
                    Trapezoid.discretize(Pendulum::default()),
                    &[1.5],
                    &[0.0],
                    h,
                    n,
                ),
            };
            let e = (s.q[0] - exact.0).hypot(s.p[0] - exact.1);
            // Four significant digits in the table.
            assert!(
                (e / table[i] - 1.0).abs() < 1e-3,
                "{name} N = {n}: {e:.4e} vs {:.3e}",
                table[i]
            );
        }
    }
}
