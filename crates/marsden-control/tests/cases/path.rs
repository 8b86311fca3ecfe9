//! Path inequalities `g(t, q, q̇, u) ≤ 0`: the Bryson–Denham problem with its state constraint
//! written as a path inequality, and a control bound written as two, against the simple
//! bounds that give the same optimum.

use marsden::systems::FreeFall;
use marsden::{Midpoint, Scalar};
use marsden_control::{
    Boundary, Effort, Horizon, InputMap, OptimalControl, PathConstraint, SqpOptions, Status,
};

/// `x − ℓ ≤ 0`.
struct Ceiling(f64);

impl PathConstraint for Ceiling {
    fn count(&self) -> usize {
        1
    }
    fn eval<S: Scalar>(&self, _t: S, q: &[S], _v: &[S], _u: &[S], out: &mut [S]) {
        out[0] = q[0] - self.0;
    }
}

/// `u − a ≤ 0` and `−u − a ≤ 0`.
struct Saturation(f64);

impl PathConstraint for Saturation {
    fn count(&self) -> usize {
        2
    }
    fn eval<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], u: &[S], out: &mut [S]) {
        out[0] = u[0] - self.0;
        out[1] = -u[0] - self.0;
    }
}

fn double_integrator(
    steps: usize,
    start: Boundary,
    end: Boundary,
) -> OptimalControl<FreeFall, InputMap, Effort> {
    let system = FreeFall { m: 1.0, g: 0.0 };
    OptimalControl::new(
        system,
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 1.0,
            steps,
        },
        start,
        end,
    )
    .unwrap()
}

/// The Bryson–Denham problem ([BH75] §3.11) with `x ≤ ℓ = 1/9` as the path inequality
/// `x − ℓ ≤ 0` at each step's midpoint: the continuous optimum costs `J = 4/(9ℓ) = 4`, with
/// the constraint active on `t ∈ [⅓, ⅔]`. The discrete optimum approaches 4 at order 2, the
/// inequality holds at every midpoint, and its multipliers are nonnegative and vanish off the
/// active arc.
#[test]
fn bryson_denham_path_inequality_approaches_four() {
    let ell = 1.0 / 9.0;
    let mut errors = Vec::new();
    for steps in [40, 80, 160] {
        let ends = (
            Boundary::velocity(&[0.0], &[1.0]),
            Boundary::velocity(&[0.0], &[-1.0]),
        );
        let problem = double_integrator(steps, ends.0, ends.1).with_path(Ceiling(ell));
        let s = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
        assert_eq!(s.status, Status::Converged, "N = {steps}");
        let midpoints: Vec<f64> = s.q.windows(2).map(|w| 0.5 * (w[0][0] + w[1][0])).collect();
        let highest = midpoints.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert!(highest <= ell + 1e-10, "x reaches {highest} at a midpoint");
        let h = 1.0 / steps as f64;
        let mut active = Vec::new();
        for (k, (x, mu)) in midpoints.iter().zip(&s.path_multipliers).enumerate() {
            assert!(mu[0] >= -1e-10, "multiplier {} at step {k}", mu[0]);
            let t = (k as f64 + 0.5) * h;
            if ell - x <= 1e-9 {
                active.push(t);
            } else {
                assert!(
                    mu[0].abs() <= 1e-7,
                    "inactive at t = {t} with multiplier {}",
                    mu[0]
                );
            }
        }
        let (first, last) = (active[0], active[active.len() - 1]);
        println!(
            "Bryson–Denham (path) N = {steps}: cost {:.6}, {} iterations, active on \
             [{first:.3}, {last:.3}]",
            s.cost, s.iterations
        );
        assert!((first - 1.0 / 3.0).abs() <= 2.0 * h && (last - 2.0 / 3.0).abs() <= 2.0 * h);
        errors.push((s.cost - 4.0).abs());
    }
    println!("Bryson–Denham (path) |J − 4|: {errors:?}");
    for pair in errors.windows(2) {
        let ratio = pair[0] / pair[1];
        assert!((3.6..4.4).contains(&ratio), "{errors:?}");
    }
}

