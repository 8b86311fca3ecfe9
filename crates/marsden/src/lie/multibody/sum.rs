//! The sum of two potentials of the same bodies, `U = U₁ + U₂` (e.g. gravity and springs).

use crate::lie::potential::RigidPotential;
use crate::numerics::scratch::Buffer;
use crate::scalar::Scalar;

/// Inline capacity of the second term's gradient buffers (four bodies stay on the stack).
const INLINE: usize = 36;

/// `U = U₁ + U₂`; its gradient is closed-form when both terms' are (a term that is
/// [`RigidPotential::ZERO`] is skipped), and otherwise the body moment is taken by automatic
/// differentiation of the sum.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PotentialSum<A, B> {
    /// `U₁`.
    pub first: A,
    /// `U₂`.
    pub second: B,
}

impl<A: RigidPotential, B: RigidPotential> RigidPotential for PotentialSum<A, B> {
    const ZERO: bool = A::ZERO && B::ZERO;

    fn value<S: Scalar>(&self, t: S, rotations: &[S], positions: &[S]) -> S {
        let mut u = S::from(0.0);
        if !A::ZERO {
            u += self.first.value(t, rotations, positions);
        }
        if !B::ZERO {
            u += self.second.value(t, rotations, positions);
        }
        u
    }

    fn gradient(
        &self,
        t: f64,
        rotations: &[f64],
        positions: &[f64],
        d_rotations: &mut [f64],
        d_positions: &mut [f64],
    ) -> bool {
        if !A::ZERO
            && !self
                .first
                .gradient(t, rotations, positions, d_rotations, d_positions)
        {
            return false;
        }
        if B::ZERO {
            return true;
        }
        // The second term writes into zeroed buffers of its own (a term may assign rather than
        // add), which are then added.
        let mut rotation_part = Buffer::<f64, INLINE>::empty();
        let rotation_part = rotation_part.filled(d_rotations.len(), 0.0);
        let mut position_part = Buffer::<f64, INLINE>::empty();
        let position_part = position_part.filled(d_positions.len(), 0.0);
        if !(self.second).gradient(t, rotations, positions, rotation_part, position_part) {
            return false;
        }
        for (d, g) in d_rotations.iter_mut().zip(rotation_part.iter()) {
            *d += g;
        }
        for (d, g) in d_positions.iter_mut().zip(position_part.iter()) {
            *d += g;
        }
        true
    }
}
