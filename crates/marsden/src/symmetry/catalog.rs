//! The symmetries declared by catalog systems ([`crate::systems`]).
//!
//! | system | symmetries | conserved (`J_H`) |
//! |---|---|---|
//! | [`Kepler`] | planar rotations `SO(2)` | angular momentum `x p_y − y p_x` |
//! | [`NBody`] | translations `ℝ³`, rotations `SO(3)` | total linear and angular momentum |
//! | [`PointRigidBody`] | translations `ℝ³`, rotations `SO(3)` | total linear and angular momentum |
//!
//! (Hénon–Heiles has only the discrete symmetry of order three, no continuous one; the planar
//! pendula have none. A spherical pendulum hanging from the origin is invariant under
//! [`AxisRotation::about_z`]`(1)`.)

use super::{AxisRotation, DeclaresSymmetries, Rotations, Symmetry, Translations};
use crate::systems::{Kepler, NBody, PointRigidBody};

impl DeclaresSymmetries for Kepler {
    fn symmetries(&self) -> Vec<Symmetry> {
        vec![Symmetry::AxisRotation(AxisRotation::planar(1))]
    }
}

impl DeclaresSymmetries for NBody {
    fn symmetries(&self) -> Vec<Symmetry> {
        particles_in_space(self.bodies())
    }
}

impl DeclaresSymmetries for PointRigidBody {
    fn symmetries(&self) -> Vec<Symmetry> {
        particles_in_space(self.bodies())
    }
}

/// Translations and rotations of `k` particles in `ℝ³`.
fn particles_in_space(k: usize) -> Vec<Symmetry> {
    vec![
        Symmetry::Translations(Translations::new(k, 3)),
        Symmetry::Rotations(Rotations::new(k)),
    ]
}
