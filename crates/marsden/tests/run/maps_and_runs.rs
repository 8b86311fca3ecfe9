//! The discrete flow maps, and runs with a storage stride, observers and streaming monitors.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::ops::ControlFlow;

use crate::common::SamplesOnly;
use marsden::analysis::diagnostics::{EnergyMonitor, EnergyReport};
use marsden::discrete::legendre::legendre_plus;
use marsden::integrator::maps::{discrete_hamiltonian_map, two_step_map};
use marsden::systems::Pendulum;
use marsden::{
    Initial, Lagrangian, Midpoint, NewtonOptions, Problem, Rule, RunOptions, Scalar, SolveOptions,
    StepView, Termination, TimeGrid,
};

#[test]
fn two_step_map_agrees_with_the_discrete_hamiltonian_map() {
    let ld = Midpoint.discretize(Pendulum::default());
    let o = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let (q0, q1, h) = ([1.2], [1.17], 0.1);
    let q2 = two_step_map(&ld, 0.0, h, &q0, &q1, &o).unwrap();
    // Momentum matching: p1 = D₂L_d(q0, q1), then one Hamiltonian step from (q1, p1).
    let mut p1 = [0.0];
    legendre_plus(&ld, 0.0, h, &q0, &q1, &mut p1);
    let (q2_h, _) = discrete_hamiltonian_map(&ld, h, h, &q1, &p1, &o).unwrap();
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

/// An observer with two periods (samples every 10 steps, a stop flag every 256) that need not
/// see every step: the run loop stops exactly at the multiples of either (and the last step),
/// not at every multiple of their greatest common divisor (2), and the states are those of a
/// run watched at every step, bit for bit.
#[test]
fn an_observer_with_two_periods_sees_only_their_multiples() {
    struct TwoPeriods(Vec<(usize, u64)>);
    impl marsden::Observer for TwoPeriods {
        fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
            self.0.push((view.step, view.q[0].to_bits()));
            ControlFlow::Continue(())
        }
        fn every_step(&self) -> bool {
            false
        }
        fn next_stop(&self, step: usize) -> usize {
            marsden::run::next_multiple(step, 10).min(marsden::run::next_multiple(step, 256))
        }
    }
    let options = SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    };
    let mut two = TwoPeriods(Vec::new());
    problem(1000)
        .solve_with(&Midpoint, &options, &mut two)
        .unwrap();
    let expected: Vec<usize> = (1..=1000).filter(|k| k % 10 == 0 || k % 256 == 0).collect();
    let steps: Vec<usize> = two.0.iter().map(|(k, _)| *k).collect();
    assert_eq!(steps, expected);
    let mut all = Vec::new();
    let mut every = |view: &StepView<'_>| {
        all.push(view.q[0].to_bits());
        ControlFlow::Continue(())
    };
    problem(1000)
        .solve_with(&Midpoint, &options, &mut every)
        .unwrap();
    for (k, bits) in &two.0 {
        assert_eq!(*bits, all[k - 1], "q at step {k}");
    }
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

/// `L = ½ v² − ½ q² + q sin(3t) + r q⁴`: a driven oscillator whose step depends on the time
/// (so a time off the grid by one rounding would show in the bits), on the general Newton path
/// (no structure declared); beyond the barrier of `r > 0` it leaves the floats.
#[derive(Debug, Clone)]
struct Driven {
    r: f64,
}
impl Lagrangian for Driven {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        let (q, v) = (q[0], v[0]);
        v * v * 0.5 - q * q * 0.5 + q * (t * 3.0).sin() + q.powi(4) * self.r
    }
}

/// A Newton run between samples in one call ([`marsden::run::stepper::Stepper::advance_on`],
/// what `simulate` does when no observer watches each step) equals the run seen step by step,
/// bit for bit: samples, times, statistics, and after a failure the error (step and time) and
/// the last good state. The grid starts at `t₀ = 0.3` with `h = 0.07`, so that `t₀ + k h`
/// differs from `(t₀ + j h) + (k − j) h` in the last bits.
#[test]
fn newton_steps_between_samples_in_one_call_equal_the_steps_seen_one_by_one() {
    let run = |r: f64, q0: f64, stride: usize, watch: bool| {
        let grid = TimeGrid::new(0.3, 0.07, 700).unwrap();
        let start = Initial::velocity(&[q0], &[0.2]);
        let problem = Problem::new(Driven { r }, start, grid).unwrap();
        let options = SolveOptions {
            run: RunOptions { stride },
            ..SolveOptions::default()
        };
        match watch {
            true => {
                let mut seen = 0;
                let mut observer = |_: &StepView<'_>| {
                    seen += 1;
                    ControlFlow::Continue(())
                };
                let traj = problem.solve_with(&Midpoint, &options, &mut observer);
                let traj = traj.unwrap_or_else(|failure| failure.trajectory);
                assert_eq!(seen, traj.steps, "the watcher saw every completed step");
                traj
            }
            false => {
                let mut samples = SamplesOnly(0);
                let traj = problem.solve_with(&Midpoint, &options, &mut samples);
                let traj = traj.unwrap_or_else(|failure| failure.trajectory);
                // Shown the stored samples only (a failure's last state is stored, not shown).
                assert!(samples.0 < traj.len(), "{} of {}", samples.0, traj.len());
                traj
            }
        }
    };
    for (r, q0, stride) in [(0.0, 0.4, 50), (0.02, 6.0, 3)] {
        let (chunked, single) = (run(r, q0, stride, false), run(r, q0, stride, true));
        assert_eq!(chunked.step_indices, single.step_indices);
        assert_eq!(chunked.times, single.times);
        for i in 0..chunked.len() {
            assert_eq!(chunked.q(i), single.q(i), "sample {i}");
            assert_eq!(chunked.p(i), single.p(i), "sample {i}");
        }
        assert_eq!(chunked.statistics, single.statistics);
        assert_eq!(
            format!("{:?}", chunked.termination),
            format!("{:?}", single.termination)
        );
        let completed = matches!(chunked.termination, Termination::Completed);
        assert_eq!(completed, r == 0.0, "{:?}", chunked.termination);
        assert!(
            chunked.steps > 2 * stride,
            "failed at step {}",
            chunked.steps
        );
    }
}
