//! The separable fast path of the midpoint rule (Newton with Jacobian `M/h + (h/4)∇²V`, reused
//! across iterations and steps) gives the general path's trajectory to round-off, is chosen
//! automatically, and reuses its Jacobian (pinned work counters).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::systems::{Chain, HenonHeiles, Kepler, NBody, Pendulum};
use marsden::{
    DiscreteAction, GeneralizedMidpoint, Integrator, Midpoint, NewtonOptions, Rule, State,
    Statistics,
};

fn run<A: DiscreteAction>(
    action: A,
    start: &State,
    h: f64,
    steps: usize,
    fast: bool,
    tolerance: f64,
) -> (Vec<f64>, Statistics) {
    let options = NewtonOptions {
        residual_tolerance: tolerance,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(action)
        .with_fast_paths(fast)
        .with_options(options)
        .unwrap();
    let mut s = start.clone();
    let mut out = Vec::new();
    for k in 0..steps {
        integrator.step(&mut s, h).unwrap();
        s.t = (k + 1) as f64 * h;
        out.extend(s.q.iter().chain(&s.p));
    }
    (out, *integrator.statistics())
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The round-off floor of a run: how far the general path moves when every step's state is
/// nudged up by one ulp, i.e. when two implementations of the same step differ by a systematic
/// one-ulp rounding in every step (summation orders differ systematically, not at random).
fn floor<A: DiscreteAction + Clone>(action: &A, start: &State, h: f64, steps: usize) -> f64 {
    let (slow, _) = run(action.clone(), start, h, steps, false, 1e-15);
    let options = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(action.clone())
        .with_fast_paths(false)
        .with_options(options)
        .unwrap();
    let mut s = start.clone();
    let mut out = Vec::new();
    for k in 0..steps {
        integrator.step(&mut s, h).unwrap();
        s.t = (k + 1) as f64 * h;
        for x in s.q.iter_mut().chain(s.p.iter_mut()) {
            *x = x.next_up();
        }
        out.extend(s.q.iter().chain(&s.p));
    }
    let scale = slow.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    max_difference(&slow, &out).max(f64::EPSILON * scale)
}

/// Fast and general paths agree to round-off: one step from every state of the general run to
/// a few ulps, and the runs no further apart than the round-off floor allows; returns the fast
/// path's statistics.
fn assert_round_off_agreement<A: DiscreteAction + Clone>(
    name: &str,
    action: A,
    start: &State,
    h: f64,
    steps: usize,
) -> Statistics {
    let (slow, slow_stats) = run(action.clone(), start, h, steps, false, 1e-15);
    assert_eq!(slow_stats.potential_gradients, 0);
    let n = start.q.len();
    let mut worst_step: f64 = 0.0;
    for k in (0..steps).step_by((steps / 50).max(1)) {
        let from = if k == 0 {
            start.clone()
        } else {
            let x = &slow[(k - 1) * 2 * n..k * 2 * n];
            State {
                t: k as f64 * h,
                q: x[..n].to_vec(),
                p: x[n..].to_vec(),
            }
        };
        let (a, _) = run(action.clone(), &from, h, 1, true, 1e-15);
        let (b, _) = run(action.clone(), &from, h, 1, false, 1e-15);
        let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
        worst_step = worst_step.max(max_difference(&a, &b) / (f64::EPSILON * scale));
    }
    let (fast, stats) = run(action.clone(), start, h, steps, true, 1e-15);
    let floor = floor(&action, start, h, steps);
    let d = max_difference(&fast, &slow);
    println!(
        "{name}: one step ≤ {worst_step:.1} ulp; {steps} steps apart {d:.2e}, floor {floor:.2e}; {stats:?}"
    );
    assert!(
        worst_step <= 8.0,
        "{name}: one step differs by {worst_step} ulp"
    );
    assert!(
        d <= 10.0 * floor,
        "{name}: paths differ by {d:e}, floor {floor:e}"
    );
    assert!(
        stats.potential_gradients > 0,
        "{name}: the fast path was taken"
    );
    stats
}

fn state(q: &[f64], p: &[f64]) -> State {
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

#[test]
fn separable_midpoint_agrees_with_the_general_path() {
    let (q, p) = Kepler::pericentre(0.6);
    let kepler = state(&q, &p);
    assert_round_off_agreement(
        "kepler 0.6",
        Midpoint.discretize(Kepler::default()),
        &kepler,
        0.01,
        2000,
    );
    let (q, p) = Kepler::pericentre(0.3);
    assert_round_off_agreement(
        "kepler 0.3",
        Midpoint.discretize(Kepler::default()),
        &state(&q, &p),
        0.02,
        2000,
    );
    let hh = state(&[0.1, -0.2], &[0.3, 0.25]);
    assert_round_off_agreement(
        "henon-heiles",
        Midpoint.discretize(HenonHeiles::default()),
        &hh,
        0.1,
        2000,
    );
    let pendulum = Pendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };
    assert_round_off_agreement(
        "pendulum",
        Midpoint.discretize(pendulum),
        &state(&[1.5], &[0.0]),
        0.01,
        2000,
    );
    assert_round_off_agreement(
        "alpha 0.25",
        GeneralizedMidpoint { alpha: 0.25 }.discretize(Kepler::default()),
        &kepler,
        0.01,
        500,
    );
}

#[test]
fn separable_nbody_midpoint_agrees_with_the_general_path() {
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
    assert_round_off_agreement(
        "nbody",
        Midpoint.discretize(system),
        &state(&q, &p),
        0.01,
        300,
    );
}

/// n = 40 ≥ `REUSE_MIN_DOF`: the Jacobian is reused across iterations and steps (linear
/// convergence), and the answer is still the general path's to round-off.
#[test]
fn separable_chain_midpoint_with_jacobian_reuse_agrees_with_the_general_path() {
    let n = 40;
    assert!(n >= marsden::separable::alpha::REUSE_MIN_DOF);
    let q: Vec<f64> = (0..n)
        .map(|i| (std::f64::consts::PI * (i + 1) as f64 / (n + 1) as f64).sin())
        .collect();
    let stats = assert_round_off_agreement(
        "fpu chain 40",
        Midpoint.discretize(Chain::new(n)),
        &state(&q, &vec![0.0; n]),
        0.05,
        300,
    );
    assert!(
        stats.jacobian_factorizations * 4 < stats.newton_iterations,
        "the Jacobian was reused: {stats:?}"
    );
}
