//! Typed failures of rigid-body runs: a step whose Newton solve does not converge names the step,
//! its time and the residual, leaves the state as it was, and the run keeps its samples; bad
//! steps and initial data are input errors.

use super::{heavy_top, tight};
use marsden::NewtonOptions;
use marsden::error::{Error, InputError, StepError};
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::{Lgvi, LgviOptions};
use marsden::lie::potential::UniformGravity;
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::lie::trajectory::run;

#[test]
fn unconverged_step_is_a_typed_error_and_keeps_the_state() {
    // One Newton iteration cannot reach 1e-15 relative for the spinning top at h = 0.01.
    let options = LgviOptions {
        newton: NewtonOptions {
            residual_tolerance: 1e-15,
            step_tolerance: 1e-300,
            max_iterations: 1,
            ..NewtonOptions::default()
        },
        ..tight()
    };
    let mut lgvi = heavy_top(0.01, options);
    let before = lgvi.state().clone();
    let failure = run(&mut lgvi, 10, 1).unwrap_err();
    match &failure.error {
        Error::Step(step) => {
            assert_eq!((step.step, step.t), (0, 0.0));
            match &step.cause {
                StepError::NewtonDidNotConverge {
                    iterations,
                    residual,
                    tolerance,
                } => {
                    assert_eq!(*iterations, 1);
                    assert!(*residual > 0.0 && residual.is_finite());
                    assert_eq!(*tolerance, 1e-15);
                }
                other => panic!("{other:?}"),
            }
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(failure.trajectory.states, vec![before.clone()]);
    assert_eq!(lgvi.state(), &before);
    assert!(failure.to_string().contains("did not converge"));
}

#[test]
fn bad_step_and_initial_data_are_input_errors() {
    let body = RigidBody::fixed_point(Inertia::principal([5.0, 5.0, 1.0]).unwrap());
    let system = RigidSystem::new(vec![body], UniformGravity::top(20.0));
    let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let initial = BodyInitial {
        attitude: identity,
        angular_momentum: [0.0, 0.0, 1.0],
        position: [0.0; 3],
        linear_momentum: [0.0; 3],
    };
    let state = RigidState::new(&system, 0.0, &[initial]).unwrap();
    assert!(matches!(
        Lgvi::new(system.clone(), state, -0.1, tight()),
        Err(Error::Input(InputError::InvalidStep { .. }))
    ));
    assert!(matches!(
        RigidState::new(&system, 0.0, &[initial, initial]),
        Err(Error::Input(InputError::DimensionMismatch {
            expected: 1,
            found: 2,
            ..
        }))
    ));
    let skewed = BodyInitial {
        attitude: [1.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        ..initial
    };
    assert!(matches!(
        RigidState::new(&system, 0.0, &[skewed]),
        Err(Error::Input(InputError::NotARotation { .. }))
    ));
}
