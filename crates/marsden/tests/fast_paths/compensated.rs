//! Compensated summation of the state update (`marsden::integrator::compensated`): the same trajectory as
//! plain summation up to round-off, forces included; the carried errors never leak into a state
//! the integrator did not produce; the explicit path steps aside; constrained problems refuse
//! it. Its effect on long runs is measured in `kepler_high_order.rs` (gauss-4: |ΔL| 1.4e-15
//! instead of 1.6e-11 over 10⁵ steps).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::tight;
use marsden::discrete::rules::Galerkin;
use marsden::error::InputError;
use marsden::systems::{CartesianPendulum, DampedOscillator, Kepler};
use marsden::{
    Error, Initial, Integrator, Midpoint, Problem, Rule, SolveOptions, State, TimeGrid, Trapezoid,
};

fn max_difference(a: &State, b: &State) -> f64 {
    a.q.iter()
        .chain(&a.p)
        .zip(b.q.iter().chain(&b.p))
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// R12's damped oscillator (`q̈ = −q − 0.1 q̇`) with gauss-2, whose forces act on all three
/// control points: the momentum increment must carry `Σ f_j`, else `p` would be off by the
/// impulse of the damping (about 0.01 per step here). Compensated and plain runs agree to
/// round-off over 1000 steps.
#[test]
fn forced_runs_agree_with_plain_summation_r12() {
    let osc = DampedOscillator::default();
    let grid = TimeGrid::new(0.0, 0.1, 1000).unwrap();
    let problem = Problem::new(osc, Initial::momentum(&[1.0], &[0.0]), grid)
        .unwrap()
        .with_force(osc);
    let rule = Galerkin::gauss(2).unwrap();
    let solve = |compensated| {
        let options = SolveOptions {
            newton: tight(),
            compensated,
            ..SolveOptions::default()
        };
        let trajectory = problem.solve(&rule, &options).unwrap();
        let last = trajectory.len() - 1;
        State {
            t: trajectory.t(last),
            q: trajectory.q(last).to_vec(),
            p: trajectory.p(last).to_vec(),
        }
    };
    let (plain, compensated) = (solve(false), solve(true));
    let difference = max_difference(&plain, &compensated);
    assert!(difference < 1e-13, "difference {difference:e}");
    // The run is damped: the final amplitude is e^{−0.05·100} of the initial one.
    assert!(plain.q[0].abs() < 0.05, "q = {}", plain.q[0]);
}

/// R12's one-step matrix of the forced midpoint rule, `[[401, 40], [−40, 397]] / 403` for
/// h = 0.1, from a compensated step: the increment's force sum `f_d⁻ + f_d⁺` must be complete.
#[test]
fn compensated_midpoint_step_is_r12s_matrix() {
    let osc = DampedOscillator::default();
    let step = |q: f64, p: f64| {
        let mut integrator = Integrator::new(Midpoint.discretize(osc))
            .with_force(Midpoint.discretize_force(osc, 1))
            .with_options(tight())
            .unwrap()
            .with_compensated_summation(true);
        let mut state = State {
            t: 0.0,
            q: vec![q],
            p: vec![p],
        };
        integrator.step(&mut state, 0.1).unwrap();
        [state.q[0], state.p[0]]
    };
    let (a, b) = (step(1.0, 0.0), step(0.0, 1.0));
    let exact = [[401.0, 40.0], [-40.0, 397.0]];
    for i in 0..2 {
        for (j, column) in [a, b].iter().enumerate() {
            let expected = exact[i][j] / 403.0;
            assert!(
                (column[i] - expected).abs() <= 1e-15,
                "M[{i}][{j}] = {} against {expected}",
                column[i]
            );
        }
    }
}

fn kepler_state() -> State {
    State {
        t: 0.0,
        q: vec![0.4, 0.0],
        p: vec![0.0, 2.0],
    }
}

/// A state the integrator did not produce starts without carried errors: after a jump the
/// compensated integrator gives, bit for bit, the step of a fresh one. (The jump's step has a
/// new `h`, which resets the predictor, so both start Newton from the same guess; a leaked
/// error of up to half an ulp would show in the bits.)
#[test]
fn carried_errors_do_not_leak_into_a_new_state() {
    let rule = Galerkin::gauss(2).unwrap();
    let make = || {
        Integrator::new(rule.discretize(Kepler::default()))
            .with_options(tight())
            .unwrap()
            .with_compensated_summation(true)
    };
    let (mut used, mut fresh) = (make(), make());
    let mut state = kepler_state();
    used.advance(&mut state, 0.01, 100).unwrap();
    let jump = State {
        t: 1.0,
        q: vec![-0.7, 0.3],
        p: vec![0.1, -1.1],
    };
    let (mut a, mut b) = (jump.clone(), jump);
    used.step(&mut a, 0.02).unwrap();
    fresh.step(&mut b, 0.02).unwrap();
    assert_eq!(a.q, b.q);
    assert_eq!(a.p, b.p);
}

/// With compensation the trapezoid rule of a separable Lagrangian leaves its explicit run loop
/// (which sums plainly) for Newton's method; the trajectory is the Störmer–Verlet one.
#[test]
fn explicit_path_steps_aside() {
    let make = |compensated| {
        Integrator::new(Trapezoid.discretize(Kepler::default()))
            .with_options(tight())
            .unwrap()
            .with_compensated_summation(compensated)
    };
    let (mut explicit, mut compensated) = (make(false), make(true));
    assert!(explicit.is_explicit() && !compensated.is_explicit());
    assert!(compensated.is_compensated());
    let (mut a, mut b) = (kepler_state(), kepler_state());
    explicit.advance(&mut a, 0.01, 1000).unwrap();
    compensated.advance(&mut b, 0.01, 1000).unwrap();
    assert_eq!(compensated.statistics().explicit_steps, 0);
    let difference = max_difference(&a, &b);
    assert!(difference < 1e-11, "difference {difference:e}");
}

/// A constrained problem refuses compensated summation with an error that names the option.
#[test]
fn constrained_problems_refuse_it() {
    let pendulum = CartesianPendulum::default();
    let grid = TimeGrid::new(0.0, 0.01, 10).unwrap();
    let problem = Problem::new(pendulum, pendulum.initial(1.0, 0.0), grid)
        .unwrap()
        .with_constraint(pendulum)
        .unwrap();
    let options = SolveOptions {
        compensated: true,
        ..SolveOptions::default()
    };
    let failure = problem.solve(&Trapezoid, &options).unwrap_err();
    assert!(
        matches!(
            failure.error,
            Error::Input(InputError::InvalidOption {
                name: "compensated",
                ..
            })
        ),
        "{:?}",
        failure.error
    );
    assert!(
        failure
            .error
            .to_string()
            .contains("unconstrained problems only")
    );
}
