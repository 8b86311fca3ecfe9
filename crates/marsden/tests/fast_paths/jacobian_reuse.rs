//! Jacobian reuse on the separable midpoint path ([`marsden::separable::alpha`]): for n ≥
//! `REUSE_MIN_DOF` the factored `M/h + (h/4)∇²V` is kept across Newton iterations and steps,
//! and replaced by a fresh one when the iteration contracts slowly or `h` changes. The work
//! counters of [`marsden::Statistics`] show it; the counts of a reference run are pinned (a
//! change in the predictor, the convergence test or the refresh rule shows up here first), and
//! the answer stays the general path's (`separable_fast_path` checks that to round-off).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::separable::alpha::REUSE_MIN_DOF;
use marsden::systems::Chain;
use marsden::{Integrator, Midpoint, Rule, State, Statistics};

/// The FPU-β chain of `n` particles started in its lowest mode with `amplitude`, at rest.
fn start(n: usize, amplitude: f64) -> State {
    let q = (0..n)
        .map(|i| amplitude * (std::f64::consts::PI * (i + 1) as f64 / (n + 1) as f64).sin())
        .collect();
    State {
        t: 0.0,
        q,
        p: vec![0.0; n],
    }
}

/// Runs `steps` midpoint steps of each `h` in turn; returns the statistics and the energy error.
fn run(n: usize, amplitude: f64, hs: &[(f64, usize)]) -> (Statistics, f64) {
    let chain = Chain::new(n);
    let mut integrator = Integrator::new(Midpoint.discretize(chain));
    let mut s = start(n, amplitude);
    let e0 = chain.energy(&s.q, &s.p);
    let mut worst: f64 = 0.0;
    for &(h, steps) in hs {
        for _ in 0..steps {
            integrator.step(&mut s, h).unwrap();
            worst = worst.max((chain.energy(&s.q, &s.p) - e0).abs() / e0);
        }
    }
    (*integrator.statistics(), worst)
}

#[test]
fn the_jacobian_is_reused_across_iterations_and_steps() {
    let n = 64;
    assert!(n >= REUSE_MIN_DOF);
    let (s, energy) = run(n, 0.5, &[(0.05, 400)]);
    println!("{s:?}, energy error {energy:e}");
    assert_eq!(s.steps, 400);
    // One residual (one ∇V) per iterate on the separable path; no AD of the action at all.
    assert_eq!(s.potential_gradients, s.system_evaluations);
    assert_eq!(s.potential_gradients, s.newton_iterations + s.steps);
    assert_eq!(s.action_evaluations, 0);
    // Far fewer factorizations than updates: the first one serves the whole run.
    assert_eq!(
        (s.newton_iterations, s.jacobian_factorizations),
        CHAIN_064,
        "{s:?}"
    );
    // The midpoint rule keeps the energy bounded (a modest amplitude: error O(h²)).
    assert!(energy < 1e-3, "energy error {energy:e}");
}

/// Newton updates and factorizations of the reference run above.
const CHAIN_064: (usize, usize) = (401, 1);

#[test]
fn a_new_step_size_or_slow_contraction_gets_a_fresh_jacobian() {
    let n = 64;
    // Changing h invalidates the factored M/h + (h/4)∇²V: one fresh factorization per change.
    let (one_h, _) = run(n, 0.5, &[(0.05, 100)]);
    let (three_h, _) = run(n, 0.5, &[(0.05, 100), (0.04, 100), (0.05, 100)]);
    println!("one h: {one_h:?}\nthree h: {three_h:?}");
    assert!(three_h.jacobian_factorizations >= one_h.jacobian_factorizations + 2);
    assert_eq!(
        (three_h.newton_iterations, three_h.jacobian_factorizations),
        CHAIN_064_THREE_H,
        "{three_h:?}"
    );
    // A large amplitude (strongly nonlinear bonds) and a large step: ∇²V changes fast, the
    // stale Jacobian contracts slowly and is refreshed during the run.
    let (stiff, energy) = run(n, 20.0, &[(0.5, 300)]);
    println!("stiff: {stiff:?}, energy error {energy:e}");
    assert!(stiff.jacobian_factorizations > 1);
    assert!(stiff.jacobian_factorizations < stiff.newton_iterations);
    assert_eq!(
        (stiff.newton_iterations, stiff.jacobian_factorizations),
        CHAIN_064_STIFF,
        "{stiff:?}"
    );
}

/// Newton updates and factorizations of the reference runs above.
const CHAIN_064_THREE_H: (usize, usize) = (302, 3);
const CHAIN_064_STIFF: (usize, usize) = (2704, 48);
