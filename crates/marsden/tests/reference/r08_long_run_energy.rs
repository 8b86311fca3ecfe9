//! Reference case R8: the pendulum over 10⁶ steps — energy error bounded with no drift
//! (first vs last 10⁴ steps), amplitude O(h²), and the modified Hamiltonian conserved to O(h⁴).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::run_with;
use marsden::systems::Pendulum;
use marsden::{DiscreteAction, Midpoint, Rule, Trapezoid};

/// Modified Hamiltonians to O(h⁴) (R8): Störmer–Verlet and midpoint.
fn modified(trapezoid: bool, h: f64, q: f64, p: f64) -> f64 {
    let e = 0.5 * p * p - q.cos();
    if trapezoid {
        e + h * h * (p * p * q.cos() / 12.0 - q.sin().powi(2) / 24.0)
    } else {
        e - h * h / 24.0 * (p * p * q.cos() + q.sin().powi(2))
    }
}

struct Run {
    max_de: f64,
    first: f64,
    last: f64,
    max_dmod: f64,
}

fn long_run<A: DiscreteAction>(action: A, trapezoid: bool, h: f64) -> Run {
    const N: usize = 1_000_000;
    let pendulum = Pendulum::default();
    let (e0, m0) = (pendulum.energy(1.5, 0.0), modified(trapezoid, h, 1.5, 0.0));
    let mut r = Run {
        max_de: 0.0,
        first: 0.0,
        last: 0.0,
        max_dmod: 0.0,
    };
    run_with(action, &[1.5], &[0.0], h, N, |k, s| {
        let de = (pendulum.energy(s.q[0], s.p[0]) - e0).abs();
        r.max_de = r.max_de.max(de);
        if k <= 10_000 {
            r.first = r.first.max(de);
        }
        if k > N - 10_000 {
            r.last = r.last.max(de);
        }
        r.max_dmod = r
            .max_dmod
            .max((modified(trapezoid, h, s.q[0], s.p[0]) - m0).abs());
    });
    r
}

#[track_caller]
fn check(run: &Run, expected_max_de: f64, name: &str) {
    assert!(
        (run.max_de / expected_max_de - 1.0).abs() < 0.02,
        "{name}: max |ΔH| = {:.4e}",
        run.max_de
    );
    let ratio = run.last / run.first;
    assert!(
        (0.99..=1.01).contains(&ratio),
        "{name}: last/first = {ratio}"
    );
}

#[test]
fn r8_stormer_verlet_energy_bounded_and_modified_energy_fourth_order() {
    let coarse = long_run(Trapezoid.discretize(Pendulum::default()), true, 0.1);
    let fine = long_run(Trapezoid.discretize(Pendulum::default()), true, 0.05);
    check(&coarse, 1.9637e-3, "SV h=0.1");
    check(&fine, 4.9086e-4, "SV h=0.05");
    let ratio = coarse.max_dmod / fine.max_dmod;
    assert!(
        (15.0..=17.0).contains(&ratio),
        "SV modified-energy ratio {ratio}"
    );
}

#[test]
fn r8_midpoint_energy_bounded_and_modified_energy_fourth_order() {
    let coarse = long_run(Midpoint.discretize(Pendulum::default()), false, 0.1);
    let fine = long_run(Midpoint.discretize(Pendulum::default()), false, 0.05);
    check(&coarse, 3.5941e-4, "midpoint h=0.1");
    check(&fine, 8.9926e-5, "midpoint h=0.05");
    let ratio = coarse.max_dmod / fine.max_dmod;
    assert!(
        (15.0..=17.0).contains(&ratio),
        "midpoint modified-energy ratio {ratio}"
    );
}
