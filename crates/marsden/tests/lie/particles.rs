//! Particles among jointed bodies (`RigidBody::particle`: a point mass, configuration ℝ³).
//!
//! * A uniform rod hinged at its top with a particle on a ball joint at its tip: a physical
//!   pendulum whose reduced Lagrangian in the hinge angle is known in closed form,
//!   `L = ½(I_c + mℓ²/4 + Mℓ²)θ̇² + (mℓ/2 + Mℓ)g cos θ`; the jointed step converges to it at
//!   order 2, the joints closed to round-off, the particle never turning.
//! * A particle on a distance joint (a spherical pendulum of a point mass): the vertical angular
//!   momentum `(x × p)_z` is a momentum map of the rotations about the vertical, kept to
//!   round-off (discrete Noether), the rod's length kept.
//! * A joint that would turn a particle, or hold it off its position: refused.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::tight;
use marsden::discrete::rules::Method;
use marsden::error::InputError;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::invariants;
use marsden::lie::lgvi::LgviOptions;
use marsden::lie::multibody::gravity::GravityField;
use marsden::lie::multibody::joint::{Joint, JointKind};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::multibody::step::MultibodyLgvi;
use marsden::lie::so3::{Mat3, Vec3, exp};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::numerics::dense::max_or_nan;
use marsden::{Error, Initial, Lagrangian, Problem, Scalar, SolveOptions, TimeGrid};

const G: f64 = 9.81;
const ROD: f64 = 1.0;
const MASS: f64 = 1.0;
const ACROSS: f64 = MASS * ROD * ROD / 12.0;
const BOB: f64 = 0.5;
const THETA0: f64 = 0.8;
const RATE0: f64 = -0.6;
const T_END: f64 = 1.0;

fn gravity(masses: Vec<f64>) -> GravityField {
    let first_moments = vec![[0.0; 3]; masses.len()];
    GravityField {
        g: [0.0, 0.0, -G],
        masses,
        first_moments,
    }
}

/// The rod's hinge angle `θ` from the downward vertical, reduced.
struct ReducedPendulum;

impl Lagrangian for ReducedPendulum {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (l, m) = (ROD, MASS);
        let inertia = ACROSS + m * l * l / 4.0 + BOB * l * l;
        v[0] * v[0] * (0.5 * inertia) + q[0].cos() * ((m * l / 2.0 + BOB * l) * G)
    }
}

fn options() -> LgviOptions {
    LgviOptions {
        newton: tight(),
        composition: None,
    }
}

/// The rod (body 0) hinged at the origin about `e_y`, the particle (body 1) on a ball joint at
/// its tip, started at angle `θ₀` with rate `θ̇₀`.
fn rod_with_bob(h: f64) -> MultibodyLgvi<GravityField, marsden::lie::potential::NoLoads> {
    let rod = RigidBody::free(Inertia::principal([ACROSS, ACROSS, 1e-3]).unwrap(), MASS).unwrap();
    let bob = RigidBody::particle(BOB).unwrap();
    let system = RigidSystem::new(vec![rod, bob], gravity(vec![MASS, BOB]));
    let half = Vec3::new(0.0, 0.0, ROD / 2.0);
    let axes = [Vec3::y(), Vec3::y()];
    let hinge = Joint::new(
        [None, Some(0)],
        [Vec3::zeros(), half],
        JointKind::Revolute { axes },
    );
    let ball = Joint::new(
        [Some(0), Some(1)],
        [-half, Vec3::zeros()],
        JointKind::Spherical,
    );
    let joints = JointSet::new(vec![hinge.unwrap(), ball.unwrap()], 2).unwrap();
    let dir = Vec3::new(THETA0.sin(), 0.0, THETA0.cos());
    let ddir = Vec3::new(THETA0.cos(), 0.0, -THETA0.sin()) * RATE0;
    let (x, v) = (-dir * (ROD / 2.0), -ddir * (ROD / 2.0));
    let (tip, tip_v) = (-dir * ROD, -ddir * ROD);
    let bodies = [
        BodyInitial {
            attitude: marsden::lie::so3::rows(&exp(&Vec3::new(0.0, THETA0, 0.0))),
            angular_momentum: [0.0, ACROSS * RATE0, 0.0],
            position: [x.x, x.y, x.z],
            linear_momentum: [MASS * v.x, MASS * v.y, MASS * v.z],
        },
        BodyInitial {
            position: [tip.x, tip.y, tip.z],
            linear_momentum: [BOB * tip_v.x, BOB * tip_v.y, BOB * tip_v.z],
            ..BodyInitial::rotating(&Mat3::identity(), &Vec3::zeros())
        },
    ];
    let state = RigidState::new(&system, 0.0, &bodies).unwrap();
    MultibodyLgvi::new(system, joints, state, h, options()).unwrap()
}

fn reduced_angle() -> f64 {
    let grid = TimeGrid::new(0.0, T_END / 2000.0, 2000).unwrap();
    let start = Initial::velocity(&[THETA0], &[RATE0]);
    let problem = Problem::new(ReducedPendulum, start, grid).unwrap();
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    let trajectory = problem
        .solve(&Method::parse("gauss-4").unwrap(), &options)
        .unwrap();
    trajectory.q(trajectory.len() - 1)[0]
}

