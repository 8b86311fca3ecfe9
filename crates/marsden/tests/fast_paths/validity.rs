//! The structure-aware fast paths (explicit Störmer–Verlet for the trapezoid rule,
//! `M/h + (h/4)∇²V` Newton for the midpoint rule, [`marsden::separable::explicit`], [`marsden::separable::alpha`])
//! solve the *unforced, unconstrained* step only. With forces or constraints the integrator must
//! not take them: the work counters `explicit_steps` and `potential_gradients` stay zero, the
//! forces and constraints act (energy decays, `φ(q_k) = 0`), and the result is the general
//! path's (`with_fast_paths(false)`).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::forces::LinearDamping;
use marsden::holonomic::DistanceConstraints;
use marsden::systems::{Chain, Kepler, NBody};
use marsden::{
    Constraint, DiscreteAction, DiscreteForce, Integrator, Midpoint, NewtonOptions, Rule, State,
    Statistics, Trapezoid, Unconstrained,
};

/// Runs `steps` steps; returns the flattened trajectory and the statistics.
fn run<A, F, C>(
    integrator: Integrator<A, F, C>,
    start: &State,
    h: f64,
    steps: usize,
) -> (Vec<State>, Statistics)
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
{
    let options = NewtonOptions {
        residual_tolerance: 1e-14,
        ..NewtonOptions::default()
    };
    let mut integrator = integrator.with_options(options).unwrap();
    let mut s = start.clone();
    let mut out = Vec::with_capacity(steps);
    for _ in 0..steps {
        integrator.step(&mut s, h).unwrap();
        out.push(s.clone());
    }
    (out, *integrator.statistics())
}

fn max_difference(a: &[State], b: &[State]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| {
            let dq = x.q.iter().zip(&y.q).map(|(u, v)| (u - v).abs());
            let dp = x.p.iter().zip(&y.p).map(|(u, v)| (u - v).abs());
            dq.chain(dp).collect::<Vec<_>>()
        })
        .fold(0.0, f64::max)
}

fn chain_start(n: usize) -> State {
    let q = (0..n)
        .map(|i| 0.5 * (std::f64::consts::PI * (i + 1) as f64 / (n + 1) as f64).sin())
        .collect();
    State {
        t: 0.0,
        q,
        p: vec![0.0; n],
    }
}

/// A separable system with damping: neither separable fast path is taken, the damping acts.
#[test]
fn forces_keep_the_separable_fast_paths_off() {
    let n = 40;
    let chain = Chain::new(n);
    // Started at rest in the lowest mode (ω = 2 sin(π/82) ≈ 0.077, period ≈ 82) the chain
    // barely moves over t = 10 and the damping would remove little; start it instead with its
    // velocities in that mode, all energy kinetic.
    let at_rest = chain_start(n);
    let start = State {
        t: 0.0,
        q: vec![0.0; n],
        p: at_rest.q.clone(),
    };
    let e0 = chain.energy(&start.q, &start.p);
    for (name, rule) in [("midpoint", 0), ("trapezoid", 1)] {
        let damping = LinearDamping::uniform(0.2).unwrap();
        let ((fast, stats), (slow, _)) = if rule == 0 {
            let f = Midpoint.discretize_force(damping, n);
            let i = |fast| {
                Integrator::new(Midpoint.discretize(chain))
                    .with_force(f.clone())
                    .with_fast_paths(fast)
            };
            (
                run(i(true), &start, 0.05, 200),
                run(i(false), &start, 0.05, 200),
            )
        } else {
            let f = Trapezoid.discretize_force(damping, n);
            let i = |fast| {
                Integrator::new(Trapezoid.discretize(chain))
                    .with_force(f.clone())
                    .with_fast_paths(fast)
            };
            (
                run(i(true), &start, 0.05, 200),
                run(i(false), &start, 0.05, 200),
            )
        };
        assert_eq!(
            (stats.explicit_steps, stats.potential_gradients),
            (0, 0),
            "{name}: a fast path was taken with a force: {stats:?}"
        );
        assert!(stats.newton_iterations >= 200, "{name}: {stats:?}");
        // n = 40 > 4: both runs take the general path, so they agree bit for bit.
        assert_eq!(max_difference(&fast, &slow), 0.0, "{name}");
        // The damping acts. In the linear regime the mode is the oscillator
        // ẍ + c ẋ + ω² x = 0, overdamped (c = 0.2 > 2ω): with x(0) = 0, ẋ(0) = 1 the roots
        // r± = (−c ± √(c² − 4ω²))/2 give x = (e^{r₊t} − e^{r₋t})/(r₊ − r₋) and at t = 10
        // E/E₀ = ẋ² + ω² x² = 0.0935; the quartic bonds (|Δq| ≲ 0.15) and h² change it little.
        let last = fast.last().unwrap();
        let ratio = chain.energy(&last.q, &last.p) / e0;
        let omega = 2.0 * (std::f64::consts::PI / 82.0).sin();
        let root = (0.04 - 4.0 * omega * omega).sqrt();
        let (rp, rm) = ((-0.2 + root) / 2.0, (-0.2 - root) / 2.0);
        let x = ((rp * 10.0).exp() - (rm * 10.0).exp()) / (rp - rm);
        let xdot = (rp * (rp * 10.0).exp() - rm * (rm * 10.0).exp()) / (rp - rm);
        let linear = xdot * xdot + omega * omega * x * x;
        println!("{name}: energy ratio {ratio} (linear mode: {linear})");
        assert!(
            (ratio / linear - 1.0).abs() < 0.03,
            "{name}: energy ratio {ratio}"
        );
    }
}

