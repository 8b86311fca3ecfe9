//! A multibody file's system in the core's terms (`marsden::lie::multibody`): the bodies in a
//! uniform field, the joints, the initial state.
//!
//! A prismatic or fixed joint locks the relative attitude `R₀ᵀR₁` its bodies start with, and a
//! distance joint without a written `length` keeps the distance they start at: both are read
//! from the initial state here.

use marsden::error::Error;
use marsden::lie::body::RigidBody;
use marsden::lie::multibody::gravity::GravityField;
use marsden::lie::multibody::joint::{Joint, JointKind};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::so3::{Mat3, Vec3};
use marsden::lie::state::{RigidState, RigidSystem};

use crate::problem::multibody::{JointKindSpec, JointSpec, MultibodySpec};

/// The core's system of a multibody file: free bodies in the field `g`, no other loads.
pub type MultibodySystem = RigidSystem<GravityField>;

/// The system, the joints and the state at `t0` of `spec`.
///
/// # Errors
/// A body or joint the core refuses (checked when the file was read), an initial attitude that
/// is not a rotation.
pub fn core(
    spec: &MultibodySpec,
    t0: f64,
) -> Result<(MultibodySystem, JointSet, RigidState), Error> {
    let bodies = (spec.bodies.iter())
        .map(|b| RigidBody::free(b.inertia, b.mass))
        .collect::<Result<Vec<_>, _>>()?;
    let gravity = GravityField {
        g: spec.gravity,
        masses: spec.bodies.iter().map(|b| b.mass).collect(),
        first_moments: vec![[0.0; 3]; spec.bodies.len()],
    };
    let system = RigidSystem::new(bodies, gravity);
    let state = RigidState::new(&system, t0, &spec.initial)?;
    let joints = (spec.joints.iter())
        .map(|j| joint(j, &state))
        .collect::<Result<Vec<_>, _>>()?;
    let joints = JointSet::new(joints, spec.bodies.len())?;
    Ok((system, joints, state))
}

/// One joint, its references read from `state`.
fn joint(j: &JointSpec, state: &RigidState) -> Result<Joint, Error> {
    let attitude = |side: Option<usize>| side.map_or(Mat3::identity(), |b| state.rotation(b));
    let position = |side: Option<usize>| side.map_or(Vec3::zeros(), |b| state.position(b));
    let reference = attitude(j.bodies[0]).transpose() * attitude(j.bodies[1]);
    let points = j.points.map(Vec3::from);
    let kind = match j.kind {
        JointKindSpec::Spherical => JointKind::Spherical,
        JointKindSpec::Revolute { axes } => JointKind::Revolute {
            axes: axes.map(Vec3::from),
        },
        JointKindSpec::Prismatic { axis } => JointKind::Prismatic {
            axis: Vec3::from(axis),
            reference,
        },
        JointKindSpec::Fixed => JointKind::Fixed { reference },
        JointKindSpec::Distance { length } => {
            let at =
                |side: usize| position(j.bodies[side]) + attitude(j.bodies[side]) * points[side];
            JointKind::Distance {
                length: length.unwrap_or_else(|| (at(1) - at(0)).norm()),
            }
        }
    };
    Joint::new(j.bodies, points, kind)
}
