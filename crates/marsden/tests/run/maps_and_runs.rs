//! The discrete flow maps, and runs with a storage stride, observers and streaming monitors.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::ops::ControlFlow;

use marsden::analysis::diagnostics::{EnergyMonitor, EnergyReport};
use marsden::discrete::legendre::legendre_plus;
use marsden::integrator::maps::{discrete_hamiltonian_map, two_step_map};
use marsden::systems::Pendulum;
use marsden::{
    Initial, Midpoint, NewtonOptions, Problem, Rule, RunOptions, SolveOptions, StepView,
    Termination, TimeGrid,
};

#[test]
fn two_step_map_agrees_with_the_discrete_hamiltonian_map() {
    let ld = Midpoint.discretize(Pendulum::default());
    let o = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let (q0, q1, h) = ([1.2], [1.17], 0.1);
    let q2 = two_step_map(&ld, 0.0, h, (&q0, &q1), &o).unwrap();
    // Momentum matching: p1 = D₂L_d(q0, q1), then one Hamiltonian step from (q1, p1).
    let mut p1 = [0.0];
    legendre_plus(&ld, 0.0, h, &q0, &q1, &mut p1);
    let (q2_h, _) = discrete_hamiltonian_map(&ld, h, h, (&q1, &p1), &o).unwrap();
    assert!((q2[0] - q2_h[0]).abs() < 1e-15);
}

fn problem(steps: usize) -> Problem<Pendulum> {
    let grid = TimeGrid::new(0.0, 0.05, steps).unwrap();
    Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), grid).unwrap()
}

#[test]
fn stride_stores_every_kth_state_plus_first_and_last() {
    let options = SolveOptions {
        run: RunOptions { stride: 10 },
        ..SolveOptions::default()
    };
    let traj = problem(95).solve(&Midpoint, &options).unwrap();
    let expected: Vec<usize> = (0..=90).step_by(10).chain([95]).collect();
    assert_eq!(traj.step_indices, expected);
    assert_eq!(traj.len(), expected.len());
    assert!(
        (traj.t(traj.len() - 1) - 95.0 * 0.05).abs() < 1e-15,
        "times are t0 + k h"
    );
    let full = problem(95)
        .solve(&Midpoint, &SolveOptions::default())
        .unwrap();
    assert_eq!(
        traj.q(3),
        full.q(30),
        "stride changes storage, not the computation"
    );
}

#[test]
fn observers_see_every_step_and_can_stop_the_run() {
    let mut seen = Vec::new();
    let mut observer = |view: &StepView<'_>| {
        seen.push(view.step);
        if view.step == 40 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let traj = problem(100)
        .solve_with(&Midpoint, &SolveOptions::default(), &mut observer)
        .unwrap();
    assert_eq!(seen, (1..=40).collect::<Vec<_>>());
    assert_eq!(traj.termination, Termination::Stopped { steps: 40 });
    assert_eq!(*traj.step_indices.last().unwrap(), 40);
}

#[test]
fn streaming_energy_monitor_equals_the_batch_report() {
    let p = problem(2000);
    let options = SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    };
    let mut monitor = EnergyMonitor::new(Pendulum::default());
    let sparse = p.solve_with(&Midpoint, &options, &mut monitor).unwrap();
    assert_eq!(
        sparse.len(),
        2,
        "only the first and the last state are stored"
    );
    let full = p.solve(&Midpoint, &SolveOptions::default()).unwrap();
    let batch = EnergyReport::of(&Pendulum::default(), &full).unwrap();
    let streamed = monitor.report().unwrap();
    assert_eq!(streamed.samples, 2001);
    assert!((streamed.max_abs_error - batch.max_abs_error).abs() < 1e-16);
    assert!((streamed.drift_per_unit_time - batch.drift_per_unit_time).abs() < 1e-15);
    // A symplectic method on a conservative system: bounded error, no drift.
    assert!(batch.drift_per_unit_time.abs() < 1e-3 * batch.max_abs_error);
}
