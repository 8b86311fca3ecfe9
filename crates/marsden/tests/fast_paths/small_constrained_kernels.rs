//! The statically sized constrained step (`marsden::integrator::small::constrained`) and the general path
//! solve the same SHAKE equations: with and without forces, for both second-order rules and for
//! one and two constraints, the trajectories (with the RATTLE projection) agree to round-off;
//! the kernel's x86-64-v3 copy (`marsden::integrator::small::dispatch`) and its baseline code agree bit for bit.

// Tests: helpers unwrap.
#![allow(clippy::unwrap_used)]

use crate::common::tight;
use marsden::forces::LinearDamping;
use marsden::holonomic::Rattle;
use marsden::systems::{CartesianDoublePendulum, CartesianPendulum, SphericalPendulum};
use marsden::{
    Constraint, DiscreteForce, Force, Integrator, Lagrangian, Midpoint, NoForce, Rule, State,
    Trapezoid,
};

/// 1000 steps with the fast paths on or off and the wide instructions (`marsden::integrator::small::dispatch`) on
/// or off; the trajectory with the multipliers, and the Newton iterations.
fn run<L, C, F, R>(
    sys: (L, C),
    force: F,
    rule: &R,
    start: &State,
    fast: bool,
    wide: bool,
) -> (Vec<f64>, usize)
where
    L: Lagrangian + Clone,
    C: Constraint + Clone,
    F: Force + Clone,
    R: Rule,
{
    let (l, c) = sys;
    let n = l.dof();
    let mut integrator = Integrator::new(rule.discretize(l.clone()))
        .with_force(rule.discretize_force(force, n))
        .with_constraint(c.clone())
        .with_projection(Rattle::new(l, c))
        .with_options(tight())
        .unwrap()
        .with_fast_paths(fast)
        .with_wide_instructions(wide);
    let mut state = start.clone();
    let mut out = Vec::new();
    for _ in 0..1000 {
        integrator.step(&mut state, 0.02).unwrap();
        out.extend(
            state
                .q
                .iter()
                .chain(&state.p)
                .chain(integrator.multipliers()),
        );
    }
    (out, integrator.statistics().newton_iterations)
}

fn check<L, C, F, R>(name: &str, sys: (L, C), force: F, rule: R, start: State)
where
    L: Lagrangian + Clone,
    C: Constraint + Clone,
    F: Force + Clone,
    R: Rule,
    R::DiscreteForce<F>: DiscreteForce,
{
    let (fast, iterations_fast) = run(sys.clone(), force.clone(), &rule, &start, true, true);
    // The x86-64-v3 copy of the kernel and the baseline code: the same bits.
    let (baseline, _) = run(sys.clone(), force.clone(), &rule, &start, true, false);
    let same = fast
        .iter()
        .zip(&baseline)
        .all(|(a, b)| a.to_bits() == b.to_bits());
    assert!(same, "{name}: wide and baseline instructions differ");
    let (general, iterations_general) = run(sys, force, &rule, &start, false, true);
    let diff = fast
        .iter()
        .zip(&general)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!("{name}: max |static − general| = {diff:.1e}");
    assert!(diff < 1e-12, "{name}: {diff:e}");
    let spread = iterations_fast.abs_diff(iterations_general);
    assert!(
        spread <= 10,
        "{name}: Newton iterations {iterations_fast} vs {iterations_general}"
    );
}

fn start(initial: marsden::Initial, l: &impl Lagrangian) -> State {
    let marsden::Initial::Velocity { q, v } = initial else {
        panic!("velocity data expected")
    };
    let mut p = vec![0.0; q.len()];
    marsden::mechanics::momentum(l, 0.0, &q, &v, &mut p);
    State { t: 0.0, q, p }
}

#[test]
fn static_and_general_constrained_steps_agree() {
    let plane = CartesianPendulum::default();
    let s = start(plane.initial(1.5, 0.0), &plane);
    check(
        "planar, midpoint",
        (plane, plane),
        NoForce,
        Midpoint,
        s.clone(),
    );
    check("planar, trapezoid", (plane, plane), NoForce, Trapezoid, s);
    let sphere = SphericalPendulum::default();
    let s = start(sphere.initial(1.0, 0.0, 0.0, 0.8), &sphere);
    let damping = LinearDamping::uniform(0.1).unwrap();
    check("sphere, damped", (sphere, sphere), damping, Midpoint, s);
    let double = CartesianDoublePendulum::default();
    let s = start(double.initial([0.8, 0.3], [0.0, 0.0]), &double);
    check("double pendulum", (double, double), NoForce, Midpoint, s);
}
