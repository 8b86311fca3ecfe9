//! The catalog's closed forms agree with what the library derives by AD, and its exact
//! solutions reproduce the reference values (R6 pendulum, R10 Kepler).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::mechanics::{energy_from_momentum, momentum};
use marsden::systems::{
    DoublePendulum, FreeFall, HarmonicOscillator, HenonHeiles, Kepler, NBody, Pendulum,
};
use marsden::{Initial, Lagrangian, Midpoint, Problem, SolveOptions, TimeGrid};

fn hamiltonian<L: Lagrangian>(l: &L, q: &[f64], p: &[f64]) -> f64 {
    let mut v = vec![0.0; l.dof()];
    energy_from_momentum(l, 0.0, q, p, &mut v).unwrap()
}

#[test]
fn closed_form_energies_equal_the_legendre_transform_energy() {
    let (q, p) = ([0.7, -0.4], [0.3, 1.1]);
    let ho = HarmonicOscillator { m: 2.0, k: 3.0 };
    assert!((ho.energy(q[0], p[0]) - hamiltonian(&ho, &q[..1], &p[..1])).abs() < 1e-14);
    let pend = Pendulum {
        m: 1.5,
        l: 0.8,
        g: 9.81,
    };
    assert!((pend.energy(q[0], p[0]) - hamiltonian(&pend, &q[..1], &p[..1])).abs() < 1e-13);
    let kepler = Kepler { mu: 2.0 };
    assert!((kepler.energy(&q, &p) - hamiltonian(&kepler, &q, &p)).abs() < 1e-14);
    let hh = HenonHeiles::default();
    assert!((hh.energy(&q, &p) - hamiltonian(&hh, &q, &p)).abs() < 1e-14);
    let nbody = NBody {
        masses: vec![1.0, 0.1],
        g: 1.5,
        softening: 0.01,
    };
    let (q6, p6) = (
        [0.0, 0.1, 0.0, 1.0, 0.0, 0.2],
        [0.0, -0.1, 0.0, 0.0, 0.1, 0.0],
    );
    assert!((nbody.energy(&q6, &p6) - hamiltonian(&nbody, &q6, &p6)).abs() < 1e-14);
}

#[test]
fn double_pendulum_energy_is_kinetic_plus_potential_of_the_bobs() {
    let dp = DoublePendulum {
        m1: 1.0,
        m2: 2.0,
        l1: 1.5,
        l2: 0.5,
        g: 9.81,
    };
    let (q, v) = ([0.9, -0.3], [0.4, 1.2]);
    let mut p = [0.0; 2];
    momentum(&dp, 0.0, &q, &v, &mut p);
    // Bob velocities by finite differences of positions along v.
    let eps = 1e-7;
    let (a, b) = (
        dp.positions(&[q[0] - eps * v[0], q[1] - eps * v[1]]),
        dp.positions(&[q[0] + eps * v[0], q[1] + eps * v[1]]),
    );
    let vel: Vec<f64> = (0..4).map(|i| (b[i] - a[i]) / (2.0 * eps)).collect();
    let x = dp.positions(&q);
    let kinetic = 0.5 * dp.m1 * (vel[0].powi(2) + vel[1].powi(2))
        + 0.5 * dp.m2 * (vel[2].powi(2) + vel[3].powi(2));
    let potential = dp.g * (dp.m1 * x[1] + dp.m2 * x[3]);
    assert!((hamiltonian(&dp, &q, &p) - kinetic - potential).abs() < 1e-7);
}

#[test]
fn exact_solutions_reproduce_the_reference_values() {
    let (q, p) = Pendulum::default().exact(1.5, 0.0, 5.0).unwrap();
    assert!((q + 0.6247457443050779).abs() < 1e-13 && (p - 1.2168604323725019).abs() < 1e-13);
    // Period 4K(sin²(0.75))/1 for amplitude 1.5.
    let period = Pendulum::default().period(1.5).unwrap();
    let (q, p) = Pendulum::default().exact(1.5, 0.0, period).unwrap();
    assert!((q - 1.5).abs() < 1e-12 && p.abs() < 1e-12);
    let (q0, p0) = Kepler::pericentre(0.6);
    let (q, p) = Kepler::default().exact(q0, p0, 1.0).unwrap();
    let want = [
        -0.6289481768266243,
        0.7996647309700393,
        -0.9825156909388113,
        -0.0227631700974305,
    ];
    for (got, w) in q.iter().chain(&p).zip(want) {
        assert!((got - w).abs() < 1e-13);
    }
    let (q, p) = FreeFall::default().exact(0.0, 5.0, 10.0);
    assert!((q + 440.5).abs() < 1e-12 && (p + 93.1).abs() < 1e-12);
}

#[test]
fn midpoint_converges_to_the_exact_pendulum_with_order_two() {
    let pend = Pendulum {
        m: 1.0,
        l: 2.0,
        g: 9.81,
    };
    let (t_end, q0, v0) = (3.0, 2.0, 0.5);
    let (qe, pe) = pend
        .exact(q0, pend.m * pend.l * pend.l * v0, t_end)
        .unwrap();
    let errors: Vec<f64> = [300, 600]
        .iter()
        .map(|&n| {
            let grid = TimeGrid::new(0.0, t_end / n as f64, n).unwrap();
            let traj = Problem::new(pend, Initial::velocity(&[q0], &[v0]), grid)
                .unwrap()
                .solve(&Midpoint, &SolveOptions::default())
                .unwrap();
            let last = traj.len() - 1;
            (traj.q(last)[0] - qe).hypot(traj.p(last)[0] - pe)
        })
        .collect();
    let order = (errors[0] / errors[1]).log2();
    assert!(
        (order - 2.0).abs() < 0.05,
        "order {order}, errors {errors:?}"
    );
}
