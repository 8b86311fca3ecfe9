//! Bad constrained input is refused with typed errors that carry the numbers: an unsatisfiable
//! constraint, redundant constraints (rank-deficient `Dφ`), initial positions off the manifold,
//! initial velocities or momenta not tangent to it, and a failing momentum projection. The
//! explicit projections repair initial data.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use crate::common::tight;
use marsden::error::{SetupError, StepError, StepFailure};
use marsden::holonomic::{self, project_position};
use marsden::systems::{CartesianPendulum, SphericalPendulum};
use marsden::{
    Constraint, Error, Initial, Integrator, Midpoint, Problem, Rule, Scalar, State, TimeGrid,
};

/// `φ(q) = ½(|q|² + 1)`: never zero.
#[derive(Debug)]
struct Unsatisfiable;

impl Constraint for Unsatisfiable {
    fn count(&self) -> usize {
        1
    }
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] + 1.0) * 0.5;
    }
}

/// The unit circle twice: `φ₁ = ½(|q|² − 1)`, `φ₂ = |q|² − 1 = 2φ₁`.
#[derive(Debug)]
struct Doubled;

impl Constraint for Doubled {
    fn count(&self) -> usize {
        2
    }
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let r2 = q[0] * q[0] + q[1] * q[1];
        out[0] = (r2 - 1.0) * 0.5;
        out[1] = r2 - 1.0;
    }
}

fn grid() -> TimeGrid {
    TimeGrid::new(0.0, 0.05, 10).unwrap()
}

fn pendulum_problem(initial: Initial) -> Problem<CartesianPendulum> {
    Problem::new(CartesianPendulum::default(), initial, grid()).unwrap()
}

#[test]
fn unsatisfiable_constraint_is_refused_at_the_start_by_projection_and_by_the_step() {
    // At the problem: q0 = (0, −1) gives φ = 1.
    let err = pendulum_problem(Initial::velocity(&[0.0, -1.0], &[0.0, 0.0]))
        .with_constraint(Unsatisfiable)
        .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::InitialPositionOffConstraint { index: 0, residual, .. }) if residual == 1.0),
        "{err:?}"
    );
    let message = err.to_string();
    eprintln!("{message}");
    assert!(
        message.contains("violate constraint 0: |φ_0(q0)| = 1.000e0"),
        "{message}"
    );
    // The explicit projection cannot find a point with φ = 0 either.
    let err = project_position(&Unsatisfiable, &[0.0, -1.0]).unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::PositionProjectionFailed { residual, .. }) if residual > 0.4),
        "{err:?}"
    );
    let message = err.to_string();
    eprintln!("{message}");
    assert!(
        message.contains("could not project q onto the constraint manifold"),
        "{message}"
    );
    assert!(message.contains("unsatisfiable"), "{message}");
    // An integrator built by hand (no initial check) fails in its first step with the same
    // diagnosis instead of a bare Newton failure.
    let mut integrator = Integrator::new(Midpoint.discretize(CartesianPendulum::default()))
        .with_constraint(Unsatisfiable)
        .with_options(tight())
        .unwrap();
    let mut state = State {
        t: 0.0,
        q: vec![0.0, -1.0],
        p: vec![0.3, 0.0],
    };
    let err = integrator.step(&mut state, 0.05).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Step(StepFailure {
                step: 0,
                cause: StepError::ConstraintNotSatisfied { index: 0, .. },
                ..
            })
        ),
        "{err:?}"
    );
    let message = err.to_string();
    eprintln!("{message}");
    assert!(
        message.contains("constraint 0 could not be satisfied in step 0"),
        "{message}"
    );
    assert!(message.contains("is it satisfiable?"), "{message}");
    assert_eq!(
        state.q,
        [0.0, -1.0],
        "state must be unchanged after a failed step"
    );
}

#[test]
fn redundant_constraints_are_refused_with_their_rank() {
    let err = pendulum_problem(Initial::velocity(&[0.0, -1.0], &[0.5, 0.0]))
        .with_constraint(Doubled)
        .unwrap_err();
    match &err {
        Error::Setup(SetupError::RedundantConstraints {
            count,
            rank,
            singular_values,
            ..
        }) => {
            assert_eq!((*count, *rank), (2, 1));
            // Dφ = [[0, −1], [0, −2]]: singular values √5 and 0.
            assert!((singular_values[0] - 5f64.sqrt()).abs() < 1e-14);
            assert!(singular_values[1].abs() < 1e-15);
        }
        other => panic!("{other:?}"),
    }
    let message = err.to_string();
    eprintln!("{message}");
    assert!(
        message.contains("the 2 constraints are redundant"),
        "{message}"
    );
    assert!(message.contains("Dφ has rank 1 < 2"), "{message}");
    // The rank is available on its own too.
    let rank = holonomic::constraint_rank(&Doubled, &[0.6, -0.8]);
    assert_eq!(rank.rank, 1);
}

