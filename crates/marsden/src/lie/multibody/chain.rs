//! A hanging chain of `N` uniform rods joined by hinges: the scaling case of the joint solve.
//!
//! Rod `i` (mass `m`, length `ℓ`, body axis `e₃` along the rod, moments `mℓ²/12` across it) hangs
//! from rod `i − 1` (rod 0 from the ground at the origin) by a hinge about `e_y` at their common
//! end. Rod `i` starts at the angle `θ_i = θ̂ sin(0.7 i)` from the downward vertical with rate
//! `θ̇_i = ω̂ cos(1.3 i)`, a state on the joints by construction (a smooth, non-uniform shape
//! that exercises every hinge).

use super::gravity::GravityField;
use super::joint::{Joint, JointKind};
use super::joints::JointSet;
use crate::error::Error;
use crate::lie::body::{Inertia, RigidBody};
use crate::lie::so3::{Vec3, exp, rows};
use crate::lie::state::{BodyInitial, RigidState, RigidSystem};

/// The data of a hanging chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HangingChain {
    /// Number of rods `N`.
    pub links: usize,
    /// Each rod's mass `m`.
    pub mass: f64,
    /// Each rod's length `ℓ`.
    pub length: f64,
    /// Each rod's moment about its own axis (small: a slender rod).
    pub axial_moment: f64,
    /// The acceleration of gravity (along `−e₃`).
    pub g: f64,
    /// The amplitude `θ̂` of the initial angles.
    pub angle: f64,
    /// The amplitude `ω̂` of the initial rates.
    pub rate: f64,
}

impl HangingChain {
    /// `N` rods of unit mass and length under `g = 9.81`, `θ̂ = 0.3`, `ω̂ = 0.2`.
    pub fn new(links: usize) -> Self {
        Self {
            links,
            mass: 1.0,
            length: 1.0,
            axial_moment: 1e-3,
            g: 9.81,
            angle: 0.3,
            rate: 0.2,
        }
    }

    /// The system, its hinges (listed along the chain: the joint matrix is banded) and the
    /// initial state.
    ///
    /// # Errors
    /// Those of the inertia, body and state constructors for invalid data.
    pub fn build(&self) -> Result<(RigidSystem<GravityField>, JointSet, RigidState), Error> {
        let (n, l, m) = (self.links, self.length, self.mass);
        let across = m * l * l / 12.0;
        let rod = RigidBody::free(Inertia::principal([across, across, self.axial_moment])?, m)?;
        let half = Vec3::new(0.0, 0.0, l / 2.0);
        let axes = [Vec3::y(), Vec3::y()];
        let mut joints = Vec::with_capacity(n);
        for i in 0..n {
            let (upper, point) = if i == 0 {
                (None, Vec3::zeros())
            } else {
                (Some(i - 1), -half)
            };
            joints.push(Joint::new(
                [upper, Some(i)],
                [point, half],
                JointKind::Revolute { axes },
            )?);
        }
        let gravity = GravityField {
            g: [0.0, 0.0, -self.g],
            masses: vec![m; n],
            first_moments: vec![[0.0; 3]; n],
        };
        let system = RigidSystem::new(vec![rod; n], gravity);
        let joints = JointSet::new(joints, n)?;
        let mut bodies = Vec::with_capacity(n);
        let (mut top, mut top_velocity) = (Vec3::zeros(), Vec3::zeros());
        for i in 0..n {
            let theta = self.angle * (0.7 * i as f64).sin();
            let rate = self.rate * (1.3 * i as f64).cos();
            let along = Vec3::new(theta.sin(), 0.0, theta.cos());
            let turning = Vec3::new(theta.cos(), 0.0, -theta.sin()) * rate;
            let x = top - along * (l / 2.0);
            let v = top_velocity - turning * (l / 2.0);
            bodies.push(BodyInitial {
                attitude: rows(&exp(&Vec3::new(0.0, theta, 0.0))),
                angular_momentum: [0.0, across * rate, 0.0],
                position: [x.x, x.y, x.z],
                linear_momentum: [m * v.x, m * v.y, m * v.z],
            });
            top -= along * l;
            top_velocity -= turning * l;
        }
        let state = RigidState::new(&system, 0.0, &bodies)?;
        Ok((system, joints, state))
    }
}
