//! Reference case R2: harmonic oscillator with the trapezoid discrete Lagrangian (= velocity
//! Störmer–Verlet) — closed form, exact modified energy, stability limit hω < 2.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, one_step_matrix, run_with};
use marsden::systems::HarmonicOscillator;
use marsden::{Rule, Trapezoid};

#[test]
fn r2_table_of_states_and_modified_energy_over_a_million_steps() {
    let ho = HarmonicOscillator::default();
    let h = 0.1;
    let modified = |q: f64, p: f64| 0.5 * p * p + 0.5 * (1.0 - h * h / 4.0) * q * q;
    let (h0, m0) = (0.5, modified(1.0, 0.0));
    let (mut max_dh, mut max_dm): (f64, f64) = (0.0, 0.0);
    let table = [
        (10, 0.53995125093350849, -0.84064351243484952),
        (100, -0.83679492711038773, 0.54683161424465491),
        (1000, 0.88268496731653979, 0.46937733259310209),
    ];
    let end = run_with(
        Trapezoid.discretize(ho),
        &[1.0],
        &[0.0],
        h,
        1_000_000,
        |k, s| {
            let (q, p) = (s.q[0], s.p[0]);
            max_dh = max_dh.max((ho.energy(q, p) - h0).abs());
            max_dm = max_dm.max((modified(q, p) - m0).abs());
            if let Some((_, qe, pe)) = table.iter().find(|row| row.0 == k) {
                assert_close(q, *qe, 1e-12, &format!("q_{k}"));
                assert_close(p, *pe, 1e-12, &format!("p_{k}"));
            }
        },
    );
    assert_close(end.q[0], 0.66958187968933969, 1e-9, "q_1e6");
    assert_close(end.p[0], -0.74180924510665907, 1e-9, "p_1e6");
    assert!(max_dm <= 1e-11, "max |H̃_n − H̃_0| = {max_dm:e}");
    // max |H_n − H_0| = k h² ω² q0² / 8 = h²/8 exactly, to relative 1e-9.
    assert_close(
        max_dh / (h * h / 8.0),
        1.0,
        1e-9,
        "max |H_n − H_0| / (h²/8)",
    );
}

#[test]
fn r2_one_step_matrix_has_determinant_one() {
    let h: f64 = 0.1;
    let m = one_step_matrix(&Trapezoid.discretize(HarmonicOscillator::default()), h);
    let exact = [
        [1.0 - h * h / 2.0, h],
        [-h * (1.0 - h * h / 4.0), 1.0 - h * h / 2.0],
    ];
    for i in 0..2 {
        for j in 0..2 {
            assert_close(m[i][j], exact[i][j], 1e-15, &format!("M[{i}][{j}]"));
        }
    }
    assert_close(m[0][0] * m[1][1] - m[0][1] * m[1][0], 1.0, 1e-15, "det");
}

/// Eigenvalues of a real 2×2 matrix with real spectrum, ascending.
fn real_eigenvalues(m: [[f64; 2]; 2]) -> [f64; 2] {
    let tr = m[0][0] + m[1][1];
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    let disc = (tr * tr / 4.0 - det).sqrt();
    [tr / 2.0 - disc, tr / 2.0 + disc]
}

#[test]
fn r2_unstable_beyond_h_omega_2_while_midpoint_is_not() {
    let ho = HarmonicOscillator::default();
    let trap = one_step_matrix(&Trapezoid.discretize(ho), 2.5);
    let [a, b] = real_eigenvalues(trap);
    assert_close(a, -4.0, 1e-13, "λ₁");
    assert_close(b, -0.25, 1e-13, "λ₂");
    let mid = one_step_matrix(&marsden::Midpoint.discretize(ho), 2.5);
    assert_close(
        0.5 * (mid[0][0] + mid[1][1]),
        -9.0 / 41.0,
        1e-15,
        "midpoint cos θ",
    );
    assert_close(
        mid[0][0] * mid[1][1] - mid[0][1] * mid[1][0],
        1.0,
        1e-15,
        "midpoint det",
    );
}
