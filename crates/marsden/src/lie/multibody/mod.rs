//! Multibody systems: rigid bodies joined by joints, stepped by a constrained LGVI.
//!
//! Each body lives on SO(3) × ℝ³ (or SO(3) about a fixed point, [`crate::lie::body`]); a joint
//! ([`joint`]: spherical, revolute, prismatic, fixed, distance) is a set of holonomic constraints
//! `g(R, x) = 0` between two bodies or a body and the ground. The step ([`step`]) adds the joints'
//! reactions with one multiplier per row to the LGVI of [`crate::lie::lgvi`], imposes the joints
//! at the end of each step (SHAKE-type) and projects the momenta onto the hidden constraint
//! (RATTLE-type), the constrained discrete mechanics of [LMO08] on the bodies' groups. The joint
//! system is banded for a chain ([`joints`]), so a step of an `N`-link chain costs `O(N)`.
//!
//! * [`chain`]: a hanging chain of `N` rods (the scaling case);
//! * [`frames`]: points and directions of the joint's sides, with their derivatives;
//! * [`joint`]: one joint's rows and their gradients;
//! * [`joints`]: the set of joints, the banded matrices of the step;
//! * [`gravity`]: a uniform field `g` acting on every mass;
//! * [`spring`]: springs between body points, a potential; [`sum`]: the sum of two potentials
//!   (the field and the springs);
//! * [`damper`]: dampers between body points, loads that depend on the velocities;
//! * [`initial`]: checking an initial state against the joints, or moving it onto them;
//! * [`step`]: the stepper [`step::MultibodyLgvi`].
//!
//! ```
//! use marsden::lie::{body::{Inertia, RigidBody}, lgvi::LgviOptions, so3::{Mat3, Vec3},
//!     state::{BodyInitial, RigidState, RigidSystem}};
//! use marsden::lie::multibody::{gravity::GravityField, joint::{Joint, JointKind},
//!     joints::JointSet, step::MultibodyLgvi};
//! // A rod of length 1 hanging from the origin by a ball joint at its top end (the 3D pendulum).
//! let rod = RigidBody::free(Inertia::principal([1.0 / 12.0, 1.0 / 12.0, 1e-3])?, 1.0)?;
//! let gravity = GravityField { g: [0.0, 0.0, -9.81], masses: vec![1.0], first_moments: vec![[0.0; 3]] };
//! let system = RigidSystem::new(vec![rod], gravity);
//! let ball = Joint::new([None, Some(0)], [Vec3::zeros(), Vec3::new(0.0, 0.0, 0.5)], JointKind::Spherical)?;
//! let joints = JointSet::new(vec![ball], 1)?;
//! let start = BodyInitial { position: [0.0, 0.0, -0.5], ..BodyInitial::rotating(&Mat3::identity(), &Vec3::new(0.0, 0.0, 0.1)) };
//! let state = RigidState::new(&system, 0.0, &[start])?;
//! let mut lgvi = MultibodyLgvi::new(system, joints, state, 0.01, LgviOptions::default())?;
//! for _ in 0..100 { lgvi.step()?; }
//! assert!(lgvi.joint_rows().values.iter().all(|g| g.abs() < 1e-12));
//! # Ok::<(), marsden::Error>(())
//! ```
//!
//! [LMO08]: crate#references

pub mod chain;
pub mod damper;
pub mod frames;
pub mod gravity;
pub mod initial;
pub mod joint;
pub mod joints;
pub mod spring;
pub mod step;
pub mod sum;
