//! Reference case R17: time reversibility of the symmetric rules and symplecticity of the step
//! map (determinant of the one-step Jacobian by central differences).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::tight;
use marsden::systems::Pendulum;
use marsden::{DiscreteAction, Integrator, Midpoint, Rule, State, Trapezoid};

fn forward_then_back<A: DiscreteAction>(action: A) -> (f64, f64) {
    let mut integrator = Integrator::new(action).with_options(tight()).unwrap();
    let mut s = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    for _ in 0..10_000 {
        integrator.step(&mut s, 0.1).unwrap();
    }
    integrator.reset();
    for _ in 0..10_000 {
        integrator.step(&mut s, -0.1).unwrap();
    }
    ((s.q[0] - 1.5).abs(), s.p[0].abs())
}

#[test]
fn r17_midpoint_and_trapezoid_are_reversible() {
    for (name, (dq, dp)) in [
        (
            "midpoint",
            forward_then_back(Midpoint.discretize(Pendulum::default())),
        ),
        (
            "trapezoid",
            forward_then_back(Trapezoid.discretize(Pendulum::default())),
        ),
    ] {
        assert!(dq <= 1e-12, "{name}: |Δq| = {dq:e}");
        assert!(dp <= 1e-11, "{name}: |Δp| = {dp:e}");
    }
}

fn step_map<A: DiscreteAction + Clone>(action: &A, q: f64, p: f64, h: f64) -> (f64, f64) {
    let mut integrator = Integrator::new(action.clone())
        .with_options(tight())
        .unwrap();
    let mut s = State {
        t: 0.0,
        q: vec![q],
        p: vec![p],
    };
    integrator.step(&mut s, h).unwrap();
    (s.q[0], s.p[0])
}

fn jacobian_determinant<A: DiscreteAction + Clone>(action: &A) -> f64 {
    let (q, p, h, eps) = (1.5, 0.3, 0.3, 1e-6);
    let (qa, pa) = step_map(action, q + eps, p, h);
    let (qb, pb) = step_map(action, q - eps, p, h);
    let (qc, pc) = step_map(action, q, p + eps, h);
    let (qd, pd) = step_map(action, q, p - eps, h);
    let j = [
        [(qa - qb) / (2.0 * eps), (qc - qd) / (2.0 * eps)],
        [(pa - pb) / (2.0 * eps), (pc - pd) / (2.0 * eps)],
    ];
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

#[test]
fn r17_step_map_has_unit_jacobian_determinant() {
    let mid = jacobian_determinant(&Midpoint.discretize(Pendulum::default()));
    let trap = jacobian_determinant(&Trapezoid.discretize(Pendulum::default()));
    assert!((mid - 1.0).abs() <= 1e-8, "midpoint det = {mid}");
    assert!((trap - 1.0).abs() <= 1e-8, "trapezoid det = {trap}");
}
