//! Reference case R1: harmonic oscillator with the midpoint discrete Lagrangian — closed-form
//! discrete solution, exact one-step matrix, exact energy conservation (quadratic invariant).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, one_step_matrix, run, run_with};
use marsden::systems::HarmonicOscillator;
use marsden::{Midpoint, Rule};

const TABLE: [(usize, f64, f64); 3] = [
    (10, 0.54100229460035897, -0.84102111580931570),
    (100, -0.84356915087578985, 0.53702056542622173),
    (1000, 0.81725004081453757, 0.57628323833739662),
];

#[test]
fn r1_table_of_states_to_1e12_and_energy_to_1e13() {
    let ho = HarmonicOscillator::default();
    let mut max_de: f64 = 0.0;
    let mut states = Vec::new();
    run_with(
        Midpoint.discretize(ho),
        &[1.0],
        &[0.0],
        0.1,
        1000,
        |k, s| {
            max_de = max_de.max((ho.energy(s.q[0], s.p[0]) - 0.5).abs());
            if TABLE.iter().any(|row| row.0 == k) {
                states.push((s.q[0], s.p[0]));
            }
        },
    );
    for ((n, q, p), (qn, pn)) in TABLE.iter().zip(states) {
        assert_close(qn, *q, 1e-12, &format!("q_{n}"));
        assert_close(pn, *p, 1e-12, &format!("p_{n}"));
    }
    assert!(max_de <= 1e-13, "max |H_n − H_0| = {max_de:e}");
}

#[test]
fn r1_first_step_and_cayley_matrix_399_40_over_401() {
    let ld = Midpoint.discretize(HarmonicOscillator::default());
    let m = one_step_matrix(&ld, 0.1);
    let exact = [
        [399.0 / 401.0, 40.0 / 401.0],
        [-40.0 / 401.0, 399.0 / 401.0],
    ];
    for i in 0..2 {
        for j in 0..2 {
            assert_close(m[i][j], exact[i][j], 1e-15, &format!("M[{i}][{j}]"));
        }
    }
    // q1 = cos θ = 399/401 = 0.99501246882793017456.
    assert_close(m[0][0], 0.99501246882793017456, 1e-16, "q1");
}

#[test]
fn r1_million_steps_to_1e9_and_energy_to_1e9() {
    let ho = HarmonicOscillator::default();
    let mut max_de: f64 = 0.0;
    let end = run_with(
        Midpoint.discretize(ho),
        &[1.0],
        &[0.0],
        0.1,
        1_000_000,
        |_, s| {
            max_de = max_de.max((ho.energy(s.q[0], s.p[0]) - 0.5).abs());
        },
    );
    assert_close(end.q[0], -0.0078927069956715885, 1e-9, "q_1e6");
    assert_close(end.p[0], -0.99996885210304450, 1e-9, "p_1e6");
    assert!(max_de <= 1e-9, "max |H_n − H_0| = {max_de:e}");
}

#[test]
fn r1_second_data_set_k_half() {
    let ho = HarmonicOscillator { m: 1.0, k: 0.5 };
    let s = run(Midpoint.discretize(ho), &[0.5], &[0.0], 0.1, 10);
    assert_close(s.q[0], 0.38021791091075073, 1e-12, "q_10");
    assert_close(s.p[0], -0.22960219970926282, 1e-12, "p_10");
}

#[test]
fn r1_large_step_is_stable_with_cos_theta_15_over_17() {
    let ld = Midpoint.discretize(HarmonicOscillator::default());
    let m = one_step_matrix(&ld, 0.5);
    // Trace/2 = cos θ and det = 1: a rotation, unconditionally stable.
    assert_close(0.5 * (m[0][0] + m[1][1]), 15.0 / 17.0, 1e-15, "cos θ");
    assert_close(m[0][0] * m[1][1] - m[0][1] * m[1][0], 1.0, 1e-15, "det");
}
