//! The explicit fast path (trapezoid rule on a separable Lagrangian = velocity Störmer–Verlet)
//! gives the same trajectory as the general Newton path, is chosen automatically, and a false
//! declaration of separability is caught.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::error::SetupError;
use marsden::systems::{HenonHeiles, Kepler, NBody, Pendulum};
use marsden::{
    DiscreteAction, Error, Initial, Integrator, Lagrangian, MassMatrix, NewtonOptions, Problem,
    Rule, Scalar, State, Structure, TimeGrid, Trapezoid,
};

fn run<A: DiscreteAction>(
    action: A,
    start: &State,
    h: f64,
    steps: usize,
    fast: bool,
) -> (Vec<f64>, usize) {
    // The Newton path converged to round-off, so both paths solve the same equations exactly.
    let tight = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(action)
        .with_fast_paths(fast)
        .with_options(tight)
        .unwrap();
    let mut s = start.clone();
    let mut out = Vec::new();
    for _ in 0..steps {
        integrator.step(&mut s, h).unwrap();
        out.extend(s.q.iter().chain(&s.p));
    }
    (out, integrator.statistics().explicit_steps)
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The explicit and Newton paths agree to round-off: one step to a few ulps, and a whole run no
/// further apart than a one-ulp change of the largest initial position or momentum moves the
/// Newton run (dynamics amplify last-bit differences; this measures by how much).
fn assert_round_off_agreement<A: DiscreteAction + Clone>(
    action: A,
    start: &State,
    h: f64,
    steps: usize,
) {
    let (one_fast, _) = run(action.clone(), start, h, 1, true);
    let (one_slow, _) = run(action.clone(), start, h, 1, false);
    let scale = one_slow.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    assert!(max_difference(&one_fast, &one_slow) <= 8.0 * f64::EPSILON * scale);
    let (fast, explicit_steps) = run(action.clone(), start, h, steps, true);
    let (slow, none) = run(action.clone(), start, h, steps, false);
    assert_eq!(
        (explicit_steps, none),
        (steps, 0),
        "the explicit path is chosen automatically"
    );
    let sensitivity = [false, true]
        .into_iter()
        .map(|momentum| {
            let mut nudged = start.clone();
            let x = if momentum {
                &mut nudged.p
            } else {
                &mut nudged.q
            };
            let i = (0..x.len()).fold(0, |b, i| if x[i].abs() > x[b].abs() { i } else { b });
            x[i] = f64::from_bits(x[i].to_bits() + 1);
            max_difference(&slow, &run(action.clone(), &nudged, h, steps, false).0)
        })
        .fold(f64::EPSILON * scale, f64::max);
    let d = max_difference(&fast, &slow);
    assert!(
        d <= 10.0 * sensitivity,
        "paths differ by {d:e}; one ulp of p₀ moves the run by {sensitivity:e}"
    );
}

#[test]
fn explicit_and_newton_trapezoid_agree_to_round_off() {
    let (q, p) = Kepler::pericentre(0.6);
    let kepler = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    assert_round_off_agreement(Trapezoid.discretize(Kepler::default()), &kepler, 0.01, 2000);
    let hh = State {
        t: 0.0,
        q: vec![0.1, -0.2],
        p: vec![0.3, 0.25],
    };
    assert_round_off_agreement(Trapezoid.discretize(HenonHeiles::default()), &hh, 0.1, 2000);
    let pend = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    assert_round_off_agreement(
        Trapezoid.discretize(Pendulum {
            m: 2.0,
            l: 0.5,
            g: 9.81,
        }),
        &pend,
        0.01,
        2000,
    );
}

#[test]
fn explicit_nbody_matches_newton_with_unequal_masses() {
    let mut system = NBody::new(vec![1.0, 1e-3, 2e-3]);
    system.softening = 0.01;
    let q = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.1, -1.5, 0.2, 0.0];
    let p = vec![
        0.0,
        -3e-3,
        0.0,
        0.0,
        1e-3,
        0.0,
        2e-3 * 0.1,
        -2e-3 * 0.8,
        0.0,
    ];
    let start = State { t: 0.0, q, p };
    assert_round_off_agreement(Trapezoid.discretize(system), &start, 0.01, 500);
}

/// Claims to be separable but has a velocity-dependent mass.
#[derive(Debug)]
struct FalselySeparable;
impl Lagrangian for FalselySeparable {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (q[0].cos() + 2.0) * v[0] * v[0] * 0.5
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![3.0]),
        }
    }
}

#[test]
fn a_false_separability_declaration_is_an_error() {
    let grid = TimeGrid::new(0.0, 0.1, 10).unwrap();
    let err = Problem::new(FalselySeparable, Initial::velocity(&[0.5], &[1.0]), grid).unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::StructureMismatch { .. })),
        "{err:?}"
    );
    assert!(err.to_string().contains("declared separable"), "{err}");
}
