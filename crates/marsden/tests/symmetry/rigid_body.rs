//! A free rigid body of four point masses held by six distance constraints (SHAKE): total
//! linear and angular momentum are conserved to round-off while it tumbles, because the
//! constraints are invariant (their impulse h Dφᵀλ has no component along ξ_Q) — no momentum
//! projection (RATTLE) is needed for this.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use marsden::analysis::diagnostics::{NoetherMonitor, NoetherReport};
use marsden::symmetry::DeclaresSymmetries;
use marsden::systems::PointRigidBody;
use marsden::{
    Constraint, Initial, Midpoint, NewtonOptions, Problem, Rule, SolveOptions, TimeGrid, Trapezoid,
};

fn tumble<R: Rule>(rule: &R) -> (Vec<NoetherReport>, f64, f64) {
    let (body, q) = PointRigidBody::tetrahedron();
    let v = body.rigid_velocities(&q, [0.1, 0.0, 0.05], [0.3, 1.0, -0.5]);
    let grid = TimeGrid::new(0.0, 0.01, 10_000).unwrap();
    let problem = Problem::new(body.clone(), Initial::velocity(&q, &v), grid)
        .unwrap()
        .with_constraint(body.clone())
        .unwrap();
    // Reference cases §0, solver note: conservation tests at a relative Newton tolerance of
    // 1e-14. (1e-15 is below the round-off floor of this 18-unknown system with multipliers:
    // Newton stalls at a residual of 2.3e-15.)
    let options = SolveOptions {
        newton: NewtonOptions {
            residual_tolerance: 1e-14,
            ..NewtonOptions::default()
        },
        ..SolveOptions::default()
    };
    let mut monitor = NoetherMonitor::new(body.symmetries());
    let trajectory = match problem.solve_with(rule, &options, &mut monitor) {
        Ok(t) => t,
        Err(failure) => panic!("{}", failure.error),
    };
    let reports = NoetherReport::all(&body.symmetries(), &trajectory).unwrap();
    assert_eq!(monitor.reports().unwrap(), reports.as_slice());
    // Constraint residual and how far the body turned.
    let mut phi = vec![0.0; body.count()];
    let mut worst: f64 = 0.0;
    for i in 0..trajectory.len() {
        body.constraint(trajectory.q(i), &mut phi);
        worst = phi.iter().fold(worst, |m, x| m.max(x.abs()));
    }
    let last = trajectory.len() - 1;
    let moved = (0..3)
        .map(|a| (trajectory.q(last)[a] - trajectory.q(0)[a]).abs())
        .fold(0.0, f64::max);
    (reports, worst, moved)
}

#[test]
fn tumbling_point_rigid_body_conserves_momentum_and_angular_momentum() {
    // (With no potential, L_d of both rules is h·½vᵀMv: the runs coincide.)
    for (name, (reports, constraint, moved)) in [
        ("midpoint", tumble(&Midpoint)),
        ("trapezoid", tumble(&Trapezoid)),
    ] {
        println!(
            "{name}: linear {:.2e}, angular {:.2e} (relative drift); |φ| ≤ {constraint:.1e}; L₀ = {:?}",
            reports[0].max_rel_drift, reports[1].max_rel_drift, reports[1].initial
        );
        assert!(
            reports[0].max_rel_drift <= 1e-12,
            "{name}: {:?}",
            reports[0]
        );
        assert!(
            reports[1].max_rel_drift <= 1e-12,
            "{name}: {:?}",
            reports[1]
        );
        assert!(
            constraint <= 1e-12,
            "{name}: constraint residual {constraint:e}"
        );
        // It really tumbles: the angular momentum is large and the first particle moved.
        assert!(reports[1].initial.iter().map(|x| x.abs()).sum::<f64>() > 1.0);
        assert!(moved > 0.5, "{name}: moved {moved}");
    }
}
