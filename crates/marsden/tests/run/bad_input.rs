//! Bad input is a typed error with a clear message: a singular Lagrangian, NaN initial data, a
//! negative or zero step, a Newton failure (which keeps the trajectory computed so far).
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::error::{InputError, SetupError, StepError, StepFailure};
use marsden::systems::Pendulum;
use marsden::{
    Error, Initial, Integrator, Lagrangian, Midpoint, NewtonOptions, Problem, Rule, Scalar,
    SolveOptions, State, Termination, TimeGrid,
};

/// `L = ½ v₀² + q₀ v₁`: linear in v₁, so `∂²L/∂v²` is singular everywhere.
#[derive(Debug)]
struct Degenerate;
impl Lagrangian for Degenerate {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        v[0] * v[0] * 0.5 + q[0] * v[1]
    }
}

fn grid() -> TimeGrid {
    TimeGrid::new(0.0, 0.1, 10).unwrap()
}

#[test]
fn singular_lagrangian_is_reported_with_the_state() {
    let err = Problem::new(
        Degenerate,
        Initial::velocity(&[0.5, 0.0], &[1.0, 2.0]),
        grid(),
    )
    .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::SingularLagrangian { .. })),
        "{err:?}"
    );
    let msg = err.to_string();
    assert!(
        msg.contains("singular") && msg.contains("q = [0.5, 0.0]") && msg.contains("∂²L/∂v²"),
        "{msg}"
    );
    // Given momenta, the inverse Legendre transform fails the same way.
    let err = Problem::new(
        Degenerate,
        Initial::momentum(&[0.5, 0.0], &[1.0, 0.5]),
        grid(),
    )
    .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::SingularLagrangian { .. })),
        "{err:?}"
    );
}

#[test]
fn nan_and_wrong_length_initial_data_are_named() {
    let err = Problem::new(
        Pendulum::default(),
        Initial::velocity(&[f64::NAN], &[0.0]),
        grid(),
    )
    .unwrap_err();
    assert!(
        matches!(err, Error::Input(InputError::NonFinite { what: "q0", index: 0, value }) if value.is_nan())
    );
    assert_eq!(err.to_string(), "q0[0] is not finite (NaN)");
    let err = Problem::new(
        Pendulum::default(),
        Initial::momentum(&[1.0], &[f64::INFINITY]),
        grid(),
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "p0[0] is not finite (inf)");
    let err = Problem::new(
        Pendulum::default(),
        Initial::velocity(&[1.0, 2.0], &[0.0]),
        grid(),
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "q0 has length 2, expected 1");
}

#[test]
fn zero_negative_and_nan_steps_are_rejected() {
    for h in [0.0, -0.1, f64::NAN, f64::INFINITY] {
        let err = TimeGrid::new(0.0, h, 10).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("the time step h must be positive and finite"),
            "{err}"
        );
    }
    assert!(
        TimeGrid::until(1.0, 0.5, 0.1)
            .unwrap_err()
            .to_string()
            .contains("must be after t0")
    );
    // The low-level stepper accepts negative h (backward runs) but never zero.
    let mut integrator = Integrator::new(Midpoint.discretize(Pendulum::default()));
    let mut s = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![0.0],
    };
    assert_eq!(
        integrator.step(&mut s, 0.0).unwrap_err(),
        Error::Input(InputError::InvalidStep { h: 0.0 })
    );
    assert!(integrator.step(&mut s, -0.1).is_ok());
}

#[test]
fn invalid_newton_options_are_rejected() {
    let bad = NewtonOptions {
        residual_tolerance: -1.0,
        ..NewtonOptions::default()
    };
    let err = Integrator::new(Midpoint.discretize(Pendulum::default()))
        .with_options(bad)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "invalid option residual_tolerance = -1: must be positive and finite"
    );
}

/// A particle whose mass `1 − q` vanishes at q = 1, reached at t = 2/3 from (q, v) = (0, 1):
/// the run must fail there, keep the steps before, and say where.
#[derive(Debug)]
struct VanishingMass;
impl Lagrangian for VanishingMass {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (-q[0] + 1.0) * v[0] * v[0] * 0.5
    }
}

#[test]
fn newton_failure_keeps_the_trajectory_up_to_the_failure() {
    let grid = TimeGrid::new(0.0, 0.02, 100).unwrap();
    let problem = Problem::new(VanishingMass, Initial::velocity(&[0.0], &[1.0]), grid).unwrap();
    let failure = problem
        .solve(&Midpoint, &SolveOptions::default())
        .unwrap_err();
    let traj = &failure.trajectory;
    assert!(
        traj.steps >= 20 && traj.steps < 40,
        "failed after {} steps",
        traj.steps
    );
    assert!(matches!(traj.termination, Termination::Failed(_)));
    let last = traj.len() - 1;
    assert_eq!(
        traj.step_indices[last], traj.steps,
        "the last good state is kept"
    );
    assert!(traj.q(last)[0] < 1.0 && traj.q(last)[0].is_finite());
    let msg = failure.to_string();
    assert!(
        msg.contains(&format!("step {}", traj.steps)) && msg.contains("steps completed"),
        "{msg}"
    );
}

#[test]
fn exhausted_newton_budget_is_a_typed_error_with_the_numbers() {
    let options = NewtonOptions {
        max_iterations: 1,
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    let mut integrator = Integrator::new(Midpoint.discretize(Pendulum::default()))
        .with_options(options)
        .unwrap();
    let mut s = State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    };
    let err = integrator.step(&mut s, 0.5).unwrap_err();
    match &err {
        Error::Step(StepFailure {
            step,
            t,
            cause:
                StepError::NewtonDidNotConverge {
                    iterations,
                    residual,
                    tolerance,
                },
        }) => {
            assert_eq!((*step, *t, *iterations, *tolerance), (0, 0.0, 1, 1e-15));
            assert!(*residual > 1e-15);
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(
        err.to_string()
            .starts_with("Newton's method did not converge in step 0 (t = 0)")
    );
    assert_eq!(
        s,
        State {
            t: 0.0,
            q: vec![1.5],
            p: vec![0.0]
        },
        "state unchanged on failure"
    );
}
