//! Linear dampers between points of bodies (or a body and the ground): a force along the line
//! of the points, opposing its rate of stretch.
//!
//! With `d = p_b − p_a`, `e = d/‖d‖` and the points' velocities `ṗ = ẋ + R(Ω × X)` (zero for the
//! ground), the damper acts on side `b` with `f = −c (ḋ·e) e` at `p_b` and on side `a` with `−f`
//! at `p_a`: the forces `±f` on the centres and the body-frame torques `X × Rᵀ(±f)` (the moment
//! of a force at a body point, as the body moment of [`crate::lie::potential`]). The pair is
//! along the line of the points, so it changes neither the total linear nor the total angular
//! momentum, and it does work `−c (ḋ·e)² ≤ 0`. At `d = 0` the line is undefined and the damper
//! acts with zero force.
//!
//! The step applies these loads by the discrete Lagrange–d'Alembert principle with the
//! trapezoidal rule, `(h/2) f` at each end of the step ([MW01] §3.2, [LLM07] §4), as the loads of
//! [`crate::lie::lgvi`]; the velocities are those of the momenta at each end (`ẋ = p/m`,
//! `Ω = J⁻¹Π`), so the load at the end of a step is implicit in the end momenta
//! ([`super::step`] iterates on it).
//!
//! [MW01]: crate#references
//! [LLM07]: crate#references

use super::spring::point_in_space;
use crate::lie::body::RigidBody;
use crate::lie::potential::Loads;
use crate::lie::so3::Vec3;
use crate::lie::state::RigidState;
use crate::numerics::dense::max_or_nan;

/// One damper between two points.
#[derive(Debug, Clone, PartialEq)]
pub struct Damper {
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The point in each side's frame (the space frame for the ground).
    pub points: [[f64; 3]; 2],
    /// The coefficient `c ≥ 0`.
    pub coefficient: f64,
}

/// The dampers of a system.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Dampers {
    /// The dampers.
    pub dampers: Vec<Damper>,
}

/// The velocity in space of the point `X` of `side` (zero for the ground): `ẋ + R(Ω × X)`.
fn point_velocity(
    side: Option<usize>,
    point: &[f64; 3],
    bodies: &[RigidBody],
    state: &RigidState,
) -> Vec3 {
    let Some(i) = side else {
        return Vec3::zeros();
    };
    let body = &bodies[i];
    let omega = body.inertia.inverse() * state.momentum(i);
    let velocity = body
        .mass
        .map_or(Vec3::zeros(), |m| state.linear_momentum(i) / m);
    velocity + state.rotation(i) * omega.cross(&Vec3::from(*point))
}

impl Damper {
    /// The force `f = −c (ḋ·e) e` on side `b` at the state (zero at `d = 0`).
    pub fn force(&self, bodies: &[RigidBody], state: &RigidState) -> Vec3 {
        let d = Vec3::from(self.separation(state));
        let length = d.norm();
        if length == 0.0 {
            return Vec3::zeros();
        }
        let e = d / length;
        let rate = point_velocity(self.bodies[1], &self.points[1], bodies, state)
            - point_velocity(self.bodies[0], &self.points[0], bodies, state);
        -self.coefficient * rate.dot(&e) * e
    }

    fn separation(&self, state: &RigidState) -> [f64; 3] {
        let (r, x) = (&state.rotations, &state.positions);
        let a = point_in_space(self.bodies[0], &self.points[0], r, x);
        let b = point_in_space(self.bodies[1], &self.points[1], r, x);
        std::array::from_fn(|j| b[j] - a[j])
    }
}

impl Dampers {
    /// Whether there are no dampers.
    pub fn is_empty(&self) -> bool {
        self.dampers.is_empty()
    }

    /// Writes the dampers' body-frame torques into `moments` and their forces into `forces`
    /// (one per body each) at the state's velocities (module docs).
    pub fn loads(
        &self,
        bodies: &[RigidBody],
        state: &RigidState,
        moments: &mut [Vec3],
        forces: &mut [Vec3],
    ) {
        moments.iter_mut().for_each(|m| *m = Vec3::zeros());
        forces.iter_mut().for_each(|f| *f = Vec3::zeros());
        for damper in &self.dampers {
            let f = damper.force(bodies, state);
            for (side, sign) in [(0, -1.0), (1, 1.0)] {
                let Some(i) = damper.bodies[side] else {
                    continue;
                };
                let force = sign * f;
                let point = Vec3::from(damper.points[side]);
                moments[i] += point.cross(&(state.rotation(i).transpose() * force));
                forces[i] += force;
            }
        }
    }

    /// The power `Σ f·ḋ = −Σ c (ḋ·e)²` the dampers do at the state (≤ 0).
    pub fn power(&self, bodies: &[RigidBody], state: &RigidState) -> f64 {
        let mut power = 0.0;
        for damper in &self.dampers {
            let rate = point_velocity(damper.bodies[1], &damper.points[1], bodies, state)
                - point_velocity(damper.bodies[0], &damper.points[0], bodies, state);
            power += damper.force(bodies, state).dot(&rate);
        }
        power
    }
}

/// The dampers' part of a stepper's loads: the loads without them at the state (`base`), the
/// damping they hold now and a trial damping, so the end-of-step iteration of [`super::step`]
/// can replace the damping without evaluating the potential again.
#[derive(Debug, Clone, Default)]
pub(super) struct Damping {
    base: Loads,
    moments: Vec<Vec3>,
    forces: Vec<Vec3>,
    trial_moments: Vec<Vec3>,
    trial_forces: Vec<Vec3>,
}

impl Damping {
    /// Adds the dampers' loads at the state's velocities to `loads` (which hold the others),
    /// remembering both parts.
    pub(super) fn add(
        &mut self,
        dampers: &Dampers,
        bodies: &[RigidBody],
        state: &RigidState,
        loads: &mut Loads,
    ) {
        let m = bodies.len();
        self.base.clone_from(loads);
        self.moments.resize(m, Vec3::zeros());
        self.forces.resize(m, Vec3::zeros());
        dampers.loads(bodies, state, &mut self.moments, &mut self.forces);
        self.combine(loads);
    }

    /// Re-evaluates the dampers at the state's (new) velocities and puts them into `loads`;
    /// returns the largest change of a damping load.
    pub(super) fn update(
        &mut self,
        dampers: &Dampers,
        bodies: &[RigidBody],
        state: &RigidState,
        loads: &mut Loads,
    ) -> f64 {
        let m = bodies.len();
        self.trial_moments.resize(m, Vec3::zeros());
        self.trial_forces.resize(m, Vec3::zeros());
        dampers.loads(
            bodies,
            state,
            &mut self.trial_moments,
            &mut self.trial_forces,
        );
        let mut change = 0.0_f64;
        let pairs = (self.moments.iter().zip(&self.trial_moments))
            .chain(self.forces.iter().zip(&self.trial_forces));
        // NaN-propagating: a load that turned NaN must not look settled.
        for (old, new) in pairs {
            let difference = new - old;
            change = (difference.iter()).fold(change, |m, x| max_or_nan(m, x.abs()));
        }
        std::mem::swap(&mut self.moments, &mut self.trial_moments);
        std::mem::swap(&mut self.forces, &mut self.trial_forces);
        self.combine(loads);
        change
    }

    fn combine(&self, loads: &mut Loads) {
        for (i, total) in loads.moments.iter_mut().enumerate() {
            *total = self.base.moments[i] + self.moments[i];
        }
        for (i, total) in loads.forces.iter_mut().enumerate() {
            *total = self.base.forces[i] + self.forces[i];
        }
    }
}
