//! The statically sized step (`marsden::integrator::small::unconstrained`) and the general path solve the same equations:
//! both must give the same trajectory to round-off, for every rule and with a force.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::systems::{DoublePendulum, HenonHeiles, Kepler, Pendulum};
use marsden::{
    DiscreteAction, DiscreteForce, Force, GeneralizedMidpoint, Integrator, Lagrangian, Midpoint,
    NoForce, Rule, Scalar, State, SymmetrizedMidpoint, Trapezoid,
};

fn trajectory<A: DiscreteAction, F: DiscreteForce>(
    action: A,
    force: F,
    start: &State,
    h: f64,
    fast: bool,
) -> Vec<f64> {
    trajectory_in(action, force, start, h, fast, true)
}

/// 1000 steps with the fast paths on or off and the wide instructions (`marsden::integrator::small::dispatch`) on
/// or off.
fn trajectory_in<A: DiscreteAction, F: DiscreteForce>(
    action: A,
    force: F,
    start: &State,
    h: f64,
    fast: bool,
    wide: bool,
) -> Vec<f64> {
    let mut integrator = Integrator::new(action)
        .with_force(force)
        .with_fast_paths(fast)
        .with_wide_instructions(wide);
    let mut s = start.clone();
    let mut out = Vec::new();
    // 1000 steps: long enough for many Newton solves, short enough that a drag force does not
    // spiral the Kepler orbit into its singularity.
    for _ in 0..1000 {
        integrator.step(&mut s, h).unwrap();
        out.extend(s.q.iter().chain(&s.p));
    }
    out
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn check<R: Rule, F: Force + Clone>(rule: R, start: State, h: f64, force: F) {
    let n = start.q.len();
    let run = |fast| match n {
        1 => trajectory(
            rule.discretize(Pendulum::default()),
            rule.discretize_force(force.clone(), n),
            &start,
            h,
            fast,
        ),
        _ => trajectory(
            rule.discretize(Kepler::default()),
            rule.discretize_force(force.clone(), n),
            &start,
            h,
            fast,
        ),
    };
    let d = max_difference(&run(true), &run(false));
    assert!(
        d <= 1e-13,
        "{}: static vs general differ by {d:e}",
        rule.name()
    );
}

#[derive(Clone)]
struct Drag;
impl Force for Drag {
    fn force<S: Scalar>(&self, t: S, _q: &[S], v: &[S], out: &mut [S]) {
        for (o, vi) in out.iter_mut().zip(v) {
            *o = -*vi * 0.05 + t.sin() * 0.01;
        }
    }
}

#[test]
fn static_and_general_paths_agree_for_every_rule() {
    let pendulum = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    let (q, p) = Kepler::pericentre(0.6);
    let kepler = State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    };
    for (start, h) in [(pendulum, 0.05), (kepler, 0.005)] {
        check(Midpoint, start.clone(), h, NoForce);
        check(Trapezoid, start.clone(), h, NoForce);
        check(
            GeneralizedMidpoint { alpha: 0.3 },
            start.clone(),
            h,
            NoForce,
        );
        check(
            SymmetrizedMidpoint { alpha: 0.2 },
            start.clone(),
            h,
            NoForce,
        );
        check(Midpoint, start.clone(), h, Drag);
        check(Trapezoid, start, h, Drag);
    }
}

#[test]
fn static_and_general_paths_agree_for_two_degrees_of_freedom() {
    let start = State {
        t: 0.0,
        q: vec![1.0, 0.5],
        p: vec![0.0, 0.0],
    };
    let a = trajectory(
        Midpoint.discretize(DoublePendulum::default()),
        NoForce,
        &start,
        0.01,
        true,
    );
    let b = trajectory(
        Midpoint.discretize(DoublePendulum::default()),
        NoForce,
        &start,
        0.01,
        false,
    );
    assert!(max_difference(&a, &b) <= 1e-13);
    // With a force: its ε₂ parts enter the Jacobian of the n = 2 kernel.
    let forced = |fast| {
        trajectory(
            Midpoint.discretize(DoublePendulum::default()),
            Midpoint.discretize_force(Drag, 2),
            &start,
            0.01,
            fast,
        )
    };
    assert!(max_difference(&forced(true), &forced(false)) <= 1e-13);
    let start = State {
        t: 0.0,
        q: vec![0.1, -0.2],
        p: vec![0.3, 0.25],
    };
    let a = trajectory(
        Trapezoid.discretize(HenonHeiles::default()),
        NoForce,
        &start,
        0.1,
        true,
    );
    let b = trajectory(
        Trapezoid.discretize(HenonHeiles::default()),
        NoForce,
        &start,
        0.1,
        false,
    );
    assert!(max_difference(&a, &b) <= 1e-13);
}

