//! Reference case R4: unit values of L_d, the discrete Legendre transforms and the DEL residual
//! for the pendulum L = ½q̇² + cos q at (q0, q1) = (1.5, 1.49), h = 0.1.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::assert_close;
use marsden::discrete::{del_residual, legendre_minus, legendre_plus};
use marsden::integrator::maps::discrete_hamiltonian_map;
use marsden::systems::Pendulum;
use marsden::{DiscreteLagrangian, Midpoint, NewtonOptions, Rule, Trapezoid};

fn check<D: DiscreteLagrangian>(ld: &D, expected: [f64; 3], name: &str) {
    let (q0, q1, h) = ([1.5], [1.49], 0.1);
    let (mut p0, mut p1) = ([0.0], [0.0]);
    assert_close(
        ld.discrete_lagrangian(0.0, h, &q0, &q1),
        expected[0],
        1e-15,
        &format!("{name} L_d"),
    );
    legendre_minus(ld, 0.0, h, &q0, &q1, &mut p0);
    legendre_plus(ld, 0.0, h, &q0, &q1, &mut p1);
    assert_close(p0[0], expected[1], 1e-15, &format!("{name} p0"));
    assert_close(p1[0], expected[2], 1e-15, &format!("{name} p1"));
    // The library's step from (q1, p1) gives q2 with a DEL residual below solver tolerance.
    let options = NewtonOptions {
        residual_tolerance: 1e-14,
        ..NewtonOptions::default()
    };
    let (q2, _) = discrete_hamiltonian_map(ld, h, h, &q1, &p1, &options).unwrap();
    let mut r = [0.0];
    del_residual(ld, 0.0, h, [&q0, &q1, &q2], &mut r);
    assert!(r[0].abs() <= 1e-14, "{name} DEL residual {:e}", r[0]);
}

#[test]
fn r4_midpoint_values() {
    check(
        &Midpoint.discretize(Pendulum::default()),
        [
            0.0080723771606424871213,
            -0.050143558329597518235,
            -0.14985644167040248177,
        ],
        "midpoint",
    );
}

#[test]
fn r4_trapezoid_values() {
    check(
        &Trapezoid.discretize(Pendulum::default()),
        [
            0.0080722825061251762478,
            -0.050125250669797278453,
            -0.14983688760215716943,
        ],
        "trapezoid",
    );
}

#[test]
fn r4_closed_forms_of_the_momenta() {
    // midpoint: p0 = v + (h/2) sin q̄, p1 = v − (h/2) sin q̄.
    let (h, v, qbar) = (0.1, -0.1, 1.495_f64);
    let ld = Midpoint.discretize(Pendulum::default());
    let (mut p0, mut p1) = ([0.0], [0.0]);
    legendre_minus(&ld, 0.0, h, &[1.5], &[1.49], &mut p0);
    legendre_plus(&ld, 0.0, h, &[1.5], &[1.49], &mut p1);
    assert_close(p0[0], v + h / 2.0 * qbar.sin(), 1e-15, "p0 closed form");
    assert_close(p1[0], v - h / 2.0 * qbar.sin(), 1e-15, "p1 closed form");
}
