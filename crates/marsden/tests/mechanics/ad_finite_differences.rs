//! Automatic derivatives against central finite differences on random states (proptest):
//! `∂L/∂q`, `∂L/∂v` for the catalog, and `D₁L_d`, `D₂L_d` for every rule.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::discrete::{d1, d2};
use marsden::mechanics::LagrangianJet;
use marsden::systems::{DoublePendulum, HenonHeiles, Kepler, NBody, Pendulum};
use marsden::{
    DiscreteLagrangian, GeneralizedMidpoint, Lagrangian, Midpoint, Rule, SymmetrizedMidpoint,
    Trapezoid,
};
use proptest::prelude::*;

const EPS: f64 = 1e-6;

fn central(f: impl Fn(f64) -> f64, x: f64) -> f64 {
    (f(x + EPS) - f(x - EPS)) / (2.0 * EPS)
}

/// Max relative difference between the AD gradient and finite differences of `L` in q and v.
fn lagrangian_fd_error<L: Lagrangian>(l: &L, t: f64, q: &[f64], v: &[f64]) -> f64 {
    let jet = LagrangianJet::at(l, t, q, v);
    let mut worst: f64 = 0.0;
    for i in 0..l.dof() {
        let fq = central(
            |x| {
                let mut y = q.to_vec();
                y[i] = x;
                l.lagrangian(t, &y, v)
            },
            q[i],
        );
        let fv = central(
            |x| {
                let mut y = v.to_vec();
                y[i] = x;
                l.lagrangian(t, q, &y)
            },
            v[i],
        );
        worst = worst.max((fq - jet.dl_dq[i]).abs() / (1.0 + fq.abs()));
        worst = worst.max((fv - jet.dl_dv[i]).abs() / (1.0 + fv.abs()));
    }
    worst
}

/// Max relative difference between AD and finite differences of `D₁L_d`, `D₂L_d`.
fn discrete_fd_error<D: DiscreteLagrangian>(ld: &D, h: f64, q0: &[f64], q1: &[f64]) -> f64 {
    let n = ld.dof();
    let (mut g1, mut g2) = (vec![0.0; n], vec![0.0; n]);
    d1(ld, 0.3, h, q0, q1, &mut g1);
    d2(ld, 0.3, h, q0, q1, &mut g2);
    let mut worst: f64 = 0.0;
    for i in 0..n {
        let f1 = central(
            |x| {
                let mut y = q0.to_vec();
                y[i] = x;
                ld.discrete_lagrangian(0.3, h, &y, q1)
            },
            q0[i],
        );
        let f2 = central(
            |x| {
                let mut y = q1.to_vec();
                y[i] = x;
                ld.discrete_lagrangian(0.3, h, q0, &y)
            },
            q1[i],
        );
        worst = worst.max((f1 - g1[i]).abs() / (1.0 + f1.abs()));
        worst = worst.max((f2 - g2[i]).abs() / (1.0 + f2.abs()));
    }
    worst
}

fn coords(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-2.0..2.0f64, n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn lagrangian_gradients_match_finite_differences(q in coords(2), v in coords(2), t in -1.0..1.0f64) {
        prop_assert!(lagrangian_fd_error(&Pendulum::default(), t, &q[..1], &v[..1]) < 1e-7);
        prop_assert!(lagrangian_fd_error(&DoublePendulum::default(), t, &q, &v) < 1e-7);
        prop_assert!(lagrangian_fd_error(&HenonHeiles::default(), t, &q, &v) < 1e-7);
        // Keep Kepler away from its singularity.
        let qk = [q[0] + 3.0, q[1]];
        prop_assert!(lagrangian_fd_error(&Kepler::default(), t, &qk, &v) < 1e-7);
    }

    #[test]
    fn nbody_gradients_match_finite_differences(q in coords(6), v in coords(6)) {
        let mut system = NBody::new(vec![1.0, 0.5]);
        system.softening = 0.1;
        prop_assert!(lagrangian_fd_error(&system, 0.0, &q, &v) < 1e-7);
    }

    #[test]
    fn discrete_lagrangian_derivatives_match_finite_differences(
        q0 in coords(2), dq in coords(2), h in 0.01..0.5f64,
    ) {
        let q1: Vec<f64> = q0.iter().zip(&dq).map(|(a, d)| a + 0.1 * d).collect();
        let dp = DoublePendulum::default();
        prop_assert!(discrete_fd_error(&Midpoint.discretize(dp), h, &q0, &q1) < 1e-6);
        prop_assert!(discrete_fd_error(&Trapezoid.discretize(dp), h, &q0, &q1) < 1e-6);
        let (alpha, symmetrized) = (GeneralizedMidpoint { alpha: 0.3 }, SymmetrizedMidpoint { alpha: 0.2 });
        prop_assert!(discrete_fd_error(&alpha.discretize(dp), h, &q0, &q1) < 1e-6);
        prop_assert!(discrete_fd_error(&symmetrized.discretize(dp), h, &q0, &q1) < 1e-6);
    }
}
