//! Bad input gives typed errors, with the numbers that locate it.

use marsden::systems::Pendulum;
use marsden_control::{
    Boundary, ControlError, Effort, Horizon, InputMap, OptimalControl, Rate, SqpOptions,
};

fn problem(start: Boundary) -> Result<OptimalControl<Pendulum, InputMap, Effort>, ControlError> {
    OptimalControl::new(
        Pendulum::default(),
        InputMap::full(1),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 1.0,
            steps: 10,
        },
        start,
        Boundary::rest(&[1.0]),
    )
}

#[test]
fn control_bounds_with_lower_above_upper_are_refused() {
    let p = problem(Boundary::rest(&[0.0])).unwrap();
    let err = p.with_control_bounds(&[2.0], &[1.0]).unwrap_err();
    assert_eq!(
        err,
        ControlError::Bounds {
            what: "control",
            index: 0,
            lower: 2.0,
            upper: 1.0
        }
    );
}

#[test]
fn bounds_of_the_wrong_length_are_refused() {
    let p = problem(Boundary::rest(&[0.0])).unwrap();
    let err = p.with_state_bounds(&[0.0, 0.0], &[1.0, 1.0]).unwrap_err();
    assert_eq!(
        err,
        ControlError::Length {
            what: "state",
            got: 2,
            expected: 1
        }
    );
}

#[test]
fn boundary_data_of_the_wrong_length_are_refused() {
    let err = problem(Boundary::rest(&[0.0, 0.0])).unwrap_err();
    assert_eq!(
        err,
        ControlError::Length {
            what: "start q",
            got: 2,
            expected: 1
        }
    );
    let mut start = Boundary::rest(&[0.0]);
    start.rate = Rate::Momentum(vec![Some(0.0), None]);
    let err = problem(start).unwrap_err();
    assert_eq!(
        err,
        ControlError::Length {
            what: "start rate",
            got: 2,
            expected: 1
        }
    );
}

#[test]
fn non_finite_boundary_values_are_refused() {
    let err = problem(Boundary::rest(&[f64::NAN])).unwrap_err();
    assert!(matches!(
        err,
        ControlError::NotFinite {
            what: "start q",
            index: 0,
            ..
        }
    ));
}

#[test]
fn an_empty_or_negative_horizon_is_refused() {
    for (duration, steps) in [(0.0, 10), (-1.0, 10), (1.0, 0), (f64::INFINITY, 10)] {
        let err = OptimalControl::new(
            Pendulum::default(),
            InputMap::full(1),
            Effort::default(),
            Horizon {
                t0: 0.0,
                duration,
                steps,
            },
            Boundary::rest(&[0.0]),
            Boundary::rest(&[1.0]),
        )
        .unwrap_err();
        assert!(matches!(err, ControlError::Horizon { .. }), "{err}");
    }
}

#[test]
fn non_positive_tolerances_are_refused() {
    let p = problem(Boundary::rest(&[0.0])).unwrap();
    let options = SqpOptions {
        kkt_tolerance: 0.0,
        ..SqpOptions::default()
    };
    let err = p.solve(&marsden::Midpoint, &options).unwrap_err();
    assert!(
        matches!(
            err,
            ControlError::Option {
                name: "kkt_tolerance",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_guess_with_the_wrong_number_of_nodes_is_refused() {
    let p = problem(Boundary::rest(&[0.0])).unwrap();
    let guess = marsden_control::Guess {
        q: vec![vec![0.0]; 10],
        u: vec![vec![0.0]; 10],
    };
    let err = p.with_guess(guess).unwrap_err();
    assert_eq!(
        err,
        ControlError::Guess {
            what: "q",
            got: 10,
            expected: 11
        }
    );
}

#[test]
fn a_partly_free_boundary_velocity_is_refused() {
    let err = OptimalControl::new(
        marsden::systems::PendulumOnCart::default(),
        InputMap::new(&[0]),
        Effort::default(),
        Horizon {
            t0: 0.0,
            duration: 1.0,
            steps: 10,
        },
        Boundary {
            q: vec![Some(0.0), Some(0.0)],
            rate: Rate::Velocity(vec![Some(0.0), None]),
        },
        Boundary::free(2),
    )
    .unwrap_err();
    assert_eq!(
        err,
        ControlError::PartialVelocity {
            which: "start",
            free: vec![1]
        }
    );
}
