//! The spherical pendulum in Cartesian coordinates with the constraint `|q| = l` (SHAKE +
//! RATTLE, midpoint rule): constraint held to round-off, vertical angular momentum conserved
//! (discrete Noether), bounded energy with an `h²` fluctuation, and momenta on the cotangent
//! bundle after every step.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use crate::common::tight;
use marsden::analysis::diagnostics::{ConstraintMonitor, EnergyReport, energy_series};
use marsden::systems::SphericalPendulum;
use marsden::{
    Integrator, Midpoint, Problem, Rule, RunOptions, SolveOptions, State, TimeGrid, Trajectory,
    simulate,
};

fn pendulum() -> SphericalPendulum {
    SphericalPendulum::default()
}

/// θ = 1, ϕ = 0, θ̇ = 0, ϕ̇ = 0.8: a non-planar, quasi-periodic orbit.
fn problem(
    h: f64,
    steps: usize,
) -> Problem<SphericalPendulum, marsden::NoForce, SphericalPendulum> {
    let p = pendulum();
    Problem::new(
        p,
        p.initial(1.0, 0.0, 0.0, 0.8),
        TimeGrid::new(0.0, h, steps).unwrap(),
    )
    .unwrap()
    .with_constraint(p)
    .unwrap()
}

fn options() -> SolveOptions {
    SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    }
}

#[test]
fn constraint_held_to_1e13_and_momenta_tangent_over_1e5_steps() {
    let (p, problem) = (pendulum(), problem(0.01, 100_000));
    let mut monitor = ConstraintMonitor::new(p, p);
    let traj = problem
        .solve_with(&Midpoint, &options(), &mut monitor)
        .unwrap();
    let worst = (0..traj.len())
        .map(|i| (SphericalPendulum::radius(traj.q(i)) - p.l).abs())
        .fold(0.0, f64::max);
    let (_, velocity) = monitor.max_residuals().unwrap();
    eprintln!("max ||q_k| − l| = {worst:.2e}, max |Dφ·FH(p)| = {velocity:.2e} over 1e5 steps");
    assert!(worst <= 1e-13, "max ||q_k| − l| = {worst:e}");
    // RATTLE: the hidden constraint q·v = 0 holds after every step to solver tolerance.
    assert!(velocity <= 1e-14, "max |q_k · v_k| = {velocity:e}");
    assert_eq!(monitor.samples(), 100_001);
    // Both multiplier series are stored; their sum approximates the continuous multiplier
    // λ(t) = m(|v|² − g z)/l² ≥ m g cos θ_max > 0 here (the rod is under tension).
    for i in 1..traj.len() {
        let (lambda, mu) = (traj.multipliers(i)[0], traj.projection_multipliers(i)[0]);
        assert!(
            lambda.is_finite() && mu.is_finite() && lambda + mu > 0.0,
            "sample {i}"
        );
    }
}

#[test]
fn vertical_angular_momentum_conserved_to_1e10_over_2e5_steps() {
    let (p, problem) = (pendulum(), problem(0.01, 200_000));
    let traj = problem.solve(&Midpoint, &options()).unwrap();
    let j0 = p.vertical_angular_momentum(traj.q(0), traj.p(0));
    let worst = (0..traj.len())
        .map(|i| (p.vertical_angular_momentum(traj.q(i), traj.p(i)) - j0).abs())
        .fold(0.0, f64::max);
    eprintln!("J_z = {j0}, max |J_z − J_z(0)| = {worst:.2e} over 2e5 steps");
    assert!((j0 - 0.8 * 1f64.sin().powi(2)).abs() < 1e-15);
    assert!(worst <= 1e-10, "max |ΔJ_z| = {worst:e}");
}

/// `max E − min E` over `t ∈ [0, T]` and the drift over the run, for step `h`.
fn energy_fluctuation(h: f64, t_end: f64) -> (f64, f64) {
    let steps = (t_end / h).round() as usize;
    let traj = problem(h, steps).solve(&Midpoint, &options()).unwrap();
    let e = energy_series(&pendulum(), &traj).unwrap();
    let (lo, hi) = e
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    let report = EnergyReport::from_series(&traj.times, &e);
    (hi - lo, report.drift_per_unit_time * t_end)
}

