//! Jointed rigid bodies (the constrained LGVI of `marsden::lie::multibody`).
//!
//! * R21, the compound double pendulum: two uniform rods joined by hinges, stepped on
//!   (SO(3) × ℝ³)² with 10 joint rows, against its reduced-coordinate Lagrangian in the two hinge
//!   angles integrated by `gauss-4` (order 8) at a tiny step: orders 2 (the step) and 4 (its
//!   triple jump) fitted from three step sizes; the joints closed to round-off at every step.
//! * R22, the 3D pendulum ([CLLM11]): a rigid body on a ball joint under gravity; the vertical
//!   angular momentum about the pivot is a momentum map of the rotations about the vertical, so
//!   discrete Noether keeps it to round-off.
//! * A free satellite with a reaction wheel (two bodies on a hinge, no external load): total
//!   angular and linear momentum to round-off.
//! * A chain of `N` links: the joint matrix is banded with a bandwidth independent of `N`, and the
//!   Newton iterations per step do not grow with `N`.
//! * Bad input: an initial state off the joints (the row and residual), redundant joints (a
//!   singular joint matrix), a body index beyond the system, and `project` closing the joints.
//!
//! [CLLM11]: marsden#references
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::tight;
use marsden::discrete::rules::Method;
use marsden::discrete::rules::composition::CompositionScheme;
use marsden::error::SetupError;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::invariants;
use marsden::lie::lgvi::LgviOptions;
use marsden::lie::multibody::chain::HangingChain;
use marsden::lie::multibody::gravity::GravityField;
use marsden::lie::multibody::initial;
use marsden::lie::multibody::joint::{Joint, JointKind};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::multibody::step::MultibodyLgvi;
use marsden::lie::potential::NoPotential;
use marsden::lie::so3::{Mat3, Vec3, exp};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::numerics::dense::max_or_nan;
use marsden::{Error, Initial, Lagrangian, Problem, Scalar, SolveOptions, TimeGrid};

const G: f64 = 9.81;
const ROD: f64 = 1.0;
const MASS: f64 = 1.0;
/// A slender rod's moments about its centre: `mℓ²/12` across, a small one along.
const ACROSS: f64 = MASS * ROD * ROD / 12.0;
const ALONG: f64 = 1e-3;

fn rod() -> RigidBody {
    RigidBody::free(Inertia::principal([ACROSS, ACROSS, ALONG]).unwrap(), MASS).unwrap()
}

fn gravity(bodies: usize) -> GravityField {
    GravityField {
        g: [0.0, 0.0, -G],
        masses: vec![MASS; bodies],
        first_moments: vec![[0.0; 3]; bodies],
    }
}

/// The reduced-coordinate compound double pendulum: hinge angles `θ₁, θ₂` about `e_y` from the
/// downward vertical, rods of mass `m`, length `ℓ`, moment `I` about their centres.
struct ReducedDoublePendulum;

impl Lagrangian for ReducedDoublePendulum {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (l, m) = (ROD, MASS);
        let c12 = (q[0] - q[1]).cos();
        let kinetic = (v[0] * v[0] * (l * l * 1.25)
            + v[1] * v[1] * (l * l * 0.25)
            + v[0] * v[1] * c12 * (l * l))
            * (0.5 * m)
            + (v[0] * v[0] + v[1] * v[1]) * (0.5 * ACROSS);
        let height = -(q[0].cos() * (1.5 * l) + q[1].cos() * (0.5 * l));
        kinetic - height * (m * G)
    }
}

fn ry(theta: f64) -> Mat3 {
    exp(&Vec3::new(0.0, theta, 0.0))
}

/// The bodies' state from hinge angles and rates (rod axes along body `e₃`, hinges about `e_y`).
fn double_pendulum_state(
    system: &RigidSystem<GravityField>,
    theta: [f64; 2],
    rate: [f64; 2],
) -> RigidState {
    let (l, m) = (ROD, MASS);
    let dir = |t: f64| Vec3::new(t.sin(), 0.0, t.cos());
    let ddir = |t: f64, w: f64| Vec3::new(t.cos(), 0.0, -t.sin()) * w;
    let x1 = -dir(theta[0]) * (l / 2.0);
    let x2 = -dir(theta[0]) * l - dir(theta[1]) * (l / 2.0);
    let v1 = -ddir(theta[0], rate[0]) * (l / 2.0);
    let v2 = -ddir(theta[0], rate[0]) * l - ddir(theta[1], rate[1]) * (l / 2.0);
    let body = |t: f64, w: f64, x: Vec3, v: Vec3| BodyInitial {
        attitude: marsden::lie::so3::rows(&ry(t)),
        angular_momentum: [0.0, ACROSS * w, 0.0],
        position: [x.x, x.y, x.z],
        linear_momentum: [m * v.x, m * v.y, m * v.z],
    };
    let bodies = [
        body(theta[0], rate[0], x1, v1),
        body(theta[1], rate[1], x2, v2),
    ];
    RigidState::new(system, 0.0, &bodies).unwrap()
}

