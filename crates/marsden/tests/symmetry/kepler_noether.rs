//! Reference case R10 (discrete Noether): the angular momentum of Kepler e = 0.6 through the
//! discrete momentum maps J^±_{L_d} is constant to 1e-12 over 10⁵ steps for the midpoint and
//! trapezoid rules; the Noether diagnostics (batch and streaming) report it, and report a
//! non-conserved "momentum map" as drifting.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use crate::common::tight;
use marsden::analysis::diagnostics::{NoetherMonitor, NoetherReport};
use marsden::symmetry::{
    AxisRotation, DeclaresSymmetries, Side, StepSpan, discrete_momentum_offset,
};
use marsden::systems::{HenonHeiles, Kepler};
use marsden::{
    DiscreteLagrangian, Initial, Integrator, Midpoint, Problem, Rule, SolveOptions, State,
    TimeGrid, Trapezoid,
};
use std::f64::consts::PI;

/// Max over 10⁵ steps of |J⁺_{L_d}(q_k, q_{k+1}) − 0.8| and |J⁻_{L_d}(q_k, q_{k+1}) − 0.8|.
fn discrete_noether<D: DiscreteLagrangian>(ld: D, steps: usize) -> (f64, f64) {
    let h = 2.0 * PI / 1000.0;
    let (q0, p0) = Kepler::pericentre(0.6);
    let rotation = AxisRotation::planar(1);
    let mut integrator = Integrator::new(ld).with_options(tight()).unwrap();
    let mut state = State {
        t: 0.0,
        q: q0.to_vec(),
        p: p0.to_vec(),
    };
    let (mut plus, mut minus) = (0.0_f64, 0.0_f64);
    let mut j = [0.0];
    for k in 0..steps {
        let (t, q) = (state.t, state.q.clone());
        integrator.step(&mut state, h).unwrap();
        state.t = (k + 1) as f64 * h;
        let (ld, span) = (integrator.action(), StepSpan { t0: t, h });
        let delta = integrator.stage_offsets();
        discrete_momentum_offset(ld, &rotation, span, &q, delta, Side::Plus, &mut j);
        plus = plus.max((j[0] - 0.8).abs());
        discrete_momentum_offset(ld, &rotation, span, &q, delta, Side::Minus, &mut j);
        minus = minus.max((j[0] - 0.8).abs());
    }
    (plus, minus)
}

#[test]
fn r10_discrete_momentum_maps_constant_to_1e12_over_1e5_steps() {
    for (name, (plus, minus)) in [
        (
            "midpoint",
            discrete_noether(Midpoint.discretize(Kepler::default()), 100_000),
        ),
        (
            "trapezoid",
            discrete_noether(Trapezoid.discretize(Kepler::default()), 100_000),
        ),
    ] {
        println!("{name}: max |J⁺ − 0.8| = {plus:.2e}, max |J⁻ − 0.8| = {minus:.2e}");
        assert!(plus <= 1e-12, "{name}: max |J⁺ − 0.8| = {plus:e}");
        assert!(minus <= 1e-12, "{name}: max |J⁻ − 0.8| = {minus:e}");
    }
}

#[test]
fn noether_report_and_monitor_agree_and_detect_a_non_symmetry() {
    let (q0, p0) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 2.0 * PI / 1000.0, 10_000).unwrap();
    let problem = Problem::new(Kepler::default(), Initial::momentum(&q0, &p0), grid).unwrap();
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    let mut monitor = NoetherMonitor::new(Kepler::default().symmetries());
    let trajectory = problem
        .solve_with(&Midpoint, &options, &mut monitor)
        .unwrap();
    let batch = NoetherReport::all(&Kepler::default().symmetries(), &trajectory).unwrap();
    let streamed = monitor.reports().unwrap();
    assert_eq!(batch.len(), 1);
    assert_eq!(batch[0], streamed[0]);
    assert!((batch[0].initial[0] - 0.8).abs() < 1e-15);
    assert!(batch[0].max_rel_drift < 1e-13, "{:?}", batch[0]);
    assert_eq!(batch[0].samples, 10_001);

    // Hénon–Heiles is not rotation invariant: its "angular momentum" is not conserved.
    let hh = Problem::new(
        HenonHeiles::default(),
        Initial::momentum(&[0.1, 0.2], &[0.3, -0.1]),
        TimeGrid::new(0.0, 0.1, 1000).unwrap(),
    )
    .unwrap();
    let trajectory = hh.solve(&Midpoint, &options).unwrap();
    let report = NoetherReport::of(&AxisRotation::planar(1), &trajectory).unwrap();
    assert!(report.max_drift > 1e-3, "{report:?}");
}

#[test]
fn hamiltonian_runs_conserve_angular_momentum_too() {
    use marsden::RunOptions;
    use marsden::hamiltonian::{HamiltonianIntegrator, ImplicitMidpoint, Splitting};
    // Cotangent-lifted rotations leave H invariant; implicit midpoint (a Gauss method) and
    // Störmer–Verlet conserve the quadratic momentum map q × p exactly.
    let (q0, p0) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 2.0 * PI / 1000.0, 10_000).unwrap();
    let start = State {
        t: 0.0,
        q: q0.to_vec(),
        p: p0.to_vec(),
    };
    let options = RunOptions { stride: 100 };
    let mut midpoint =
        HamiltonianIntegrator::new(Kepler::default(), ImplicitMidpoint::new(tight()).unwrap());
    let mut monitor = NoetherMonitor::new(Kepler::default().symmetries());
    let trajectory = midpoint.solve(start.clone(), &grid, &options, &mut monitor);
    assert!(trajectory.is_complete() && trajectory.len() == 101);
    let report = &monitor.reports().unwrap()[0];
    assert_eq!(report.samples, 10_001);
    assert!(report.max_drift <= 1e-12, "implicit midpoint: {report:?}");
    let mut verlet = HamiltonianIntegrator::new(Kepler::default(), Splitting::stormer_verlet());
    let trajectory = verlet.solve(start, &grid, &options, &mut ());
    let report = NoetherReport::of(&AxisRotation::planar(1), &trajectory).unwrap();
    assert!(report.max_drift <= 1e-12, "Störmer–Verlet: {report:?}");
}
