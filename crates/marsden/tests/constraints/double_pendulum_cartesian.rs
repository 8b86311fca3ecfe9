//! The planar double pendulum two ways: angle coordinates (`systems::DoublePendulum`) and
//! Cartesian coordinates with two distance constraints (`systems::CartesianDoublePendulum`,
//! SHAKE + RATTLE). Both are second-order midpoint discretisations of the same motion but of
//! different discrete Lagrangians, so they agree to `O(h²)`, not to round-off: the test shows
//! that both converge with order 2 to the same (Richardson-extrapolated) reference and that
//! their difference shrinks by 4 per halving of `h`.
// Tests: helpers unwrap, and reference values keep all their published digits.
#![allow(clippy::unwrap_used, clippy::excessive_precision)]

use crate::common::{loglog_slope, tight};
use marsden::analysis::diagnostics::ConstraintReport;
use marsden::systems::{CartesianDoublePendulum, DoublePendulum};
use marsden::{Initial, Midpoint, Problem, RunOptions, SolveOptions, TimeGrid, Trajectory};

const THETA: [f64; 2] = [0.8, 0.3];
const T_END: f64 = 10.0;
/// Bob positions are compared every 0.1 time units.
const SAMPLE: f64 = 0.1;

fn options(h: f64) -> SolveOptions {
    SolveOptions {
        newton: tight(),
        run: RunOptions {
            stride: (SAMPLE / h).round() as usize,
        },
        ..SolveOptions::default()
    }
}

fn grid(h: f64) -> TimeGrid {
    TimeGrid::until(0.0, T_END, h).unwrap()
}

/// Bob positions `(x₁, y₁, x₂, y₂)` at `t = 0, 0.1, …, 10` from the angle model.
fn angle_model(h: f64) -> Vec<[f64; 4]> {
    let sys = DoublePendulum::default();
    let initial = Initial::velocity(&THETA, &[0.0, 0.0]);
    let traj = Problem::new(sys, initial, grid(h))
        .unwrap()
        .solve(&Midpoint, &options(h))
        .unwrap();
    (0..traj.len()).map(|i| sys.positions(traj.q(i))).collect()
}

fn cartesian_run(h: f64) -> Trajectory {
    let sys = CartesianDoublePendulum::default();
    Problem::new(sys, sys.initial(THETA, [0.0, 0.0]), grid(h))
        .unwrap()
        .with_constraint(sys)
        .unwrap()
        .solve(&Midpoint, &options(h))
        .unwrap()
}

fn cartesian_model(h: f64) -> Vec<[f64; 4]> {
    let traj = cartesian_run(h);
    (0..traj.len())
        .map(|i| {
            let q = traj.q(i);
            [q[0], q[1], q[2], q[3]]
        })
        .collect()
}

