//! A multibody file's system in the core's terms (`marsden::lie::multibody`): the bodies in a
//! uniform field with the springs between them, the dampers, the joints, the initial state.
//!
//! A prismatic or fixed joint locks the relative attitude `R₀ᵀR₁` its bodies start with, and a
//! distance joint without a written `length` keeps the distance they start at: both are read
//! from the initial state here, as is a spring's rest length when not written.

use marsden::error::Error;
use marsden::lie::body::RigidBody;
use marsden::lie::multibody::damper::{Damper, Dampers};
use marsden::lie::multibody::gravity::GravityField;
use marsden::lie::multibody::joint::{Joint, JointKind};
use marsden::lie::multibody::joints::JointSet;
use marsden::lie::multibody::spring::{Spring, Springs};
use marsden::lie::multibody::sum::PotentialSum;
use marsden::lie::so3::{Mat3, Vec3};
use marsden::lie::state::{RigidState, RigidSystem};

use super::multibody_potential::ExprMultibodyPotential;
use crate::problem::multibody::{JointKindSpec, JointSpec, MultibodySpec};
use crate::problem::multibody_springs::{DamperSpec, SpringSpec};

/// The core's system of a multibody file: free bodies in the field `g`, the springs' potential
/// and the file's `potential` (the dampers, which depend on velocities, go to the stepper:
/// [`dampers`]).
pub type MultibodySystem = RigidSystem<Potential>;

/// The potential of a multibody file: the field, the springs, and the written `U`.
pub type Potential = PotentialSum<GravityField, PotentialSum<Springs, ExprMultibodyPotential>>;

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
        .map(|b| match b.particle {
            true => RigidBody::particle(b.mass),
            false => RigidBody::free(b.inertia, b.mass),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let gravity = GravityField {
        g: spec.gravity,
        masses: spec.bodies.iter().map(|b| b.mass).collect(),
        first_moments: vec![[0.0; 3]; spec.bodies.len()],
    };
    let unsprung = RigidSystem::new(bodies, gravity.clone());
    let state = RigidState::new(&unsprung, t0, &spec.initial)?;
    let springs = Springs {
        springs: spec.springs.iter().map(|s| spring(s, &state)).collect(),
    };
    let written = ExprMultibodyPotential {
        program: spec.potential.clone(),
        particles: spec.bodies.iter().map(|b| b.particle).collect(),
    };
    let system = RigidSystem::new(
        unsprung.bodies,
        PotentialSum {
            first: gravity,
            second: PotentialSum {
                first: springs,
                second: written,
            },
        },
    );
    let joints = (spec.joints.iter())
        .map(|j| joint(j, &state))
        .collect::<Result<Vec<_>, _>>()?;
    let joints = JointSet::new(joints, spec.bodies.len())?;
    Ok((system, joints, state))
}

/// One spring, its rest length (if not written) the distance of its points in `state`.
fn spring(s: &SpringSpec, state: &RigidState) -> Spring {
    let mut spring = Spring {
        bodies: s.bodies,
        points: s.points,
        stiffness: s.stiffness,
        rest_length: 0.0,
    };
    spring.rest_length = s.rest_length.unwrap_or_else(|| {
        let d = spring.separation(&state.rotations, &state.positions);
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    });
    spring
}

/// The dampers of a multibody file.
pub fn dampers(spec: &MultibodySpec) -> Dampers {
    let damper = |d: &DamperSpec| Damper {
        bodies: d.bodies,
        points: d.points,
        coefficient: d.coefficient,
    };
    Dampers {
        dampers: spec.dampers.iter().map(damper).collect(),
    }
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