fn hinge(bodies: [Option<usize>; 2], points: [Vec3; 2]) -> Joint {
    let axes = [Vec3::y(), Vec3::y()];
    Joint::new(bodies, points, JointKind::Revolute { axes }).unwrap()
}

fn double_pendulum() -> (RigidSystem<GravityField>, JointSet) {
    let half = Vec3::new(0.0, 0.0, ROD / 2.0);
    let joints = vec![
        hinge([None, Some(0)], [Vec3::zeros(), half]),
        hinge([Some(0), Some(1)], [-half, half]),
    ];
    let system = RigidSystem::new(vec![rod(), rod()], gravity(2));
    (system, JointSet::new(joints, 2).unwrap())
}

const THETA0: [f64; 2] = [0.9, -0.4];
const RATE0: [f64; 2] = [0.5, -1.0];
const T_END: f64 = 1.0;

/// The hinge angles at `T_END` of the jointed bodies, and the largest joint residual met.
fn jointed_angles(h: f64, composition: Option<CompositionScheme>) -> ([f64; 2], f64) {
    let (system, joints) = double_pendulum();
    let state = double_pendulum_state(&system, THETA0, RATE0);
    let options = LgviOptions {
        newton: tight(),
        composition,
    };
    let mut lgvi = MultibodyLgvi::new(system, joints, state, h, options).unwrap();
    let steps = (T_END / h).round() as usize;
    let mut worst: f64 = 0.0;
    for _ in 0..steps {
        lgvi.step().unwrap();
        worst = max_or_nan(
            worst,
            max_or_nan(
                0.0,
                lgvi.joint_rows()
                    .values
                    .iter()
                    .fold(0.0, |a: f64, g| max_or_nan(a, g.abs())),
            ),
        );
    }
    let angle = |i: usize| {
        let r = lgvi.state().rotation(i);
        r[(0, 2)].atan2(r[(0, 0)])
    };
    ([angle(0), angle(1)], worst)
}

/// The reduced model's angles at `T_END` (gauss-4, order 8, 2000 steps).
fn reduced_angles() -> [f64; 2] {
    let grid = TimeGrid::new(0.0, T_END / 2000.0, 2000).unwrap();
    let problem = Problem::new(
        ReducedDoublePendulum,
        Initial::velocity(&THETA0, &RATE0),
        grid,
    )
    .unwrap();
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    let trajectory = problem
        .solve(&Method::parse("gauss-4").unwrap(), &options)
        .unwrap();
    let q = trajectory.q(trajectory.len() - 1);
    [q[0], q[1]]
}

