//! Noether's theorem with forces, discrete and per step: for a damped two-particle system with
//! translation (and rotation) symmetry, the change of the discrete momentum map in each step
//! equals the discrete impulse of the forces along the generator,
//! J_{k+1} − J_k = ⟨f_d⁻, ξ_Q(q_k)⟩ + ⟨f_d⁺, ξ_Q(q_{k+1})⟩, to 1e-12.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use crate::common::tight;
use marsden::analysis::diagnostics::{BalanceMonitor, force_balance};
use marsden::symmetry::{AxisRotation, GroupAction, Translations};
use marsden::{
    Force, GeneralizedMidpoint, Initial, Lagrangian, Midpoint, Problem, Rule, Scalar, SolveOptions,
    TimeGrid, Trapezoid,
};

/// Two planar particles joined by a spring of rest length r₀ (translation and rotation invariant).
struct Dumbbell;
impl Lagrangian for Dumbbell {
    fn dof(&self) -> usize {
        4
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let kinetic = (v[0] * v[0] + v[1] * v[1]) * 0.5 + (v[2] * v[2] + v[3] * v[3]) * 1.5;
        let (dx, dy) = (q[2] - q[0], q[3] - q[1]);
        let stretch = (dx * dx + dy * dy).sqrt() - 1.0;
        kinetic - stretch * stretch * 2.0
    }
}

/// Linear drag −cᵢ vᵢ with a different coefficient on each particle (not along any symmetry).
#[derive(Clone, Copy)]
struct Drag;
impl Force for Drag {
    fn force<S: Scalar>(&self, _t: S, _q: &[S], v: &[S], out: &mut [S]) {
        for i in 0..2 {
            out[i] = v[i] * (-0.3);
            out[2 + i] = v[2 + i] * (-0.05);
        }
    }
}

fn problem(steps: usize) -> Problem<Dumbbell, Drag> {
    let grid = TimeGrid::new(0.0, 0.05, steps).unwrap();
    Problem::new(
        Dumbbell,
        Initial::velocity(&[0.0, 0.0, 1.2, 0.1], &[1.0, -0.5, 0.2, 0.9]),
        grid,
    )
    .unwrap()
    .with_force(Drag)
}

fn check<R: Rule, G: GroupAction>(rule: &R, action: &G) -> (f64, f64) {
    let problem = problem(2000);
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    let trajectory = problem.solve(rule, &options).unwrap();
    let fd = rule.discretize_force(Drag, 4);
    let report = force_balance(action, &fd, &trajectory).unwrap();
    assert_eq!(report.steps, 2000);
    // The same through the streaming monitor.
    let mut monitor = BalanceMonitor::new(action, &fd, 0.05);
    problem.solve_with(rule, &options, &mut monitor).unwrap();
    assert_eq!(monitor.report().unwrap(), &report);
    let change = report
        .total_change
        .iter()
        .map(|x| x.abs())
        .fold(0.0, f64::max);
    println!(
        "{} / {}: max |ΔJ − impulse| = {:.2e} (relative {:.2e}); total ΔJ = {:?}",
        rule.name(),
        action.name(),
        report.max_residual,
        report.max_rel_residual,
        report.total_change
    );
    (report.max_residual, change)
}

#[test]
fn damped_momentum_change_equals_discrete_impulse_per_step() {
    let translations = Translations::new(2, 2);
    let rotation = AxisRotation::planar(2);
    for (residual, change) in [
        check(&Midpoint, &translations),
        check(&Trapezoid, &translations),
        check(&GeneralizedMidpoint { alpha: 0.3 }, &translations),
        check(&Midpoint, &rotation),
        check(&Trapezoid, &rotation),
    ] {
        assert!(residual <= 1e-12, "balance residual {residual:e}");
        // Not vacuous: the forces really change the momentum.
        assert!(change > 0.1, "momentum change {change}");
    }
}
