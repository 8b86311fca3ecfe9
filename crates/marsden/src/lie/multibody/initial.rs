//! Initial states of jointed bodies: checked against the joints, or moved onto them.
//!
//! A state satisfies the joints when `g(R, x) = 0` (positions) and `G · (J⁻¹Π, p/m) = 0` (the
//! hidden constraint: the rows' rates vanish). [`project`] moves a nearby state onto both, the
//! positions by Gauss–Newton along the mass-weighted directions `δ = −W Gᵀ ν`,
//! `G W Gᵀ ν = g` (`W = diag(J⁻¹, I/m)`; each attitude turned by `exp(ξ^)`, so it stays a
//! rotation), then the momenta by the projection of the step ([`super::step`]).

use super::joint::JointKind;
use super::joints::{BodyWeight, JointRows, JointSet};
use crate::error::{Error, InputError, SetupError};
use crate::lie::potential::{ExternalLoads, RigidPotential};
use crate::lie::so3::{Vec3, exp};
use crate::lie::state::{RigidState, RigidSystem};
use crate::numerics::banded::{BandLu, Banded};
use crate::numerics::dense::max_norm;

/// Relative tolerance of an initial state's joint residuals (positions and rates).
pub const INITIAL_TOLERANCE: f64 = 1e-10;

/// Iterations of the position projection.
const PROJECTION_ITERATIONS: usize = 50;

/// The joints' length scale: 1 or the largest joint point and body position, whichever is
/// larger (residuals of positions are judged relative to it).
pub fn length_scale(joints: &JointSet, state: &RigidState) -> f64 {
    let points = joints
        .joints()
        .iter()
        .flat_map(|j| j.points.iter().map(|p| p.amax()));
    points
        .chain(state.positions.iter().map(|x| x.abs()))
        .fold(1.0, f64::max)
}

/// The joint rows at `state`, after checking that it satisfies the joints.
///
/// # Errors
/// [`InputError::ParticleJoint`] for a joint that acts on a particle off its position or on
/// its attitude, [`SetupError::InitialPositionOffConstraint`] (the most violated row; the problem layer names
/// its joint), [`SetupError::SingularConstraintMass`] when `G W Gᵀ` is singular (redundant or
/// singular joints), [`SetupError::InitialVelocityNotTangent`].
pub fn check<U, E>(
    system: &RigidSystem<U, E>,
    joints: &JointSet,
    state: &RigidState,
) -> Result<JointRows, Error> {
    particles_joined_at_their_position(system, joints)?;
    let mut rows = JointRows::new(joints.rows());
    joints.evaluate(
        &system.bodies,
        &state.rotations,
        &state.positions,
        &mut rows,
    );
    let length = length_scale(joints, state);
    let (index, residual) = worst(&rows.values);
    let tolerance = INITIAL_TOLERANCE * length;
    let holds = residual.abs() <= tolerance; // false for a NaN residual
    if !holds {
        return Err(Error::Setup(SetupError::InitialPositionOffConstraint {
            index,
            residual,
            tolerance,
        }));
    }
    let mut lu = BandLu::new();
    factor_weighted(system, joints, state, &rows, &mut lu)?;
    let mut rates = vec![0.0; joints.rows()];
    let (omega, velocity, speed) = velocities(system, state);
    joints.rates(&rows, &omega, &velocity, &mut rates);
    let (index, residual) = worst(&rates);
    let tolerance = INITIAL_TOLERANCE * (1.0 + speed * length);
    let tangent = residual.abs() <= tolerance; // false for a NaN rate
    if !tangent {
        return Err(Error::Setup(SetupError::InitialVelocityNotTangent {
            what: "angular and linear momenta",
            index,
            residual,
            tolerance,
        }));
    }
    Ok(rows)
}