fn slope(hs: &[f64], errors: &[f64]) -> f64 {
    let n = hs.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = hs.iter().zip(errors).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

fn fitted_order(hs: &[f64], composition: Option<CompositionScheme>) -> (f64, Vec<f64>) {
    let reference = reduced_angles();
    let mut errors = Vec::new();
    for &h in hs {
        let (angles, worst) = jointed_angles(h, composition);
        assert!(worst < 1e-13, "joints open by {worst:e} at h = {h}");
        errors.push(max_or_nan(
            (angles[0] - reference[0]).abs(),
            (angles[1] - reference[1]).abs(),
        ));
    }
    (slope(hs, &errors), errors)
}

#[test]
fn r21_compound_double_pendulum_is_second_order_against_reduced_coordinates() {
    let (order, errors) = fitted_order(&[0.02, 0.01, 0.005], None);
    eprintln!("R21 trapezoid LGVI: order {order:.3}, errors {errors:?}");
    assert!(
        (order - 2.0).abs() < 0.1,
        "order {order}, errors {errors:?}"
    );
    assert!(errors[2] < 1e-3, "{errors:?}");
}

#[test]
fn r21_triple_jump_of_the_jointed_step_is_fourth_order() {
    let scheme = Some(CompositionScheme::TripleJump { order: 4 });
    let (order, errors) = fitted_order(&[0.02, 0.01, 0.005], scheme);
    eprintln!("R21 triple jump: order {order:.3}, errors {errors:?}");
    assert!(
        (order - 4.0).abs() < 0.2,
        "order {order}, errors {errors:?}"
    );
}

/// The total angular momentum about the origin, `Σ R_iΠ_i + x_i × p_i`.
fn angular_momentum(state: &RigidState) -> Vec3 {
    invariants::spatial_angular_momentum(state)
}

#[test]
fn r22_three_dimensional_pendulum_keeps_its_vertical_momentum() {
    // A box-shaped body hanging by a ball joint at a point off its centre, tilted and spinning.
    let body = RigidBody::free(Inertia::principal([0.3, 0.2, 0.15]).unwrap(), 2.0).unwrap();
    let pivot = Vec3::new(0.05, 0.0, 0.4);
    let system = RigidSystem::new(
        vec![body],
        GravityField {
            g: [0.0, 0.0, -G],
            masses: vec![2.0],
            first_moments: vec![[0.0; 3]],
        },
    );
    let ball = Joint::new(
        [None, Some(0)],
        [Vec3::zeros(), pivot],
        JointKind::Spherical,
    )
    .unwrap();
    let joints = JointSet::new(vec![ball], 1).unwrap();
    let r = exp(&Vec3::new(0.4, -0.2, 0.1));
    let omega = Vec3::new(0.3, 1.5, 4.0);
    let x = -(r * pivot);
    let v = r * omega.cross(&-pivot); // ẋ = Ṙ(−s) = R(Ω × (−s))
    let start = BodyInitial {
        attitude: marsden::lie::so3::rows(&r),
        angular_momentum: [0.3 * omega.x, 0.2 * omega.y, 0.15 * omega.z],
        position: [x.x, x.y, x.z],
        linear_momentum: [2.0 * v.x, 2.0 * v.y, 2.0 * v.z],
    };
    let state = RigidState::new(&system, 0.0, &[start]).unwrap();
    let options = LgviOptions {
        newton: tight(),
        composition: None,
    };
    let mut lgvi = MultibodyLgvi::new(system, joints, state, 0.005, options).unwrap();
    let l0 = angular_momentum(lgvi.state()).z;
    let e0 = invariants::energy(lgvi.system(), lgvi.state());
    let (mut drift, mut energy, mut open): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..4000 {
        lgvi.step().unwrap();
        drift = max_or_nan(drift, (angular_momentum(lgvi.state()).z - l0).abs());
        energy = max_or_nan(
            energy,
            (invariants::energy(lgvi.system(), lgvi.state()) - e0).abs(),
        );
        open = lgvi
            .joint_rows()
            .values
            .iter()
            .fold(open, |a, g| max_or_nan(a, g.abs()));
    }
    eprintln!("R22: L_z = {l0}, drift {drift:.2e}, energy error {energy:.2e}, joints {open:.2e}");
    assert!(l0.abs() > 0.1, "a nontrivial momentum: {l0}");
    assert!(
        drift < 1e-12 * l0.abs().max(1.0),
        "vertical momentum drift {drift:e} of {l0}"
    );
    assert!(open < 1e-13, "joint residual {open:e}");
    // Bounded energy error of order h² (not conserved exactly: a symplectic map of fixed step).
    assert!(
        energy < 1e-2 * e0.abs().max(1.0),
        "energy error {energy:e} of {e0}"
    );
}

#[test]
fn free_satellite_with_a_reaction_wheel_keeps_total_momenta() {
    let hub = RigidBody::free(Inertia::principal([4.0, 5.0, 6.0]).unwrap(), 50.0).unwrap();
    let wheel = RigidBody::free(Inertia::principal([0.012, 0.012, 0.02]).unwrap(), 1.0).unwrap();
    let system = RigidSystem::new(vec![hub, wheel], NoPotential);
    let mount = Vec3::new(0.2, 0.0, 0.1);
    let axle = JointKind::Revolute {
        axes: [Vec3::z(), Vec3::z()],
    };
    let joints = JointSet::new(
        vec![Joint::new([Some(0), Some(1)], [mount, Vec3::zeros()], axle).unwrap()],
        2,
    )
    .unwrap();
    // The wheel spins at 20 rad/s relative to the hub, which tumbles slowly.
    let hub_omega = Vec3::new(0.1, -0.05, 0.2);
    let wheel_omega = hub_omega + Vec3::new(0.0, 0.0, 20.0);
    let v_hub = Vec3::new(0.01, 0.0, -0.02);
    let v_wheel = v_hub + hub_omega.cross(&mount);
    let bodies = [
        BodyInitial {
            attitude: marsden::lie::so3::rows(&Mat3::identity()),
            angular_momentum: [0.4, -0.25, 1.2],
            position: [0.0; 3],
            linear_momentum: [0.5, 0.0, -1.0],
        },
        BodyInitial {
            attitude: marsden::lie::so3::rows(&Mat3::identity()),
            angular_momentum: [
                0.012 * wheel_omega.x,
                0.012 * wheel_omega.y,
                0.02 * wheel_omega.z,
            ],
            position: [mount.x, mount.y, mount.z],
            linear_momentum: [v_wheel.x, v_wheel.y, v_wheel.z],
        },
    ];
    let state = RigidState::new(&system, 0.0, &bodies).unwrap();
    let options = LgviOptions {
        newton: tight(),
        composition: None,
    };
    let mut lgvi = MultibodyLgvi::new(system, joints, state, 0.01, options).unwrap();
    let (l0, p0) = (
        angular_momentum(lgvi.state()),
        invariants::linear_momentum(lgvi.state()),
    );
    let (mut dl, mut dp, mut open): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..2000 {
        lgvi.step().unwrap();
        dl = max_or_nan(dl, (angular_momentum(lgvi.state()) - l0).amax());
        dp = max_or_nan(dp, (invariants::linear_momentum(lgvi.state()) - p0).amax());
        open = lgvi
            .joint_rows()
            .values
            .iter()
            .fold(open, |a, g| max_or_nan(a, g.abs()));
    }
    assert!(
        dl < 1e-12 * l0.amax(),
        "angular momentum drift {dl:e} of {l0}"
    );
    assert!(dp < 1e-13, "linear momentum drift {dp:e}");
    assert!(open < 1e-13, "joint residual {open:e}");
}

/// A chain of `n` rods hanging from the ground by hinges, slightly displaced and moving.
fn chain(n: usize) -> MultibodyLgvi<GravityField, marsden::lie::potential::NoLoads> {
    let (system, joints, state) = HangingChain::new(n).build().unwrap();
    MultibodyLgvi::new(system, joints, state, 0.001, LgviOptions::default()).unwrap()
}

#[test]
fn a_chain_solves_a_banded_joint_system_whose_work_does_not_grow_with_its_length() {
    let mut iterations = Vec::new();
    for n in [10, 100] {
        let mut lgvi = chain(n);
        // Two hinges per body at most, 5 rows each: rows of neighbours are within 2·5 − 1.
        assert!(
            lgvi.joints().bandwidth() <= 9,
            "bandwidth {}",
            lgvi.joints().bandwidth()
        );
        for _ in 0..20 {
            lgvi.step().unwrap();
        }
        let open = lgvi
            .joint_rows()
            .values
            .iter()
            .fold(0.0, |a: f64, g| max_or_nan(a, g.abs()));
        assert!(open < 1e-11, "N = {n}: joint residual {open:e}");
        iterations.push(lgvi.statistics().joint_iterations as f64 / 20.0);
    }
    assert!(
        iterations[1] <= iterations[0] + 1.0,
        "Newton iterations per step: {iterations:?}"
    );
}

#[test]
fn an_initial_state_off_the_joints_is_refused_with_its_row_and_residual() {
    let (system, joints) = double_pendulum();
    let mut state = double_pendulum_state(&system, THETA0, RATE0);
    state.positions[3] += 0.01; // the second rod moved along x by 1 cm
    let error =
        MultibodyLgvi::new(system, joints, state, 0.01, LgviOptions::default()).unwrap_err();
    match error {
        Error::Setup(SetupError::InitialPositionOffConstraint {
            index, residual, ..
        }) => {
            assert!(
                (5..8).contains(&index),
                "a row of the second hinge: {index}"
            );
            assert!((residual.abs() - 0.01).abs() < 1e-12, "{residual}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn project_closes_the_joints_and_the_run_then_starts() {
    let (system, joints) = double_pendulum();
    let mut state = double_pendulum_state(&system, THETA0, RATE0);
    state.positions[3] += 0.01;
    state.linear_momenta[5] += 0.1;
    let projected = initial::project(&system, &joints, &state).unwrap();
    let mut lgvi =
        MultibodyLgvi::new(system, joints, projected, 0.01, LgviOptions::default()).unwrap();
    lgvi.step().unwrap();
}

#[test]
fn redundant_joints_are_refused() {
    let (system, _) = double_pendulum();
    let half = Vec3::new(0.0, 0.0, ROD / 2.0);
    let ball = |b| Joint::new(b, [Vec3::zeros(), half], JointKind::Spherical).unwrap();
    let joints = JointSet::new(
        vec![
            ball([None, Some(0)]),
            ball([None, Some(0)]),
            hinge([Some(0), Some(1)], [-half, half]),
        ],
        2,
    )
    .unwrap();
    let state = double_pendulum_state(&system, THETA0, [0.0, 0.0]);
    let error =
        MultibodyLgvi::new(system, joints, state, 0.01, LgviOptions::default()).unwrap_err();
    assert!(
        matches!(
            error,
            Error::Setup(SetupError::SingularConstraintMass { .. })
        ),
        "{error}"
    );
}

#[test]
fn a_joint_naming_a_missing_body_is_refused() {
    let joint = Joint::new([None, Some(3)], [Vec3::zeros(); 2], JointKind::Spherical).unwrap();
    assert!(JointSet::new(vec![joint], 2).is_err());
}
