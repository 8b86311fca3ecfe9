//! Work statistics pinned for reference runs (as diffsol snapshots its solver statistics): a
//! change in the predictor or the convergence test shows up here first.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

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
    // One Newton update per step once the predictor has history, two on the first steps (the
    // separable path: exact Newton on `M/h + (h/4)∇²V`, [`marsden::separable::alpha`]).
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
    // Kepler is separable: the trapezoid rule runs as explicit Störmer–Verlet, no Newton.
    let explicit = (s.explicit_steps, s.newton_iterations, s.system_evaluations);
    assert_eq!(explicit, (1000, 0, 0), "{s:?}");
    // On the Newton path the step is linear in q_{k+1}: one update always suffices.
    let integrator = problem.integrator(&Trapezoid, Default::default()).unwrap();
    let mut integrator = integrator.with_fast_paths(false);
    let mut state = problem.start().clone();
    for _ in 0..1000 {
        integrator.step(&mut state, 0.01).unwrap();
    }
    let s = integrator.statistics();
    let newton = (
        s.newton_iterations,
        s.max_newton_iterations,
        s.system_evaluations,
    );
    assert_eq!(newton, (1000, 1, 2000), "{s:?}");
}