/// A small separable system (n = 2) with damping: the statically sized Newton step handles the
/// force; the explicit Verlet step (which would ignore it) is not taken.
#[test]
fn forces_on_small_systems_take_the_forced_newton_step() {
    let (q, p) = Kepler::pericentre(0.6);
    let start = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    let f = Trapezoid.discretize_force(LinearDamping::uniform(0.1).unwrap(), 2);
    let i = |fast| {
        Integrator::new(Trapezoid.discretize(Kepler::default()))
            .with_force(f.clone())
            .with_fast_paths(fast)
    };
    let (fast, stats) = run(i(true), &start, 0.01, 500);
    let (slow, _) = run(i(false), &start, 0.01, 500);
    assert_eq!((stats.explicit_steps, stats.potential_gradients), (0, 0));
    let d = max_difference(&fast, &slow);
    assert!(d <= 1e-12, "small and general forced paths differ by {d:e}");
    // Unforced Verlet conserves energy to 7.4e-4 (R10, verlet.c); damping removes energy.
    let kepler = Kepler::default();
    let e =
        |s: &State| 0.5 * (s.p[0] * s.p[0] + s.p[1] * s.p[1]) - kepler.mu / s.q[0].hypot(s.q[1]);
    assert!(e(fast.last().unwrap()) < e(&start) - 0.01);
}

/// Separable systems with holonomic constraints: the fast paths are not taken, and the
/// constraints hold at every step.
#[test]
fn constraints_keep_the_separable_fast_paths_off() {
    // Kepler held on the circle |q| = 0.4 through its pericentre (n = 2: the static SHAKE step).
    let (q, p) = Kepler::pericentre(0.6);
    let start = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    let circle = DistanceConstraints::new(2)
        .anchor(0, &[0.0, 0.0], 0.4)
        .unwrap();
    for rule in [0, 1] {
        fn constrained<A: DiscreteAction>(
            action: A,
            circle: &DistanceConstraints,
            start: &State,
            fast: bool,
        ) -> (Vec<State>, Statistics) {
            let i = Integrator::new(action)
                .with_constraint(circle.clone())
                .with_fast_paths(fast);
            run(i, start, 0.01, 300)
        }
        let make = |fast: bool| {
            if rule == 0 {
                constrained(
                    Trapezoid.discretize(Kepler::default()),
                    &circle,
                    &start,
                    fast,
                )
            } else {
                constrained(
                    Midpoint.discretize(Kepler::default()),
                    &circle,
                    &start,
                    fast,
                )
            }
        };
        let ((fast, stats), (slow, _)) = (make(true), make(false));
        assert_eq!(
            (stats.explicit_steps, stats.potential_gradients),
            (0, 0),
            "rule {rule}: {stats:?}"
        );
        let worst = fast
            .iter()
            .map(|s| (s.q[0].hypot(s.q[1]) - 0.4).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 1e-13, "rule {rule}: |q| − 0.4 up to {worst:e}");
        let d = max_difference(&fast, &slow);
        assert!(
            d <= 1e-11,
            "rule {rule}: small and general SHAKE differ by {d:e}"
        );
    }
}

/// Three gravitating bodies with one rod (n = 9: the general constrained path).
#[test]
fn a_constrained_nbody_problem_takes_the_general_path() {
    let mut system = NBody::new(vec![1.0, 1e-3, 2e-3]);
    system.softening = 0.01;
    let q = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.1, -1.5, 0.2, 0.0];
    let p = vec![0.0, -3e-3, 0.0, 0.0, 1e-3, 0.0, 2e-4, -1.6e-3, 0.0];
    let start = State { t: 0.0, q, p };
    let d = 1.01_f64.sqrt();
    let rod = DistanceConstraints::new(3).link(0, 1, d).unwrap();
    let i = |fast| {
        Integrator::new(Trapezoid.discretize(system.clone()))
            .with_constraint(rod.clone())
            .with_fast_paths(fast)
    };
    let (fast, stats) = run(i(true), &start, 0.01, 200);
    let (slow, _) = run(i(false), &start, 0.01, 200);
    assert_eq!((stats.explicit_steps, stats.potential_gradients), (0, 0));
    assert_eq!(max_difference(&fast, &slow), 0.0);
    let worst = fast
        .iter()
        .map(|s| {
            let r: f64 = (0..3).map(|a| (s.q[3 + a] - s.q[a]).powi(2)).sum();
            (r.sqrt() - d).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst <= 1e-12, "rod length off by {worst:e}");
    // Without the rod the same integrator takes the explicit path.
    let free = Integrator::new(Trapezoid.discretize(system)).with_constraint(Unconstrained);
    let (_, stats) = run(free, &start, 0.01, 10);
    assert_eq!(stats.explicit_steps, 10);
}