fn max_difference(a: &[[f64; 4]], b: &[[f64; 4]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| x.iter().zip(y).map(|(u, v)| (u - v).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn cartesian_and_angle_models_converge_to_the_same_motion_with_order_2() {
    // Reference: Richardson extrapolation of the angle model, error O(h⁴) ≈ 1e-11.
    let (fine, finer) = (angle_model(0.00125), angle_model(0.000625));
    let reference: Vec<[f64; 4]> = fine
        .iter()
        .zip(&finer)
        .map(|(a, b)| std::array::from_fn(|k| (4.0 * b[k] - a[k]) / 3.0))
        .collect();
    let hs = [0.02, 0.01, 0.005];
    let mut errors = [Vec::new(), Vec::new()];
    let mut differences = Vec::new();
    for h in hs {
        let (angle, cartesian) = (angle_model(h), cartesian_model(h));
        errors[0].push(max_difference(&angle, &reference));
        errors[1].push(max_difference(&cartesian, &reference));
        differences.push(max_difference(&angle, &cartesian));
    }
    let slopes = [loglog_slope(&hs, &errors[0]), loglog_slope(&hs, &errors[1])];
    let diff_slope = loglog_slope(&hs, &differences);
    eprintln!(
        "max bob-position error over t ∈ [0, 10] for h = {hs:?}: angle {:?} (order {:.3}), \
         Cartesian {:?} (order {:.3}); difference {:?} (order {diff_slope:.3})",
        errors[0], slopes[0], errors[1], slopes[1], differences
    );
    for s in slopes {
        assert!((s - 2.0).abs() < 0.05, "order {s}");
    }
    assert!(
        (diff_slope - 2.0).abs() < 0.05,
        "difference order {diff_slope}"
    );
    // At h = 0.005 the two models agree to 1e-4 in bob positions over ten time units.
    assert!(differences[2] < 1e-4, "{:e}", differences[2]);
    // Removing the h² term of the Cartesian run (Richardson, h = 0.0025 and 0.00125) leaves
    // the reference motion of the angle model to O(h⁴).
    let (a, b) = (cartesian_model(0.0025), cartesian_model(0.00125));
    let extrapolated: Vec<[f64; 4]> = a
        .iter()
        .zip(&b)
        .map(|(x, y)| std::array::from_fn(|k| (4.0 * y[k] - x[k]) / 3.0))
        .collect();
    let agreement = max_difference(&extrapolated, &reference);
    eprintln!("extrapolated Cartesian vs extrapolated angle model: {agreement:.2e}");
    assert!(agreement < 1e-10, "{agreement:e}");
}

#[test]
fn cartesian_double_pendulum_keeps_both_rods_and_tangent_momenta() {
    let sys = CartesianDoublePendulum::default();
    let traj = cartesian_run(0.01);
    let report = ConstraintReport::of(&sys, &sys, &traj).unwrap();
    eprintln!(
        "double pendulum: max |φ| = {:.1e}, max |Dφ v| = {:.1e}",
        report.max_position, report.max_velocity
    );
    assert!(report.max_position < 1e-14, "{:e}", report.max_position);
    assert!(report.max_velocity < 1e-14, "{:e}", report.max_velocity);
    // Angles recovered from the Cartesian run start where they should.
    let angles = CartesianDoublePendulum::angles(traj.q(0));
    assert!((angles[0] - THETA[0]).abs() < 1e-15 && (angles[1] - THETA[1]).abs() < 1e-15);
}

/// Bob positions every 0.1 from `rule` in both formulations.
fn both_models<R: marsden::Rule>(rule: &R, h: f64) -> (Vec<[f64; 4]>, Vec<[f64; 4]>) {
    let sys = DoublePendulum::default();
    let initial = Initial::velocity(&THETA, &[0.0, 0.0]);
    let angle = Problem::new(sys, initial, grid(h))
        .unwrap()
        .solve(rule, &options(h))
        .unwrap();
    let cart = CartesianDoublePendulum::default();
    let cartesian = Problem::new(cart, cart.initial(THETA, [0.0, 0.0]), grid(h))
        .unwrap()
        .with_constraint(cart)
        .unwrap()
        .solve(rule, &options(h))
        .unwrap();
    let angle = (0..angle.len())
        .map(|i| sys.positions(angle.q(i)))
        .collect();
    let cartesian = (0..cartesian.len())
        .map(|i| {
            let q = cartesian.q(i);
            [q[0], q[1], q[2], q[3]]
        })
        .collect();
    (angle, cartesian)
}

/// R14 at order 4: with constrained Lobatto IIIA–IIIB (`lobatto-3`, stage constraints) the
/// Cartesian and angle formulations agree to the order's error — their difference shrinks by
/// 16 per halving of `h` (it shrank by 4 when the constraint was imposed at the step ends only).
#[test]
fn r14_cartesian_and_angle_models_agree_at_order_4_with_lobatto_3() {
    let rule = marsden::discrete::rules::Galerkin::lobatto(3).unwrap();
    let hs = [0.02, 0.01, 0.005];
    let differences: Vec<f64> = hs
        .iter()
        .map(|&h| {
            let (angle, cartesian) = both_models(&rule, h);
            max_difference(&angle, &cartesian)
        })
        .collect();
    let slope = loglog_slope(&hs, &differences);
    eprintln!(
        "lobatto-3: max bob-position difference over t ∈ [0, 10] for h = {hs:?}: \
         {differences:?} (order {slope:.3})"
    );
    assert!((slope - 4.0).abs() < 0.2, "difference order {slope}");
    assert!(differences[2] < 1e-7, "{:e}", differences[2]);
}
