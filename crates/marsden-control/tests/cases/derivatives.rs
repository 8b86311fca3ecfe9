//! The AD derivatives of the program against central differences (trep's `check_*` pattern):
//! cost gradient, constraint Jacobian and Hessian of the Lagrangian, for every kind of rule
//! (midpoint, trapezoid, Gauss and Lobatto with control stages, a composition, a rule chosen by
//! name), on a problem that exercises every term: a cart-pole (configuration-dependent
//! mass), a force nonlinear in `q`, `v` and `u`, a running cost in all of them, a final cost
//! in `(q_N, p_N)`, two path inequalities in all of `t, q, v, u`, a start velocity (the target momentum `∂L/∂v(q_0, v_0)` depends on `q_0`)
//! and an end with free components.

use marsden::discrete::rules::{Composition, CompositionScheme, Galerkin, Method};
use marsden::systems::PendulumOnCart;
use marsden::{Midpoint, Rule, Scalar, Trapezoid};
use marsden_control::{
    Boundary, ControlForce, FinalCost, Horizon, OptimalControl, PathConstraint, Rate, RunningCost,
    StagedControls,
};

struct Actuator;

impl ControlForce for Actuator {
    fn controls(&self) -> usize {
        2
    }
    fn force<S: Scalar>(&self, _t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        out[0] = u[0] - v[0] * 0.3 + u[1] * q[1].sin();
        out[1] = u[1] * q[1].cos() - v[1] * v[1] * 0.1 + u[0] * u[1] * 0.2;
    }
}

struct Running;

impl RunningCost for Running {
    fn cost<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S]) -> S {
        u[0] * u[0] * 0.5
            + u[1] * u[1] * (t + 1.0)
            + q[1].cos() * v[0] * 0.2
            + v[1] * v[1] * q[0] * 0.1
    }
}

struct Terminal;

impl FinalCost for Terminal {
    fn cost<S: Scalar>(&self, q: &[S], p: &[S]) -> S {
        q[0] * q[1] + p[0] * p[1] * 0.5 + p[1].sin()
    }
}

struct Envelope;

impl PathConstraint for Envelope {
    fn count(&self) -> usize {
        2
    }
    fn eval<S: Scalar>(&self, t: S, q: &[S], v: &[S], u: &[S], out: &mut [S]) {
        out[0] = q[0] * q[0] + v[1] * u[0] * 0.3 - t * 0.5;
        out[1] = q[1].sin() * v[0] + u[1] * u[1] * q[0] - 1.0;
    }
}

fn problem() -> OptimalControl<PendulumOnCart, Actuator, Running, Terminal, Envelope> {
    let start = Boundary::velocity(&[0.1, 0.4], &[0.5, -0.7]);
    let end = Boundary {
        q: vec![None, Some(2.0)],
        rate: Rate::Momentum(vec![Some(0.3), None]),
    };
    OptimalControl::new(
        PendulumOnCart::default(),
        Actuator,
        Running,
        Horizon {
            t0: 0.2,
            duration: 1.0,
            steps: 4,
        },
        start,
        end,
    )
    .unwrap()
    .with_final_cost(Terminal)
    .with_path(Envelope)
}

/// Deterministic values in [−1, 1] (a linear congruential generator).
fn values(count: usize, seed: u64) -> Vec<f64> {
    let mut state = seed;
    (0..count)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

fn check<R: Rule + StagedControls>(rule: &R) {
    let p = problem();
    let (unknowns, rows) = p.sizes(rule).unwrap();
    // n = 2, m = 2, N = 4; σ control values and r inner points per step; 4 + 2 fixed ends;
    // two path inequalities at each of the σ points of a step.
    let stages = rule.control_stages();
    let (sigma, r) = (stages.count(), stages.inner());
    let per_step = 2 + 2 * sigma + 2 * r;
    assert_eq!(
        (unknowns, rows),
        (4 * per_step + 2, 3 * 2 + 4 + 2 + 4 * 2 * r + 4 * 2 * sigma)
    );
    let z = values(unknowns, 7);
    let lambda = values(rows, 11);
    let c = p.check_derivatives(rule, &z, &lambda, 1e-5).unwrap();
    println!("{}: {c:?}", rule.name());
    assert!(c.scale > 0.1, "the check compared nothing: {c:?}");
    for (what, error) in [
        ("gradient", c.gradient),
        ("jacobian", c.jacobian),
        ("hessian", c.hessian),
    ] {
        assert!(
            error <= 1e-7 * c.scale.max(1.0),
            "{what}: {error:e} ({c:?})"
        );
    }
}

#[test]
fn midpoint_derivatives_match_central_differences() {
    check(&Midpoint);
}

#[test]
fn trapezoid_derivatives_match_central_differences() {
    check(&Trapezoid);
}

#[test]
fn gauss_derivatives_match_central_differences() {
    check(&Galerkin::gauss(2).unwrap());
}

#[test]
fn lobatto_derivatives_match_central_differences() {
    check(&Galerkin::lobatto(3).unwrap());
}

#[test]
fn galerkin_with_more_nodes_than_points_derivatives_match_central_differences() {
    // P1 with 3 Gauss points: the control values sit at the two control points.
    let rule = Galerkin::new(1, marsden::discrete::rules::QuadratureFamily::Gauss, 3).unwrap();
    assert_eq!(rule.control_stages().count(), 2);
    check(&rule);
}

#[test]
fn composition_derivatives_match_central_differences() {
    check(&Composition::new(
        marsden::Midpoint,
        CompositionScheme::TripleJump { order: 4 },
    ));
}

#[test]
fn rule_chosen_by_name_derivatives_match_central_differences() {
    check(&Method::parse("suzuki-4(lobatto-3)").unwrap());
}

#[test]
fn alpha_and_symmetrized_derivatives_match_central_differences() {
    check(&marsden::GeneralizedMidpoint::new(0.3).unwrap());
    check(&marsden::SymmetrizedMidpoint::new(0.3).unwrap());
}
