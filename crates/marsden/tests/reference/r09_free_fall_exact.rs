//! Reference case R9: in a linear potential every variational integrator is exact.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::run;
use marsden::systems::FreeFall;
use marsden::{Midpoint, Rule, Trapezoid};

#[test]
fn r9_midpoint_and_trapezoid_are_exact_for_free_fall() {
    let ff = FreeFall::default();
    let (q_exact, p_exact) = ff.exact(0.0, 5.0, 10.0);
    assert!((q_exact + 440.5).abs() < 1e-12 && (p_exact + 93.1).abs() < 1e-12);
    for (name, s) in [
        (
            "midpoint",
            run(Midpoint.discretize(ff), &[0.0], &[5.0], 0.1, 100),
        ),
        (
            "trapezoid",
            run(Trapezoid.discretize(ff), &[0.0], &[5.0], 0.1, 100),
        ),
    ] {
        assert!(
            ((s.q[0] - q_exact) / q_exact).abs() <= 1e-13,
            "{name}: q = {}",
            s.q[0]
        );
        assert!(
            ((s.p[0] - p_exact) / p_exact).abs() <= 1e-13,
            "{name}: p = {}",
            s.p[0]
        );
    }
}
