//! Reference case R3 with the exact discrete Lagrangian computed by shooting
//! ([`marsden::discrete::exact`]): its discrete Hamiltonian map is the exact flow, and the local errors of
//! midpoint and trapezoid against it are the closed-form values; the local order of Galerkin
//! rules is `2s + 1` against it on the pendulum.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use crate::common::{assert_close, loglog_slope};
use marsden::discrete::exact::{ExactDiscreteLagrangian, local_error};
use marsden::discrete::rules::Galerkin;
use marsden::systems::{HarmonicOscillator, Pendulum};
use marsden::{
    DiscreteAction, DiscreteLagrangian, Integrator, Midpoint, NewtonOptions, Rule, State, Trapezoid,
};

#[test]
fn r3_shooting_value_matches_hamiltons_principal_function() {
    let exact = ExactDiscreteLagrangian::new(HarmonicOscillator::default());
    for (h, q0, q1) in [(0.1_f64, 1.0, 0.3), (0.5, -0.2, 0.7), (1.3, 0.4, 0.4)] {
        let (s, c) = h.sin_cos();
        let closed = ((q0 * q0 + q1 * q1) * c - 2.0 * q0 * q1) / (2.0 * s);
        let shot = exact.value(0.0, h, &[q0], &[q1]).unwrap();
        // The closed form loses ~10 ulp to cancellation: relative 2e-15.
        assert_close(
            shot,
            closed,
            2e-15 * closed.abs().max(1.0),
            &format!("L_d^E, h = {h}"),
        );
        // F^±L_d^E = FL at the ends: p0 = (q1 − q0 cos h)/sin h, p1 = (q1 cos h − q0)/sin h.
        let (p0, p1) = exact.momenta(0.0, h, &[q0], &[q1]).unwrap();
        let (e0, e1) = ((q1 - q0 * c) / s, (q1 * c - q0) / s);
        // Both sides carry a few ulp of cancellation (q₁ − q₀ cos h)/sin h: relative 1e-14.
        assert_close(p0[0], e0, 1e-14 * e0.abs().max(1.0), "p0");
        assert_close(p1[0], e1, 1e-14 * e1.abs().max(1.0), "p1");
    }
}

#[test]
fn r3_exact_discrete_lagrangian_by_shooting_reproduces_the_exact_flow() {
    let exact = ExactDiscreteLagrangian::new(HarmonicOscillator::default());
    // The shooting's value and gradient carry noise of a few 1e-15, so Newton's residual
    // cannot reach `tight()`; it is stopped at 1e-13 relative (its quadratic convergence leaves
    // the accepted iterate at the noise level).
    let options = NewtonOptions {
        residual_tolerance: 1e-13,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(exact).with_options(options).unwrap();
    let mut s = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![0.0],
    };
    for k in 0..1000 {
        integrator.step(&mut s, 0.5).unwrap();
        s.t = (k + 1) as f64 * 0.5;
    }
    // Observed (shooting): see the report; tolerance of R3.
    println!(
        "q = {:.17e} (err {:.2e}), p = {:.17e} (err {:.2e})",
        s.q[0],
        s.q[0] + 0.883849273431478,
        s.p[0],
        s.p[0] - 0.467771805322476
    );
    assert_close(s.q[0], -0.883849273431478, 1e-12, "q(500)");
    assert_close(s.p[0], 0.467771805322476, 1e-12, "p(500)");
}

#[test]
fn r3_local_errors_of_midpoint_and_trapezoid_against_shooting() {
    let ho = HarmonicOscillator::default();
    let exact = ExactDiscreteLagrangian::new(ho);
    let (mid, trap) = (Midpoint.discretize(ho), Trapezoid.discretize(ho));
    let cases = [
        (0.1, 4.16042781533164e-5, 4.12922985962003e-5),
        (0.05, 5.2063810800287e-6, 5.19661952327626e-6),
    ];
    for (h, e_mid, e_trap) in cases {
        let h: f64 = h;
        let ends = ([1.0], [h.cos()]);
        let d_mid = local_error(&mid, &exact, 0.0, h, &ends.0, &ends.1).unwrap();
        let d_trap = local_error(&trap, &exact, 0.0, h, &ends.0, &ends.1).unwrap();
        println!(
            "h = {h}: mid {d_mid:.15e} ({:.1e}), trap {d_trap:.15e} ({:.1e})",
            d_mid - e_mid,
            d_trap - e_trap
        );
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

/// `L_d(q₀, q₁)` of a two-stage Galerkin rule (one interior point), extremised over the
/// interior point by Newton's method with hyper-dual derivatives.
fn galerkin_ld(g: &Galerkin, q0: f64, q1: f64, h: f64) -> f64 {
    use num_dual::HyperDual64;
    let ld = g.discretize(Pendulum::default());
    assert_eq!(ld.internal_stages(), 1);
    let mut mid = 0.5 * (q1 - q0);
    for _ in 0..30 {
        let x = HyperDual64::new(mid, 1.0, 1.0, 0.0);
        let end = HyperDual64::from(q1 - q0);
        let a = ld.action(0.0, h, &[HyperDual64::from(q0)], &[x, end]);
        let update = a.eps1 / a.eps1eps2;
        mid -= update;
        if update.abs() < 1e-17 {
            break;
        }
    }
    ld.action(0.0, h, &[q0], &[mid, q1 - q0])
}

#[test]
fn local_order_of_galerkin_rules_against_the_exact_discrete_lagrangian() {
    // Along the exact pendulum path from (1.5, 0): L_d(q(0), q(h)) − L_d^E(q(0), q(h)) is
    // O(h^{r+1}) for a rule of order r (MW01 §2.3): 3 for midpoint, 5 for P2 with 2 Gauss or
    // 3 Lobatto points.
    let pendulum = Pendulum::default();
    let exact = ExactDiscreteLagrangian::new(pendulum);
    let hs = [0.1, 0.05, 0.025];
    let ends: Vec<f64> = hs
        .iter()
        .map(|&h| pendulum.exact(1.5, 0.0, h).unwrap().0)
        .collect();
    let reference: Vec<f64> = hs
        .iter()
        .zip(&ends)
        .map(|(&h, &q1)| exact.value(0.0, h, &[1.5], &[q1]).unwrap())
        .collect();
    let slope = |ld: &dyn Fn(f64, f64) -> f64| {
        let errors: Vec<f64> = (0..hs.len())
            .map(|k| (ld(hs[k], ends[k]) - reference[k]).abs())
            .collect();
        (loglog_slope(&hs, &errors), errors)
    };
    let mid = Midpoint.discretize(pendulum);
    let (s, e) = slope(&|h, q1| mid.discrete_lagrangian(0.0, h, &[1.5], &[q1]));
    println!("midpoint: local errors {e:?}, slope {s:.3}");
    assert!((s - 3.0).abs() < 0.05, "midpoint local order {s}");
    for g in [Galerkin::gauss(2).unwrap(), Galerkin::lobatto(3).unwrap()] {
        let (s, e) = slope(&|h, q1| galerkin_ld(&g, 1.5, q1, h));
        println!("{}: local errors {e:?}, slope {s:.3}", g.name());
        assert!((s - 5.0).abs() < 0.2, "{}: local order {s}", g.name());
    }
}
