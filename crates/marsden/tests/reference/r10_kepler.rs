//! Reference case R10: Kepler e = 0.6 — discrete Noether (angular momentum), bounded energy,
//! linear error growth, regression values after one period.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, run, run_with};
use marsden::systems::Kepler;
use marsden::{DiscreteAction, Midpoint, Rule, Trapezoid};
use std::f64::consts::PI;

fn start() -> ([f64; 2], [f64; 2]) {
    Kepler::pericentre(0.6)
}

/// Max angular-momentum deviation and max energy error over `steps` steps.
fn invariants<A: DiscreteAction>(action: A, h: f64, steps: usize) -> (f64, f64) {
    let k = Kepler::default();
    let (q0, p0) = start();
    let (mut dl, mut de): (f64, f64) = (0.0, 0.0);
    run_with(action, &q0, &p0, h, steps, |_, s| {
        dl = dl.max((Kepler::angular_momentum(&s.q, &s.p) - 0.8).abs());
        de = de.max((k.energy(&s.q, &s.p) + 0.5).abs());
    });
    (dl, de)
}

#[test]
fn r10_angular_momentum_to_1e12_and_bounded_energy_over_1e5_steps() {
    let h = 2.0 * PI / 1000.0;
    let (dl, de) = invariants(Midpoint.discretize(Kepler::default()), h, 100_000);
    assert!(dl <= 1e-12, "midpoint |L − 0.8| = {dl:e}");
    assert!(
        de <= 2e-4 && (de / 1.67e-4 - 1.0).abs() < 0.02,
        "midpoint max |ΔH| = {de:e}"
    );
    let (dl, de) = invariants(Trapezoid.discretize(Kepler::default()), h, 100_000);
    assert!(dl <= 1e-12, "trapezoid |L − 0.8| = {dl:e}");
    assert!(
        de <= 2e-4 && (de / 1.46e-4 - 1.0).abs() < 0.02,
        "trapezoid max |ΔH| = {de:e}"
    );
}

#[test]
fn r10_regression_after_one_period() {
    let h = 2.0 * PI / 1000.0;
    let (q0, p0) = start();
    let sv = run(Trapezoid.discretize(Kepler::default()), &q0, &p0, h, 1000);
    let want = [
        0.399976743183,
        -0.005395258405,
        0.017048904009,
        1.999886319368,
    ];
    for (got, w) in sv.q.iter().chain(&sv.p).zip(want) {
        assert_close(*got, w, 1e-10, "Störmer–Verlet after one period");
    }
    let mid = run(Midpoint.discretize(Kepler::default()), &q0, &p0, h, 1000);
    let want = [
        0.399966557645,
        0.006421333776,
        -0.020458119069,
        1.999838777269,
    ];
    for (got, w) in mid.q.iter().chain(&mid.p).zip(want) {
        assert_close(*got, w, 1e-10, "midpoint after one period");
    }
}

#[test]
fn r10_global_error_grows_linearly() {
    // Störmer–Verlet at h = 2π/4000: error at t = 2πn is |z_N − z_0| (periodic orbit).
    let h = 2.0 * PI / 4000.0;
    let (q0, p0) = start();
    let mut errors = Vec::new();
    run_with(
        Trapezoid.discretize(Kepler::default()),
        &q0,
        &p0,
        h,
        160 * 4000,
        |k, s| {
            if [10, 160].iter().any(|&n| k == n * 4000) {
                let d = [
                    s.q[0] - q0[0],
                    s.q[1] - q0[1],
                    s.p[0] - p0[0],
                    s.p[1] - p0[1],
                ];
                errors.push(d.iter().map(|x| x * x).sum::<f64>().sqrt());
            }
        },
    );
    assert_close(errors[0], 1.117e-2, 1e-5, "error after 10 periods");
    let exponent = (errors[1] / errors[0]).log2() / 4.0;
    assert!(
        (0.95..=1.05).contains(&exponent),
        "growth exponent {exponent}"
    );
}