#[test]
fn energy_bounded_without_drift_and_fluctuation_scales_as_h_squared() {
    let t_end = 500.0;
    let (f1, drift1) = energy_fluctuation(0.02, t_end);
    let (f2, drift2) = energy_fluctuation(0.01, t_end);
    let ratio = f1 / f2;
    eprintln!(
        "energy fluctuation h=0.02: {f1:.3e}, h=0.01: {f2:.3e}, ratio {ratio:.3}; \
         drift over T: {drift1:.1e}, {drift2:.1e}"
    );
    assert!((3.6..=4.4).contains(&ratio), "fluctuation ratio {ratio}");
    // No drift: the least-squares trend over the whole run is a small fraction of the
    // (bounded) fluctuation.
    assert!(
        drift1.abs() < 0.05 * f1 && drift2.abs() < 0.05 * f2,
        "{drift1:e} {drift2:e}"
    );
    assert!(f1 < 1e-3, "fluctuation {f1:e}");
}

/// SHAKE alone (no projection) gives the same positions but momenta off the cotangent bundle:
/// its velocity residual is O(h), which is why the RATTLE projection is applied.
#[test]
fn rattle_positions_equal_shake_positions_and_only_rattle_momenta_are_tangent() {
    let p = pendulum();
    let (h, steps) = (0.05, 400);
    let problem = problem(h, steps);
    let rattle = problem.solve(&Midpoint, &options()).unwrap();
    let mut shake = Integrator::new(Midpoint.discretize(p))
        .with_constraint(p)
        .with_options(tight())
        .unwrap();
    shake.set_velocity_hint(problem.initial_velocity());
    let grid = TimeGrid::new(0.0, h, steps).unwrap();
    let shake_traj: Trajectory = simulate(
        &mut shake,
        problem.start().clone(),
        &grid,
        &RunOptions::default(),
        &mut (),
    );
    let dq = (0..3)
        .map(|a| (rattle.q(steps)[a] - shake_traj.q(steps)[a]).abs())
        .fold(0.0, f64::max);
    assert!(dq < 1e-11, "positions differ by {dq:e}");
    let tangency = |traj: &Trajectory| {
        (1..traj.len())
            .map(|i| {
                let (q, pp) = (traj.q(i), traj.p(i));
                (q[0] * pp[0] + q[1] * pp[1] + q[2] * pp[2]).abs()
            })
            .fold(0.0, f64::max)
    };
    let (t_rattle, t_shake) = (tangency(&rattle), tangency(&shake_traj));
    eprintln!(
        "max |q·p|: RATTLE {t_rattle:.1e}, SHAKE {t_shake:.1e}; positions differ by {dq:.1e}"
    );
    assert!(t_rattle < 1e-14, "{t_rattle:e}");
    assert!(t_shake > 1e-3, "{t_shake:e}");
    // The multiplier shift: λ^SHAKE_k = λ^RATTLE_k + μ_{k−1} (module docs of holonomic).
    for i in 2..steps {
        let shifted = rattle.multipliers(i)[0] + rattle.projection_multipliers(i - 1)[0];
        let diff = (shake_traj.multipliers(i)[0] - shifted).abs();
        assert!(diff < 1e-9, "sample {i}: {diff:e}");
    }
}

#[test]
fn at_rest_at_the_bottom_the_multipliers_carry_the_weight() {
    // One RATTLE step from rest at the bottom stays there, and the constraint force
    // h q (λ + μ) balances gravity: λ + μ = m g / l = 1.
    let p = pendulum();
    let problem = Problem::new(
        p,
        p.initial(0.0, 0.0, 0.0, 0.0),
        TimeGrid::new(0.0, 0.1, 1).unwrap(),
    )
    .unwrap()
    .with_constraint(p)
    .unwrap();
    let mut integrator = problem.integrator(&Midpoint, tight()).unwrap();
    let mut state: State = problem.start().clone();
    integrator.step(&mut state, 0.1).unwrap();
    assert!(state.q[0].abs() < 1e-16 && (state.q[2] + 1.0).abs() < 1e-16);
    assert!(state.p.iter().all(|x| x.abs() < 1e-16));
    assert!(
        (integrator.multipliers()[0] + integrator.projection_multipliers()[0] - 1.0).abs() < 1e-14
    );
}