/// `state` moved onto the joints: positions, then momenta (module docs).
///
/// # Errors
/// [`SetupError::PositionProjectionFailed`] when the positions do not converge (the joints
/// cannot be closed near the state), [`SetupError::SingularConstraintMass`] for redundant joints.
pub fn project<U: RigidPotential, E: ExternalLoads>(
    system: &RigidSystem<U, E>,
    joints: &JointSet,
    state: &RigidState,
) -> Result<RigidState, Error> {
    particles_joined_at_their_position(system, joints)?;
    let mut state = state.clone();
    let mut rows = JointRows::new(joints.rows());
    let mut lu = BandLu::new();
    let length = length_scale(joints, &state);
    let m = system.bodies.len();
    for iteration in 0..=PROJECTION_ITERATIONS {
        joints.evaluate(
            &system.bodies,
            &state.rotations,
            &state.positions,
            &mut rows,
        );
        let (index, residual) = worst(&rows.values);
        if residual.abs() <= 1e-14 * length {
            break;
        }
        if iteration == PROJECTION_ITERATIONS || !residual.is_finite() {
            return Err(Error::Setup(SetupError::PositionProjectionFailed {
                iterations: iteration,
                index,
                residual,
            }));
        }
        let mut nu = rows.values.clone();
        factor_weighted(system, joints, &state, &rows, &mut lu)?;
        lu.solve(&mut nu);
        let (mut turns, mut shifts) = (vec![Vec3::zeros(); m], vec![Vec3::zeros(); m]);
        joints.add_transpose(&rows, &nu, &mut turns, &mut shifts);
        for (i, body) in system.bodies.iter().enumerate() {
            let xi = -(body.inertia.inverse() * turns[i]);
            let r = state.rotation(i);
            state.set_rotation(i, &(r * exp(&xi)));
            if let Some(mass) = body.mass {
                let x = state.position(i) - shifts[i] / mass;
                state.set_position(i, &x);
            }
        }
    }
    let (omega, velocity, _) = velocities(system, &state);
    let mut nu = vec![0.0; joints.rows()];
    joints.rates(&rows, &omega, &velocity, &mut nu);
    factor_weighted(system, joints, &state, &rows, &mut lu)?;
    lu.solve(&mut nu);
    let (mut turns, mut shifts) = (vec![Vec3::zeros(); m], vec![Vec3::zeros(); m]);
    joints.add_transpose(&rows, &nu, &mut turns, &mut shifts);
    for (i, body) in system.bodies.iter().enumerate() {
        let pi = state.momentum(i) - turns[i];
        state.set_momentum(i, &pi);
        if body.mass.is_some() {
            let p = state.linear_momentum(i) - shifts[i];
            state.set_linear_momentum(i, &p);
        }
    }
    Ok(state)
}

/// Factors `G W Gᵀ` (`W = diag(J⁻¹, I/m)`) into `lu`.
/// Every joint on a particle is spherical or a distance joint, at the particle's position: its
/// rows then have no moment on the particle, which does not turn ([`RigidBody::particle`]).
///
/// # Errors
/// [`InputError::ParticleJoint`] for the first that is not.
///
/// [`RigidBody::particle`]: crate::lie::body::RigidBody::particle
pub fn particles_joined_at_their_position<U, E>(
    system: &RigidSystem<U, E>,
    joints: &JointSet,
) -> Result<(), Error> {
    for (index, joint) in joints.joints().iter().enumerate() {
        for (side, body) in joint.bodies.iter().enumerate() {
            let Some(body) = *body else { continue };
            if !system.bodies.get(body).is_some_and(|b| b.particle) {
                continue;
            }
            let point = joint.points[side];
            let turns = !matches!(
                joint.kind,
                JointKind::Spherical | JointKind::Distance { .. }
            );
            if turns || point != Vec3::zeros() {
                let where_ = match turns {
                    true => String::new(),
                    false => format!(" at [{}, {}, {}]", point.x, point.y, point.z),
                };
                return Err(Error::Input(InputError::ParticleJoint {
                    joint: index,
                    kind: joint.kind.name(),
                    body,
                    where_,
                }));
            }
        }
    }
    Ok(())
}

fn factor_weighted<U, E>(
    system: &RigidSystem<U, E>,
    joints: &JointSet,
    state: &RigidState,
    rows: &JointRows,
    lu: &mut BandLu,
) -> Result<(), Error> {
    let weights: Vec<BodyWeight> = system
        .bodies
        .iter()
        .map(|b| BodyWeight {
            rotation: *b.inertia.inverse(),
            translation: b.mass.map_or(0.0, |m| 1.0 / m),
        })
        .collect();
    let mut a = Banded::new(joints.rows(), joints.bandwidth());
    joints.assemble(rows, rows, &weights, 1.0, &mut a);
    lu.factor(&a).map_err(|singular| {
        Error::Setup(SetupError::SingularConstraintMass {
            t: state.t,
            q: state.positions.clone(),
            pivot: singular.pivot,
        })
    })
}

/// The bodies' `ω = J⁻¹Π`, `v = p/m`, and the largest speed `max(|ω|, |v|)`.
fn velocities<U, E>(system: &RigidSystem<U, E>, state: &RigidState) -> (Vec<Vec3>, Vec<Vec3>, f64) {
    let mut speed: f64 = 0.0;
    let mut omega = Vec::with_capacity(system.bodies.len());
    let mut velocity = Vec::with_capacity(system.bodies.len());
    for (i, body) in system.bodies.iter().enumerate() {
        let w = body.inertia.inverse() * state.momentum(i);
        let v = body
            .mass
            .map_or(Vec3::zeros(), |m| state.linear_momentum(i) / m);
        speed = speed
            .max(max_norm(w.as_slice()))
            .max(max_norm(v.as_slice()));
        omega.push(w);
        velocity.push(v);
    }
    (omega, velocity, speed)
}

/// The index and value of the entry of largest magnitude (a NaN wins: it is never small).
fn worst(values: &[f64]) -> (usize, f64) {
    let mut best = (0, 0.0_f64);
    for (k, &v) in values.iter().enumerate() {
        if v.is_nan() || v.abs() > best.1.abs() {
            best = (k, v);
            if v.is_nan() {
                break;
            }
        }
    }
    best
}