/// `n` pendulum-like angles with a configuration-dependent mass:
/// `L = ½ Σ vᵢ² + 0.3 Σ_{i<j} vᵢ vⱼ cos(qᵢ − qⱼ) + Σ cos qᵢ` (positive definite for n ≤ 4:
/// the off-diagonal row sums stay below 0.9). Not separable, so the AD kernels take it.
#[derive(Clone, Copy)]
struct Coupled(usize);

impl Lagrangian for Coupled {
    fn dof(&self) -> usize {
        self.0
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let mut l = S::from(0.0);
        for i in 0..self.0 {
            l += v[i] * v[i] * 0.5 + q[i].cos();
            for j in i + 1..self.0 {
                l += v[i] * v[j] * (q[i] - q[j]).cos() * 0.3;
            }
        }
        l
    }
}

/// The statically sized kernels for n = 3 and 4 (fixed-size hyper-duals, `small_dual`) against
/// the general path, free and with a force.
#[test]
fn static_and_general_paths_agree_for_three_and_four_coupled_angles() {
    for n in [3, 4] {
        let start = State {
            t: 0.0,
            q: (0..n).map(|i| 0.4 - 0.3 * i as f64).collect(),
            p: (0..n).map(|i| 0.1 * i as f64).collect(),
        };
        let free = |fast| trajectory(Midpoint.discretize(Coupled(n)), NoForce, &start, 0.01, fast);
        let d = max_difference(&free(true), &free(false));
        assert!(d <= 1e-13, "n = {n}: static vs general differ by {d:e}");
        let forced = |fast| {
            trajectory(
                Midpoint.discretize(Coupled(n)),
                Midpoint.discretize_force(Drag, n),
                &start,
                0.01,
                fast,
            )
        };
        let d = max_difference(&forced(true), &forced(false));
        assert!(
            d <= 1e-13,
            "n = {n}, forced: static vs general differ by {d:e}"
        );
    }
}

/// The x86-64-v3 copy of the small kernels (`marsden::integrator::small::dispatch`) and the baseline code give the
/// same bits: no fused multiply–adds, no reassociation. Forced pendulum (n = 1), double pendulum
/// free and forced (n = 2), three and four coupled angles (a user's Lagrangian, forced). On a
/// CPU without AVX2 both runs take the baseline code and the test checks nothing new.
#[test]
fn wide_and_baseline_instructions_give_the_same_bits() {
    fn same<A: DiscreteAction + Clone, F: DiscreteForce + Clone>(
        name: &str,
        action: A,
        force: F,
        start: &State,
    ) {
        let run = |wide| trajectory_in(action.clone(), force.clone(), start, 0.01, true, wide);
        let (wide, baseline) = (run(true), run(false));
        let first = wide
            .iter()
            .zip(&baseline)
            .position(|(a, b)| a.to_bits() != b.to_bits());
        assert_eq!(
            first, None,
            "{name}: the copies differ (first at value {first:?})"
        );
    }
    let state = |q: Vec<f64>| State {
        t: 0.0,
        p: vec![0.1; q.len()],
        q,
    };
    let m = Midpoint;
    let pendulum = m.discretize(Pendulum::default());
    let drag = m.discretize_force(Drag, 1);
    same("forced pendulum", pendulum, drag, &state(vec![1.5]));
    let double = m.discretize(DoublePendulum::default());
    same(
        "double pendulum",
        double.clone(),
        NoForce,
        &state(vec![1.0, 0.5]),
    );
    let drag = m.discretize_force(Drag, 2);
    same(
        "forced double pendulum",
        double,
        drag,
        &state(vec![1.0, 0.5]),
    );
    for n in [3, 4] {
        let (coupled, drag) = (m.discretize(Coupled(n)), m.discretize_force(Drag, n));
        let q = (0..n).map(|i| 0.4 - 0.3 * i as f64).collect();
        same(
            &format!("{n} coupled angles, forced"),
            coupled,
            drag,
            &state(q),
        );
    }
}
