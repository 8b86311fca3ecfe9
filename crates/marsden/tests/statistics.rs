//! Work statistics pinned for reference runs (as diffsol snapshots its solver statistics): a
//! change in the predictor or the convergence test shows up here first.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use marsden::systems::{Kepler, Pendulum};
use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, Trapezoid};

#[test]
fn pendulum_midpoint_work_is_pinned() {
    let grid = TimeGrid::new(0.0, 0.05, 1000).unwrap();
    let problem =
        Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), grid).unwrap();
    let traj = problem.solve(&Midpoint, &SolveOptions::default()).unwrap();
    let s = traj.statistics;
    assert_eq!(s.steps, 1000);
    assert_eq!(s.failed_steps, 0);
    // One Newton update per step once the predictor has history; two on the first steps.
    assert_eq!(s.newton_iterations, PENDULUM_ITERATIONS, "{s:?}");
    assert_eq!(s.max_newton_iterations, 2);
    assert_eq!(s.system_evaluations, s.newton_iterations + s.steps);
}

const PENDULUM_ITERATIONS: usize = 1002;

#[test]
fn kepler_trapezoid_work_is_pinned() {
    let (q, p) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let problem = Problem::new(Kepler::default(), Initial::momentum(&q, &p), grid).unwrap();
    let traj = problem.solve(&Trapezoid, &SolveOptions::default()).unwrap();
    let s = traj.statistics;
    // The trapezoid step is linear in q_{k+1} for this Lagrangian: one update always suffices.
    assert_eq!(
        (s.newton_iterations, s.max_newton_iterations),
        (1000, 1),
        "{s:?}"
    );
    assert_eq!(s.system_evaluations, 2000);
}
