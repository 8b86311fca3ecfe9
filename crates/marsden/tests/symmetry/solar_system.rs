//! The outer solar system (HLW06 §I.2.4; `bench/data/outer_solar_system_hlw.txt`): total linear
//! and angular momentum are discrete Noether invariants of the midpoint and trapezoid variational
//! integrators (translation and SO(3) invariance of L_d), constant to 1e-12 relative.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use marsden::analysis::diagnostics::NoetherReport;
use marsden::symmetry::DeclaresSymmetries;
use marsden::systems::NBody;
use marsden::{
    Initial, Midpoint, NewtonOptions, Problem, Rule, RunOptions, SolveOptions, TimeGrid, Trapezoid,
};

/// G in AU³/(solar mass · day²) (HLW06 §I.2.4).
const G: f64 = 2.95912208286e-4;

/// Reads `N` then `m x y z vx vy vz` per body; returns the system, positions and momenta `m v`.
fn outer_solar_system() -> (NBody, Vec<f64>, Vec<f64>) {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/outer_solar_system_hlw.txt"
    );
    let text = std::fs::read_to_string(path).expect("outer solar system data");
    let mut lines = text.lines();
    let n: usize = lines.next().unwrap().trim().parse().unwrap();
    let (mut masses, mut q, mut p) = (Vec::new(), Vec::new(), Vec::new());
    for line in lines.take(n) {
        let x: Vec<f64> = line
            .split_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        masses.push(x[0]);
        q.extend_from_slice(&x[1..4]);
        p.extend(x[4..7].iter().map(|v| x[0] * v));
    }
    let mut system = NBody::new(masses);
    system.g = G;
    (system, q, p)
}

/// Newton converged to round-off. The core's residual test is relative to max(1, |p|), i.e.
/// absolute here (|p| ~ 1e-6 in solar masses · AU/day), so the residual tolerance is set below
/// anything reachable and the iteration stops on the update size (at round-off).
fn round_off() -> NewtonOptions {
    NewtonOptions {
        residual_tolerance: 1e-30,
        ..NewtonOptions::default()
    }
}

/// Relative drifts of total linear and angular momentum over `steps` steps of 10 days.
fn drifts<R: Rule>(rule: &R, steps: usize, newton: NewtonOptions) -> (f64, f64) {
    let (system, q, p) = outer_solar_system();
    let grid = TimeGrid::new(0.0, 10.0, steps).unwrap();
    let problem = Problem::new(system.clone(), Initial::momentum(&q, &p), grid).unwrap();
    let options = SolveOptions {
        newton,
        run: RunOptions { stride: 10 },
        ..SolveOptions::default()
    };
    let start = std::time::Instant::now();
    let trajectory = problem.solve(rule, &options).unwrap();
    let reports = NoetherReport::all(&system.symmetries(), &trajectory).unwrap();
    println!(
        "{}: {steps} steps in {:.1?} ({:.2} Newton it./step): linear {:.2e}, angular {:.2e} (|P₀| = {:.2e}, |L₀| = {:.2e})",
        rule.name(),
        start.elapsed(),
        trajectory.statistics.newton_iterations as f64 / steps as f64,
        reports[0].max_rel_drift,
        reports[1].max_rel_drift,
        reports[0].initial.iter().map(|x| x * x).sum::<f64>().sqrt(),
        reports[1].initial.iter().map(|x| x * x).sum::<f64>().sqrt(),
    );
    (reports[0].max_rel_drift, reports[1].max_rel_drift)
}

fn assert_conserved(steps: usize) {
    for (name, (linear, angular)) in [
        ("midpoint", drifts(&Midpoint, steps, round_off())),
        ("trapezoid", drifts(&Trapezoid, steps, round_off())),
    ] {
        assert!(linear <= 1e-12, "{name}: linear momentum drift {linear:e}");
        assert!(
            angular <= 1e-12,
            "{name}: angular momentum drift {angular:e}"
        );
    }
}

#[test]
fn outer_solar_system_momenta_constant_2000_steps() {
    assert_conserved(2_000);
}

/// The full 2·10⁴ steps (5.5·10⁵ days); see the timing printed by the default-tier test.
#[test]
#[ignore = "slow tier: about a minute in the dev profile"]
fn outer_solar_system_momenta_constant_20000_steps() {
    assert_conserved(20_000);
}

#[test]
#[ignore = "measurement: the default Newton residual test is absolute for |p| ≪ 1"]
fn outer_solar_system_with_tight_residual_tolerance() {
    drifts(&Midpoint, 2_000, crate::common::tight());
    drifts(&Trapezoid, 2_000, crate::common::tight());
}
