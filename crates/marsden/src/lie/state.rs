//! A system of rigid bodies and its state `(t, R, Π, x, p)`.
//!
//! The state of body `i` is its attitude `R_i ∈ SO(3)` (body → space; 9 numbers, row-major), its
//! body angular momentum `Π_i = J_i Ω_i` (3 numbers), and for a free body the position `x_i` of
//! its centre of mass and its momentum `p_i = m_i ẋ_i` (3 + 3 numbers; zero for a body with a
//! fixed point). The state is stored flat, body after body, in that order.

use super::body::RigidBody;
use super::potential::{ExternalLoads, NoLoads, RigidPotential};
use super::so3::{Mat3, Vec3, attitude};
use crate::error::Error;

/// `m` rigid bodies, a potential coupling them, and external loads.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidSystem<U, E = NoLoads> {
    /// The bodies.
    pub bodies: Vec<RigidBody>,
    /// The potential `U(t, R, x)`.
    pub potential: U,
    /// External torques and forces (Lagrange–d'Alembert).
    pub loads: E,
}

impl<U: RigidPotential> RigidSystem<U, NoLoads> {
    /// Bodies in a potential, without external loads.
    pub fn new(bodies: Vec<RigidBody>, potential: U) -> Self {
        Self {
            bodies,
            potential,
            loads: NoLoads,
        }
    }
}

impl<U: RigidPotential, E: ExternalLoads> RigidSystem<U, E> {
    /// The same system with external loads.
    pub fn with_loads<F: ExternalLoads>(self, loads: F) -> RigidSystem<U, F> {
        RigidSystem {
            bodies: self.bodies,
            potential: self.potential,
            loads,
        }
    }

    /// Indices of the free bodies (those with a mass).
    pub fn free_bodies(&self) -> Vec<usize> {
        (0..self.bodies.len())
            .filter(|&i| self.bodies[i].mass.is_some())
            .collect()
    }
}

/// The initial data of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyInitial {
    /// `R₀`, row-major; checked to be a rotation to 1e-10 ([`attitude`]).
    pub attitude: [f64; 9],
    /// `Π₀ = JΩ₀` (body frame).
    pub angular_momentum: [f64; 3],
    /// `x₀` (free bodies; ignored otherwise).
    pub position: [f64; 3],
    /// `p₀ = m ẋ₀` (free bodies; ignored otherwise).
    pub linear_momentum: [f64; 3],
}

impl BodyInitial {
    /// A body at attitude `r` with body angular momentum `pi`, its centre (if free) at rest at
    /// the origin.
    pub fn rotating(r: &Mat3, pi: &Vec3) -> Self {
        Self {
            attitude: super::so3::rows(r),
            angular_momentum: [pi.x, pi.y, pi.z],
            position: [0.0; 3],
            linear_momentum: [0.0; 3],
        }
    }
}

/// The state `(t, R, Π, x, p)` of `m` bodies, flat: `rotations` 9 per body (row-major),
/// `momenta` (`Π`), `positions` (`x`) and `linear_momenta` (`p`) 3 per body.
#[derive(Debug, PartialEq, Default)]
pub struct RigidState {
    /// Time.
    pub t: f64,
    /// `R_i`, 9 entries per body, row-major.
    pub rotations: Vec<f64>,
    /// `Π_i`, 3 per body.
    pub momenta: Vec<f64>,
    /// `x_i`, 3 per body (zero for a body with a fixed point).
    pub positions: Vec<f64>,
    /// `p_i`, 3 per body (zero for a body with a fixed point).
    pub linear_momenta: Vec<f64>,
}

