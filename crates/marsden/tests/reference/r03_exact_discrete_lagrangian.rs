//! Reference case R3: the exact discrete Lagrangian of the oscillator, supplied by hand as a
//! `DiscreteLagrangian` (a first-class input), reproduces the exact flow; the local errors of
//! midpoint and trapezoid against it are O(h³).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, run};
use marsden::systems::HarmonicOscillator;
use marsden::{DiscreteLagrangian, Midpoint, Rule, Scalar, Trapezoid};

/// Hamilton's principal function of the unit oscillator:
/// `L_d^E = (mω / 2 sin ωh) [(q0² + q1²) cos ωh − 2 q0 q1]`.
struct ExactOscillatorLd;

impl DiscreteLagrangian for ExactOscillatorLd {
    fn dof(&self) -> usize {
        1
    }
    fn discrete_lagrangian<S: Scalar>(&self, _t0: f64, h: f64, q0: &[S], q1: &[S]) -> S {
        let (s, c) = h.sin_cos();
        ((q0[0] * q0[0] + q1[0] * q1[0]) * c - q0[0] * q1[0] * 2.0) * (0.5 / s)
    }
}

#[test]
fn r3_exact_discrete_lagrangian_reproduces_the_exact_flow() {
    let s = run(ExactOscillatorLd, &[1.0], &[0.0], 0.5, 1000);
    assert_close(s.q[0], -0.883849273431478, 1e-12, "q(500)");
    assert_close(s.p[0], 0.467771805322476, 1e-12, "p(500)");
}

#[test]
fn r3_local_errors_of_midpoint_and_trapezoid() {
    let ho = HarmonicOscillator::default();
    let (mid, trap) = (Midpoint.discretize(ho), Trapezoid.discretize(ho));
    let cases = [
        (0.1, 4.16042781533164e-5, 4.12922985962003e-5),
        (0.05, 5.2063810800287e-6, 5.19661952327626e-6),
    ];
    for (h, e_mid, e_trap) in cases {
        let h: f64 = h;
        let exact = -(2.0 * h).sin() / 4.0;
        let q1 = [h.cos()];
        // Cross-check of the hand-written L_d^E (cancellation in its formula costs ~10 ulp).
        assert_close(
            exact,
            ExactOscillatorLd.discrete_lagrangian(0.0, h, &[1.0], &q1),
            1e-14,
            "L_d^E",
        );
        let d_mid = mid.discrete_lagrangian(0.0, h, &[1.0], &q1) - exact;
        let d_trap = trap.discrete_lagrangian(0.0, h, &[1.0], &q1) - exact;
        assert_close(
            d_mid,
            e_mid,
            1e-15,
            &format!("midpoint local error, h = {h}"),
        );
        assert_close(
            d_trap,
            e_trap,
            1e-15,
            &format!("trapezoid local error, h = {h}"),
        );
    }
}