/// `|u| ≤ 4.5` written as two path inequalities gives the optimum of the same simple bound
/// (the double integrator of the control-bound test): the same cost and controls to the
/// solver's tolerance, and the active inequality's multiplier equal to the bound's, which the
/// KKT conditions of both programs make `|∂ℒ/∂u|` there.
#[test]
fn a_control_bound_as_path_inequalities_is_the_bound() {
    let a = 4.5;
    let options = SqpOptions::default();
    let rest = || (Boundary::rest(&[0.0]), Boundary::rest(&[1.0]));
    let (s0, e0) = rest();
    let bounded = double_integrator(40, s0, e0)
        .with_control_bounds(&[-a], &[a])
        .unwrap()
        .solve(&Midpoint, &options)
        .unwrap();
    let (s1, e1) = rest();
    let path = double_integrator(40, s1, e1)
        .with_path(Saturation(a))
        .solve(&Midpoint, &options)
        .unwrap();
    assert_eq!(
        (&bounded.status, &path.status),
        (&Status::Converged, &Status::Converged)
    );
    println!(
        "bound: cost {:.12} ({} iterations); path: cost {:.12} ({} iterations)",
        bounded.cost, bounded.iterations, path.cost, path.iterations
    );
    assert!((bounded.cost - path.cost).abs() <= 1e-9 * bounded.cost);
    let gap = (bounded.u.iter().zip(&path.u))
        .map(|(a, b)| (a[0] - b[0]).abs())
        .fold(0.0, f64::max);
    assert!(gap <= 1e-6, "controls differ by {gap:e}");
    let active = path.u.iter().filter(|u| a - u[0].abs() <= 1e-7).count();
    assert!(active >= 16, "{active} active steps");
    // Where u = a the upper inequality is active with a positive multiplier, and vice versa.
    for (u, mu) in path.u.iter().zip(&path.path_multipliers) {
        assert!(mu.iter().all(|&m| m >= -1e-10), "{mu:?}");
        match (a - u[0] <= 1e-7, a + u[0] <= 1e-7) {
            (true, _) => assert!(mu[0] > 1e-3 && mu[1].abs() <= 1e-7, "u {} {mu:?}", u[0]),
            (_, true) => assert!(mu[1] > 1e-3 && mu[0].abs() <= 1e-7, "u {} {mu:?}", u[0]),
            _ => assert!(mu[0].abs() + mu[1].abs() <= 1e-7, "u {} {mu:?}", u[0]),
        }
    }
}

/// `u ≤ 1` and `u ≥ 2` cannot both hold: the solve ends infeasible with a checked certificate
/// that leans on both inequalities (and on no bound).
#[test]
fn contradictory_path_inequalities_are_reported_infeasible() {
    struct Contradiction;
    impl PathConstraint for Contradiction {
        fn count(&self) -> usize {
            2
        }
        fn eval<S: Scalar>(&self, _t: S, _q: &[S], _v: &[S], u: &[S], out: &mut [S]) {
            out[0] = u[0] - 1.0;
            out[1] = -u[0] + 2.0;
        }
    }
    let s = double_integrator(10, Boundary::rest(&[0.0]), Boundary::rest(&[1.0]))
        .with_path(Contradiction)
        .solve(&Midpoint, &SqpOptions::default())
        .unwrap();
    let Status::Infeasible(infeasibility) = &s.status else {
        panic!("status {:?}", s.status);
    };
    println!("{infeasibility:?}, violation {:.3}", s.constraint_violation);
    assert_eq!(infeasibility.path, [0, 1]);
    assert!(infeasibility.controls.is_empty() && infeasibility.coordinates.is_empty());
    assert!(s.constraint_violation >= 0.5 - 1e-9);
}

/// `|θ̇| ≤ ω`.
struct SpeedLimit(f64);

impl PathConstraint for SpeedLimit {
    fn count(&self) -> usize {
        2
    }
    fn eval<S: Scalar>(&self, _t: S, _q: &[S], v: &[S], _u: &[S], out: &mut [S]) {
        out[0] = v[0] - self.0;
        out[1] = -v[0] - self.0;
    }
}

/// The pendulum swing-up of [`super::swing_up`] (N = 120) with a speed limit `|θ̇| ≤ 0.9` on
/// each step's secant, below the unconstrained optimum's top speed: the solve converges (a
/// nonlinear problem whose active set changes along the iteration), the limit holds at every
/// step, it is active somewhere, the cost is higher than without it, and the trajectory still
/// satisfies the forced discrete Euler–Lagrange equations to the tolerance.
#[test]
fn swing_up_with_a_speed_limit_converges_within_it() {
    let free = super::swing_up::swing_up(120)
        .solve(&Midpoint, &SqpOptions::default())
        .unwrap();
    let h = 6.0 / 120.0;
    let top = |q: &[Vec<f64>]| {
        (q.windows(2).map(|w| ((w[1][0] - w[0][0]) / h).abs())).fold(0.0, f64::max)
    };
    let limit = 0.9;
    let limited = super::swing_up::swing_up(120)
        .with_path(SpeedLimit(limit))
        .solve(&Midpoint, &SqpOptions::default())
        .unwrap();
    println!(
        "swing-up: free cost {:.6}, top speed {:.4}; limited cost {:.6}, top speed {:.9}, {} \
         iterations, violation {:.1e}",
        free.cost,
        top(&free.q),
        limited.cost,
        top(&limited.q),
        limited.iterations,
        limited.constraint_violation
    );
    assert!(top(&free.q) > limit + 0.05);
    assert_eq!(limited.status, Status::Converged);
    assert!(top(&limited.q) <= limit + 1e-9);
    let active = (limited.q.windows(2))
        .filter(|w| limit - ((w[1][0] - w[0][0]) / h).abs() <= 1e-7)
        .count();
    assert!(active >= 1);
    assert!(limited.cost > free.cost);
    assert!(limited.constraint_violation <= 1e-10);
}