/// `clone_from` field by field, so that the step's saved copy reuses its buffers (the derived
/// one would allocate four vectors per step).
impl Clone for RigidState {
    fn clone(&self) -> Self {
        Self {
            t: self.t,
            rotations: self.rotations.clone(),
            momenta: self.momenta.clone(),
            positions: self.positions.clone(),
            linear_momenta: self.linear_momenta.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.t = source.t;
        self.rotations.clone_from(&source.rotations);
        self.momenta.clone_from(&source.momenta);
        self.positions.clone_from(&source.positions);
        self.linear_momenta.clone_from(&source.linear_momenta);
    }
}

impl RigidState {
    /// The state at `t` from one [`BodyInitial`] per body of `system` (attitudes checked and
    /// re-orthonormalised; positions and momenta of fixed-point bodies set to zero; a particle's
    /// attitude `I` and angular momentum 0).
    ///
    /// # Errors
    /// [`crate::error::InputError::DimensionMismatch`] for a wrong number of bodies,
    /// [`crate::error::InputError::NonFinite`] for non-finite data,
    /// [`crate::error::InputError::NotARotation`] for an attitude that is not a rotation.
    pub fn new<U, E>(
        system: &RigidSystem<U, E>,
        t: f64,
        bodies: &[BodyInitial],
    ) -> Result<Self, Error> {
        let m = system.bodies.len();
        if bodies.len() != m {
            return Err(Error::Input(crate::error::InputError::DimensionMismatch {
                what: "initial data of the bodies",
                expected: m,
                found: bodies.len(),
            }));
        }
        Error::check_finite("t0", &[t])?;
        let mut state = Self {
            t,
            ..Self::default()
        };
        for (body, initial) in system.bodies.iter().zip(bodies) {
            if body.particle {
                // A point mass: attitude I, angular momentum 0, whatever `initial` says.
                state
                    .rotations
                    .extend_from_slice(&super::so3::rows(&Mat3::identity()));
                state.momenta.extend_from_slice(&[0.0; 3]);
            } else {
                let r = attitude("initial attitude", &initial.attitude)?;
                state.rotations.extend_from_slice(&super::so3::rows(&r));
                Error::check_finite("initial angular momentum", &initial.angular_momentum)?;
                state.momenta.extend_from_slice(&initial.angular_momentum);
            }
            let free = body.mass.is_some();
            let (x, p) = if free {
                (initial.position, initial.linear_momentum)
            } else {
                ([0.0; 3], [0.0; 3])
            };
            Error::check_finite("initial position", &x)?;
            Error::check_finite("initial linear momentum", &p)?;
            state.positions.extend_from_slice(&x);
            state.linear_momenta.extend_from_slice(&p);
        }
        Ok(state)
    }

    /// Number of bodies.
    pub fn bodies(&self) -> usize {
        self.momenta.len() / 3
    }

    /// `R_i`.
    pub fn rotation(&self, i: usize) -> Mat3 {
        Mat3::from_row_slice(&self.rotations[9 * i..9 * i + 9])
    }

    /// `Π_i`.
    pub fn momentum(&self, i: usize) -> Vec3 {
        Vec3::from_column_slice(&self.momenta[3 * i..3 * i + 3])
    }

    /// `x_i`.
    pub fn position(&self, i: usize) -> Vec3 {
        Vec3::from_column_slice(&self.positions[3 * i..3 * i + 3])
    }

    /// `p_i`.
    pub fn linear_momentum(&self, i: usize) -> Vec3 {
        Vec3::from_column_slice(&self.linear_momenta[3 * i..3 * i + 3])
    }

    /// Writes `R_i`.
    pub fn set_rotation(&mut self, i: usize, r: &Mat3) {
        self.rotations[9 * i..9 * i + 9].copy_from_slice(&super::so3::rows(r));
    }

    /// Writes `Π_i`.
    pub fn set_momentum(&mut self, i: usize, pi: &Vec3) {
        self.momenta[3 * i..3 * i + 3].copy_from_slice(pi.as_slice());
    }

    /// Writes `x_i`.
    pub fn set_position(&mut self, i: usize, x: &Vec3) {
        self.positions[3 * i..3 * i + 3].copy_from_slice(x.as_slice());
    }

    /// Writes `p_i`.
    pub fn set_linear_momentum(&mut self, i: usize, p: &Vec3) {
        self.linear_momenta[3 * i..3 * i + 3].copy_from_slice(p.as_slice());
    }
}
