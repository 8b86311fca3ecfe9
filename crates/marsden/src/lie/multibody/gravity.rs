//! A uniform gravitational field `g ∈ ℝ³` acting on every body's mass.

use crate::lie::potential::RigidPotential;
use crate::scalar::Scalar;

/// `U = −Σᵢ mᵢ g·xᵢ − Σⱼ g·(Rⱼ cⱼ)`: the free bodies' masses at their centres `xᵢ`, and for a body
/// turning about a fixed point its first moment `cⱼ = mⱼXⱼ` (mass times the body-frame position
/// of its centre of mass). [`crate::lie::potential::UniformGravity`] is the case `g = −g e₃`.
#[derive(Debug, Clone, PartialEq)]
pub struct GravityField {
    /// The acceleration of gravity, a spatial vector (e.g. `[0, 0, −9.81]`).
    pub g: [f64; 3],
    /// `mᵢ` per body (0 for a body with a fixed point).
    pub masses: Vec<f64>,
    /// `cⱼ` per body (zero for a free body).
    pub first_moments: Vec<[f64; 3]>,
}

impl RigidPotential for GravityField {
    fn value<S: Scalar>(&self, _t: S, rotations: &[S], positions: &[S]) -> S {
        let mut u = S::from(0.0);
        for (i, m) in self.masses.iter().enumerate() {
            for (a, g) in self.g.iter().enumerate() {
                u -= positions[3 * i + a] * (*m * *g);
            }
        }
        for (i, c) in self.first_moments.iter().enumerate() {
            for (a, g) in self.g.iter().enumerate() {
                let row = &rotations[9 * i + 3 * a..9 * i + 3 * a + 3];
                u -= (row[0] * c[0] + row[1] * c[1] + row[2] * c[2]) * *g;
            }
        }
        u
    }

    /// `∂U/∂xᵢ = −mᵢ g`, `∂U/∂(Rⱼ)_ab = −g_a (cⱼ)_b`.
    fn gradient(
        &self,
        _t: f64,
        _rotations: &[f64],
        _positions: &[f64],
        d_rotations: &mut [f64],
        d_positions: &mut [f64],
    ) -> bool {
        for (i, m) in self.masses.iter().enumerate() {
            for a in 0..3 {
                d_positions[3 * i + a] = -m * self.g[a];
            }
        }
        for (i, c) in self.first_moments.iter().enumerate() {
            for a in 0..3 {
                for b in 0..3 {
                    d_rotations[9 * i + 3 * a + b] = -self.g[a] * c[b];
                }
            }
        }
        true
    }
}