#[test]
fn initial_positions_off_the_manifold_are_refused_with_the_residual() {
    // |q0|² = 1.01: φ = 0.005.
    let err = pendulum_problem(Initial::velocity(&[0.1, -1.0], &[1.0, 0.1]))
        .with_constraint(CartesianPendulum::default())
        .unwrap_err();
    match err {
        Error::Setup(SetupError::InitialPositionOffConstraint {
            index, residual, ..
        }) => {
            assert_eq!(index, 0);
            assert!((residual - 0.005).abs() < 1e-15, "{residual}");
        }
        ref other => panic!("{other:?}"),
    }
    let message = err.to_string();
    eprintln!("{message}");
    assert!(message.contains("|φ_0(q0)| = 5.000e-3"), "{message}");
    assert!(message.contains("Initial::project_onto"), "{message}");
}

#[test]
fn initial_velocities_and_momenta_not_tangent_are_refused_separately() {
    let pendulum = CartesianPendulum::default();
    // Radial velocity 0.2 at the bottom: Dφ v = q · v = −0.2.
    let err = pendulum_problem(Initial::velocity(&[0.0, -1.0], &[0.5, 0.2]))
        .with_constraint(pendulum)
        .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::InitialVelocityNotTangent { what: "velocity v0", index: 0, residual, .. }) if (residual + 0.2).abs() < 1e-15),
        "{err:?}"
    );
    let message = err.to_string();
    eprintln!("{message}");
    assert!(
        message.contains("initial velocity v0 is not tangent"),
        "{message}"
    );
    assert!(message.contains("= -2.000e-1"), "{message}");
    // The same for momenta: FH(p0) = p0/m has the radial part −0.3.
    let err = pendulum_problem(Initial::momentum(&[0.0, -1.0], &[0.5, 0.3]))
        .with_constraint(pendulum)
        .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::InitialVelocityNotTangent { what: "momentum p0", residual, .. }) if (residual + 0.3).abs() < 1e-15),
        "{err:?}"
    );
    eprintln!("{err}");
    assert!(
        err.to_string()
            .contains("initial momentum p0 is not tangent")
    );
    // Within the tolerance, data pass.
    let ok = pendulum_problem(pendulum.initial(0.3, 1.0)).with_constraint(pendulum);
    assert!(ok.is_ok());
}

#[test]
fn explicit_projection_repairs_initial_data() {
    let sphere = SphericalPendulum::default();
    // Off the sphere and not tangent: |q| = 1.5, radial velocity.
    let rough = Initial::velocity(&[0.9, 0.0, -1.2], &[0.1, 0.5, 0.3]);
    let fixed = rough.project_onto(&sphere, &sphere, 0.0).unwrap();
    let Initial::Velocity { q, v } = &fixed else {
        panic!("kind changed")
    };
    // The nearest point of the sphere: q/|q|.
    assert!(
        (q[0] - 0.6).abs() < 1e-15 && (q[2] + 0.8).abs() < 1e-15,
        "{q:?}"
    );
    let radial: f64 = q.iter().zip(v).map(|(a, b)| a * b).sum();
    assert!(radial.abs() < 1e-15, "{radial:e}");
    // Tangential part kept (unit mass: the projection is orthogonal).
    assert!((v[1] - 0.5).abs() < 1e-15);
    let problem = Problem::new(sphere, fixed, grid())
        .unwrap()
        .with_constraint(sphere);
    assert!(problem.is_ok(), "{:?}", problem.err());
    // Momenta too.
    let fixed = Initial::momentum(&[0.0, 0.0, -2.0], &[0.0, 1.0, 1.0])
        .project_onto(&sphere, &sphere, 0.0)
        .unwrap();
    assert_eq!(
        fixed,
        Initial::Momentum {
            q: vec![0.0, 0.0, -1.0],
            p: vec![0.0, 1.0, 0.0]
        }
    );
}

#[test]
fn momentum_projection_failure_is_a_typed_error() {
    // With redundant constraints the KKT matrix of the projection is singular.
    let mut p = [0.5, 0.1];
    let err = holonomic::project_momentum(
        &CartesianPendulum::default(),
        &Doubled,
        0.0,
        &[0.0, -1.0],
        &mut p,
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            Error::Step(StepFailure {
                step: 0,
                cause: StepError::MomentumProjectionFailed { .. },
                ..
            })
        ),
        "{err:?}"
    );
    eprintln!("{err}");
    assert!(
        err.to_string()
            .contains("the momentum projection (RATTLE) failed")
    );
    assert_eq!(
        p,
        [0.5, 0.1],
        "momenta must be unchanged after a failed projection"
    );
}