#[test]
fn rod_with_a_particle_bob_is_second_order_against_its_reduced_pendulum() {
    let reference = reduced_angle();
    let mut errors = Vec::new();
    let hs = [0.02, 0.01, 0.005];
    for &h in &hs {
        let mut lgvi = rod_with_bob(h);
        let mut open: f64 = 0.0;
        for _ in 0..(T_END / h).round() as usize {
            lgvi.step().unwrap();
            open = (lgvi.joint_rows().values.iter()).fold(open, |a, g| max_or_nan(a, g.abs()));
        }
        let state = lgvi.state();
        assert_eq!(state.rotation(1), Mat3::identity(), "the particle turned");
        assert_eq!(state.momentum(1), Vec3::zeros());
        assert!(open < 1e-13, "joints open by {open:e} at h = {h}");
        let r = state.rotation(0);
        let angle = r[(0, 2)].atan2(r[(0, 0)]);
        // The bob hangs at the rod's tip: its own angle agrees.
        let x = state.position(1);
        assert!(((-x.x).atan2(-x.z) - angle).abs() < 1e-12);
        errors.push((angle - reference).abs());
    }
    let order = (errors[0] / errors[2]).log2() / 2.0;
    eprintln!("rod with a particle bob: order {order:.3}, errors {errors:?}");
    assert!(
        (order - 2.0).abs() < 0.1,
        "order {order}, errors {errors:?}"
    );
    assert!(errors[2] < 1e-3, "{errors:?}");
}

#[test]
fn spherical_pendulum_of_a_particle_keeps_its_vertical_momentum_and_length() {
    let bob = RigidBody::particle(2.0).unwrap();
    let system = RigidSystem::new(vec![bob], gravity(vec![2.0]));
    let rod = Joint::new(
        [None, Some(0)],
        [Vec3::zeros(), Vec3::zeros()],
        JointKind::Distance { length: 1.5 },
    );
    let joints = JointSet::new(vec![rod.unwrap()], 1).unwrap();
    let x = Vec3::new(0.6, 0.3, -(1.5f64.powi(2) - 0.45).sqrt());
    let v = Vec3::new(-0.5, 1.2, 0.0);
    let v = v - x * (x.dot(&v) / x.norm_squared()); // tangent to the sphere
    let start = BodyInitial {
        position: [x.x, x.y, x.z],
        linear_momentum: [2.0 * v.x, 2.0 * v.y, 2.0 * v.z],
        ..BodyInitial::rotating(&Mat3::identity(), &Vec3::zeros())
    };
    let state = RigidState::new(&system, 0.0, &[start]).unwrap();
    let mut lgvi = MultibodyLgvi::new(system, joints, state, 0.01, options()).unwrap();
    let lz = |s: &RigidState| invariants::spatial_angular_momentum(s).z;
    let (l0, e0) = (
        lz(lgvi.state()),
        invariants::energy(lgvi.system(), lgvi.state()),
    );
    let (mut drift, mut length, mut energy): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..5000 {
        lgvi.step().unwrap();
        let s = lgvi.state();
        drift = max_or_nan(drift, (lz(s) - l0).abs());
        length = max_or_nan(length, (s.position(0).norm() - 1.5).abs());
        energy = max_or_nan(energy, (invariants::energy(lgvi.system(), s) - e0).abs());
    }
    eprintln!(
        "particle pendulum: L_z {l0}, drift {drift:.2e}, length {length:.2e}, energy {energy:.2e}"
    );
    assert!(l0.abs() > 0.5);
    assert!(
        drift < 1e-12 * l0.abs(),
        "vertical momentum drift {drift:e}"
    );
    assert!(length < 1e-13, "length off by {length:e}");
    assert!(energy < 1e-2 * e0.abs(), "energy error {energy:e} of {e0}");
}

#[test]
fn joints_that_would_turn_a_particle_are_refused() {
    let system = RigidSystem::new(vec![RigidBody::particle(1.0).unwrap()], gravity(vec![1.0]));
    let start = BodyInitial {
        position: [0.0, 0.0, -1.0],
        ..BodyInitial::rotating(&Mat3::identity(), &Vec3::zeros())
    };
    let state = RigidState::new(&system, 0.0, &[start]).unwrap();
    let axes = [Vec3::y(), Vec3::y()];
    let cases = [
        (
            Joint::new(
                [None, Some(0)],
                [Vec3::new(0.0, 0.0, -1.0), Vec3::zeros()],
                JointKind::Revolute { axes },
            ),
            "",
        ),
        (
            Joint::new(
                [None, Some(0)],
                [Vec3::new(0.0, 0.0, -0.9), Vec3::new(0.0, 0.0, 0.1)],
                JointKind::Spherical,
            ),
            " at [0, 0, 0.1]",
        ),
    ];
    for (joint, where_) in cases {
        let joints = JointSet::new(vec![joint.unwrap()], 1).unwrap();
        let refused = MultibodyLgvi::new(system.clone(), joints, state.clone(), 0.01, options());
        match refused {
            Err(Error::Input(InputError::ParticleJoint {
                joint: 0,
                body: 0,
                where_: w,
                ..
            })) => {
                assert_eq!(w, where_);
            }
            other => panic!("{:?}", other.err()),
        }
    }
}
