//! A solve that does not converge returns its last iterate with a status saying why, never a
//! number in the place of a failure.

use marsden::Midpoint;
use marsden_control::{SqpOptions, Status};

use super::swing_up::swing_up;

#[test]
fn an_exhausted_budget_returns_the_last_iterate_marked_as_such() {
    let options = SqpOptions {
        max_iterations: 2,
        ..SqpOptions::default()
    };
    let s = swing_up(60).solve(&Midpoint, &options).unwrap();
    assert_eq!(s.status, Status::IterationLimit);
    assert!(!s.converged());
    assert_eq!(s.iterations, 2);
    assert_eq!(
        (s.q.len(), s.u.len(), s.p.len(), s.costates.len()),
        (61, 60, 61, 59)
    );
    // The last iterate, with its own measures: not yet feasible to the tolerance.
    assert!(s.cost.is_finite() && s.constraint_violation > 1e-10);
    assert_eq!(s.history.len(), 2);
}

#[test]
fn bounds_that_exclude_the_end_state_are_reported_infeasible() {
    // The swing-up must reach θ = π; the state bounds stop it at 2.
    let problem = swing_up(30).with_state_bounds(&[-1.0], &[2.0]).unwrap();
    let s = problem.solve(&Midpoint, &SqpOptions::default()).unwrap();
    let Status::Infeasible(infeasibility) = &s.status else {
        panic!("status {:?}", s.status);
    };
    // The certificate leans on the bound of the only coordinate, none of a control.
    assert_eq!(infeasibility.coordinates, [0]);
    assert!(infeasibility.controls.is_empty());
    assert!(s.q.iter().all(|q| (-1.0..=2.0).contains(&q[0])));
}
