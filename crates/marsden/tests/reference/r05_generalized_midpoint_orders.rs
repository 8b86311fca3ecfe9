//! Reference case R5 (and the convergence orders): the generalised midpoint family on
//! the pendulum to T = 5 — order 1 for α ≠ ½, order 2 for midpoint and the symmetrised rules.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{loglog_slope, run};
use marsden::systems::Pendulum;
use marsden::{
    DiscreteAction, GeneralizedMidpoint, Midpoint, Rule, SymmetrizedMidpoint, Trapezoid,
};

/// Exact pendulum solution at T = 5 from (1.5, 0) (reference case R6).
const EXACT: (f64, f64) = (-0.6247457443050779, 1.2168604323725019);

fn error_at_t5<A: DiscreteAction>(action: A, n: usize) -> f64 {
    let s = run(action, &[1.5], &[0.0], 5.0 / n as f64, n);
    (s.q[0] - EXACT.0).hypot(s.p[0] - EXACT.1)
}

fn errors<R: Rule>(rule: &R) -> Vec<f64> {
    [50, 100, 200, 400, 800]
        .iter()
        .map(|&n| error_at_t5(rule.discretize(Pendulum::default()), n))
        .collect()
}

/// Observed order of the finest refinement pair and the fitted slope of all five points.
fn orders(e: &[f64]) -> (f64, f64) {
    let h: Vec<f64> = [50.0, 100.0, 200.0, 400.0, 800.0]
        .iter()
        .map(|n| 5.0 / n)
        .collect();
    ((e[3] / e[4]).log2(), loglog_slope(&h, e))
}

#[track_caller]
fn check<R: Rule>(rule: R, order: f64, e800: Option<f64>) {
    let e = errors(&rule);
    let (last, fit) = orders(&e);
    assert!(
        (last - order).abs() <= 0.05,
        "{}: asymptotic order {last:.3}, errors {e:?}",
        rule.name()
    );
    assert!(
        (fit - order).abs() <= 0.1,
        "{}: fitted order {fit:.3}",
        rule.name()
    );
    if let Some(expected) = e800 {
        // The table gives three digits.
        assert!(
            (e[4] / expected - 1.0).abs() < 0.01,
            "{}: e(800) = {:.4e} vs {expected:.3e}",
            rule.name(),
            e[4]
        );
    }
}

#[test]
fn r5_alpha_zero_is_first_order() {
    check(GeneralizedMidpoint { alpha: 0.0 }, 1.0, Some(3.80e-3));
}

#[test]
fn r5_alpha_quarter_and_one_are_first_order() {
    check(GeneralizedMidpoint { alpha: 0.25 }, 1.0, None);
    check(GeneralizedMidpoint { alpha: 1.0 }, 1.0, None);
}

#[test]
fn r5_midpoint_is_second_order() {
    check(Midpoint, 2.0, Some(7.65e-6));
    check(GeneralizedMidpoint { alpha: 0.5 }, 2.0, Some(7.65e-6));
}

#[test]
fn r5_symmetrized_rules_are_second_order() {
    check(Trapezoid, 2.0, Some(6.53e-6));
    check(SymmetrizedMidpoint { alpha: 0.0 }, 2.0, Some(6.53e-6));
    check(SymmetrizedMidpoint { alpha: 0.25 }, 2.0, Some(4.39e-6));
}
