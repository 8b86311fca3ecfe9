//! Continuous mechanics by AD: accelerations, the Euler–Lagrange residual, the Legendre
//! transform and its inverse, time dependence.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::mechanics::{
    acceleration, check_regular, energy, euler_lagrange_residual, momentum, velocity,
};
use marsden::systems::{DoublePendulum, HarmonicOscillator, Pendulum};
use marsden::{Lagrangian, Scalar};

#[test]
fn pendulum_acceleration_is_minus_g_over_l_sine() {
    let p = Pendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };
    let mut a = [0.0];
    acceleration(&p, 0.0, &[0.7], &[1.3], &mut a).unwrap();
    assert!((a[0] + 9.81 / 0.5 * 0.7f64.sin()).abs() < 1e-13);
}

#[test]
fn euler_lagrange_residual_vanishes_on_the_exact_oscillator() {
    let ho = HarmonicOscillator { m: 2.0, k: 8.0 };
    let w = ho.omega();
    for t in [0.0, 0.3, 1.7] {
        let (q, v, a) = ((w * t).cos(), -w * (w * t).sin(), -w * w * (w * t).cos());
        let mut r = [0.0];
        euler_lagrange_residual(&ho, t, &[q], &[v], &[a], &mut r);
        assert!(r[0].abs() < 1e-13, "residual {r:?} at t = {t}");
        euler_lagrange_residual(&ho, t, &[q], &[v], &[a + 1.0], &mut r);
        assert!(
            (r[0] - 2.0).abs() < 1e-13,
            "a wrong acceleration shows as m·Δa"
        );
    }
}

#[test]
fn legendre_transform_round_trips_with_a_configuration_dependent_mass() {
    let dp = DoublePendulum {
        m1: 1.0,
        m2: 3.0,
        l1: 1.2,
        l2: 0.7,
        g: 9.81,
    };
    let (q, v) = ([0.4, -1.1], [0.9, -2.3]);
    let mut p = [0.0; 2];
    momentum(&dp, 0.0, &q, &v, &mut p);
    let mut back = [0.0; 2];
    velocity(&dp, 0.0, &q, &p, &mut back).unwrap();
    assert!((back[0] - v[0]).abs() < 1e-13 && (back[1] - v[1]).abs() < 1e-13);
    // Energy is conserved along the flow: dE/dt = ⟨∂E/∂q, v⟩ + ⟨∂E/∂v, a⟩ = 0 (finite differences).
    let mut a = [0.0; 2];
    acceleration(&dp, 0.0, &q, &v, &mut a).unwrap();
    let dt = 1e-6;
    let e = |s: f64| {
        energy(
            &dp,
            0.0,
            &[q[0] + s * v[0], q[1] + s * v[1]],
            &[v[0] + s * a[0], v[1] + s * a[1]],
        )
    };
    assert!(((e(dt) - e(-dt)) / (2.0 * dt)).abs() < 1e-7);
}

/// A driven oscillator `L = ½v² − ½q² + q sin t`: time enters L, so ∂²L/∂v∂t = 0 but ∂L/∂q does.
#[derive(Debug)]
struct Driven;
impl Lagrangian for Driven {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        v[0] * v[0] * 0.5 - q[0] * q[0] * 0.5 + q[0] * t.sin()
    }
}

#[test]
fn time_dependent_lagrangians_enter_the_equations_of_motion() {
    let mut a = [0.0];
    acceleration(&Driven, 1.2, &[0.3], &[0.0], &mut a).unwrap();
    assert!((a[0] - (-0.3 + 1.2f64.sin())).abs() < 1e-14);
    assert!(check_regular(&Driven, 0.0, &[0.0], &[0.0]).is_ok());
}
