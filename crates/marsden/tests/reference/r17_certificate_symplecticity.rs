//! The certificate of symplecticity (reference case R17, n degrees of freedom): the exact
//! Jacobian of the computed step map, by AD through the converged step (implicit function
//! theorem), satisfies DFᵀJDF = J to round-off for every variational rule on the pendulum, the
//! double pendulum and Kepler — and visibly fails for explicit RK2 and for a damped system.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use crate::common::tight;
use marsden::analysis::certificate::{DifferentiableStep, certify, symplectic_defect};
use marsden::hamiltonian::{
    ExplicitMidpoint, Hamiltonian, HamiltonianIntegrator, ImplicitMidpoint, Splitting,
};
use marsden::systems::{DoublePendulum, HarmonicOscillator, Kepler, Pendulum};
use marsden::{
    DiscreteAction, Force, GeneralizedMidpoint, Integrator, Lagrangian, Midpoint, Rule, Scalar,
    State, SymmetrizedMidpoint, TimeGrid, Trapezoid,
};
use std::f64::consts::PI;

fn state(q: &[f64], p: &[f64]) -> State {
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

/// Max relative defect over `steps` certified steps of a variational integrator.
fn vi_defect<A: DiscreteAction>(action: A, start: &State, h: f64, steps: usize) -> f64 {
    let mut integrator = Integrator::new(action).with_options(tight()).unwrap();
    let grid = TimeGrid::new(0.0, h, steps).unwrap();
    let (report, _) = certify(&mut integrator, start.clone(), &grid, 1).unwrap();
    assert_eq!(report.checked, steps);
    report.max_relative
}

fn all_rules<L: Lagrangian + Copy>(name: &str, l: L, start: &State, h: f64) {
    let defects = [
        ("midpoint", vi_defect(Midpoint.discretize(l), start, h, 200)),
        (
            "trapezoid",
            vi_defect(Trapezoid.discretize(l), start, h, 200),
        ),
        (
            "alpha(0.3)",
            vi_defect(
                GeneralizedMidpoint { alpha: 0.3 }.discretize(l),
                start,
                h,
                200,
            ),
        ),
        (
            "symmetrized(0.2)",
            vi_defect(
                SymmetrizedMidpoint { alpha: 0.2 }.discretize(l),
                start,
                h,
                200,
            ),
        ),
    ];
    for (rule, d) in defects {
        println!("{name} / {rule}: max relative defect {d:.2e}");
        assert!(d <= 1e-12, "{name} / {rule}: defect {d:e}");
    }
}

#[test]
fn every_rule_is_symplectic_on_pendulum_double_pendulum_and_kepler() {
    all_rules("pendulum", Pendulum::default(), &state(&[1.5], &[0.3]), 0.1);
    all_rules(
        "double pendulum",
        DoublePendulum::default(),
        &state(&[1.0, -0.5], &[0.3, 0.2]),
        0.05,
    );
    let (q, p) = Kepler::pericentre(0.6);
    all_rules(
        "kepler",
        Kepler::default(),
        &state(&q, &p),
        2.0 * PI / 200.0,
    );
}

fn h_defect<H: Hamiltonian, M: marsden::hamiltonian::HamiltonianMethod<H>>(
    ham: H,
    method: M,
    start: &State,
    h: f64,
) -> f64 {
    let mut integrator = HamiltonianIntegrator::new(ham, method);
    let grid = TimeGrid::new(0.0, h, 200).unwrap();
    certify(&mut integrator, start.clone(), &grid, 1)
        .unwrap()
        .0
        .max_relative
}

#[test]
fn hamiltonian_methods_symplectic_and_rk2_not() {
    let pendulum = (Pendulum::default(), state(&[1.5], &[0.3]), 0.1);
    let kepler = {
        let (q, p) = Kepler::pericentre(0.6);
        (Kepler::default(), state(&q, &p), 2.0 * PI / 200.0)
    };
    let double = (
        DoublePendulum::default(),
        state(&[1.0, -0.5], &[0.3, 0.2]),
        0.05,
    );
    let midpoint = || ImplicitMidpoint::new(tight()).unwrap();
    for (name, d) in [
        (
            "pendulum / implicit midpoint",
            h_defect(pendulum.0, midpoint(), &pendulum.1, pendulum.2),
        ),
        (
            "pendulum / Störmer–Verlet",
            h_defect(
                pendulum.0,
                Splitting::stormer_verlet(),
                &pendulum.1,
                pendulum.2,
            ),
        ),
        (
            "kepler / implicit midpoint",
            h_defect(kepler.0, midpoint(), &kepler.1, kepler.2),
        ),
        (
            "kepler / symplectic Euler",
            h_defect(kepler.0, Splitting::symplectic_euler(), &kepler.1, kepler.2),
        ),
        (
            "double pendulum / implicit midpoint",
            h_defect(double.0, midpoint(), &double.1, double.2),
        ),
    ] {
        println!("{name}: max relative defect {d:.2e}");
        assert!(d <= 1e-12, "{name}: defect {d:e}");
    }
    for (name, d) in [
        (
            "pendulum",
            h_defect(pendulum.0, ExplicitMidpoint, &pendulum.1, pendulum.2),
        ),
        (
            "kepler",
            h_defect(kepler.0, ExplicitMidpoint, &kepler.1, kepler.2),
        ),
        (
            "double pendulum",
            h_defect(double.0, ExplicitMidpoint, &double.1, double.2),
        ),
    ] {
        println!("{name} / explicit RK2: max relative defect {d:.2e}");
        assert!(
            d > 1e-6,
            "{name} / RK2: defect {d:e} should be clearly non-zero"
        );
    }
}

#[test]
fn ad_jacobian_matches_finite_differences_and_has_unit_determinant() {
    // R17 setting: pendulum at (1.5, 0.3), h = 0.3.
    let step = |q: f64, p: f64, jac: &mut [f64]| {
        let mut integrator = Integrator::new(Midpoint.discretize(Pendulum::default()))
            .with_options(tight())
            .unwrap();
        let mut s = state(&[q], &[p]);
        DifferentiableStep::step_with_jacobian(&mut integrator, &mut s, 0.3, jac).unwrap();
        (s.q[0], s.p[0])
    };
    let mut jac = [0.0; 4];
    step(1.5, 0.3, &mut jac);
    let det = jac[0] * jac[3] - jac[1] * jac[2];
    assert!((det - 1.0).abs() < 1e-14, "det = {det}");
    let eps = 1e-6;
    let mut scratch = [0.0; 4];
    let (qa, pa) = step(1.5 + eps, 0.3, &mut scratch);
    let (qb, pb) = step(1.5 - eps, 0.3, &mut scratch);
    let (qc, pc) = step(1.5, 0.3 + eps, &mut scratch);
    let (qd, pd) = step(1.5, 0.3 - eps, &mut scratch);
    let fd = [
        (qa - qb) / (2.0 * eps),
        (qc - qd) / (2.0 * eps),
        (pa - pb) / (2.0 * eps),
        (pc - pd) / (2.0 * eps),
    ];
    for (a, f) in jac.iter().zip(fd) {
        assert!((a - f).abs() < 1e-8, "AD {a} vs finite differences {f}");
    }
}

/// Damping −c v: the forced discrete flow contracts volume, det DF = |λ_d|² < 1 (R12).
#[derive(Clone, Copy)]
struct Damping(f64);
impl Force for Damping {
    fn force<S: Scalar>(&self, _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        out[0] = v[0] * (-self.0);
    }
}

#[test]
fn forced_step_is_certified_not_symplectic() {
    let oscillator = HarmonicOscillator::default();
    let mut integrator = Integrator::new(Midpoint.discretize(oscillator))
        .with_force(Midpoint.discretize_force(Damping(0.1), 1))
        .with_options(tight())
        .unwrap();
    let mut jac = [0.0; 4];
    let mut s = state(&[1.0], &[0.0]);
    integrator
        .step_with_jacobian(&mut s, 0.1, &mut jac)
        .unwrap();
    // R12: the one-step matrix is exactly [[401, 40], [−40, 397]]/403.
    let want = [401.0 / 403.0, 40.0 / 403.0, -40.0 / 403.0, 397.0 / 403.0];
    for (a, w) in jac.iter().zip(want) {
        assert!((a - w).abs() < 1e-15, "{a} vs {w}");
    }
    let (_, relative) = symplectic_defect(&jac, 1);
    // det = 160797/403² = 0.99007..., so the defect is 1 − det ≈ 9.9e-3.
    assert!((relative - (1.0 - 160_797.0 / 162_409.0) / (401.0f64 / 403.0).powi(2)).abs() < 1e-14);
}
