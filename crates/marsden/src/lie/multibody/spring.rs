//! Linear springs between points of bodies (or a body and the ground), a potential of the
//! bodies' configuration.
//!
//! A spring joins the point `X_a` of side `a` to the point `X_b` of side `b` (body-frame points;
//! a space-frame point for the ground). With `p = x + R X` the point in space and
//! `d = p_b − p_a`,
//!
//! ```text
//! U = ½ k (‖d‖ − ℓ₀)²,        ∂U/∂p_b = −∂U/∂p_a = k (‖d‖ − ℓ₀) d/‖d‖,
//! ∂U/∂x = ∂U/∂p,              ∂U/∂R_{jl} = (∂U/∂p)_j X_l,
//! ```
//!
//! the chain rule through `p = x + R X` ([MR99] §1.2 for the spring, [LLM07] eq. (9) for the body
//! moment the step takes from `∂U/∂R`). A rest length `ℓ₀ = 0` is the zero-length spring
//! `U = ½ k ‖d‖²`, smooth everywhere, with gradient `k d` (no division by `‖d‖`). For `ℓ₀ > 0`
//! the potential has a kink at `d = 0` (the direction is undefined there); its gradient is taken
//! as zero at that one point, the mean of its one-sided derivatives.
//!
//! [MR99]: crate#references
//! [LLM07]: crate#references

use crate::lie::potential::RigidPotential;
use crate::scalar::Scalar;

/// One spring between two points.
#[derive(Debug, Clone, PartialEq)]
pub struct Spring {
    /// The body index of each side (`None`: the ground).
    pub bodies: [Option<usize>; 2],
    /// The point in each side's frame (the space frame for the ground).
    pub points: [[f64; 3]; 2],
    /// The stiffness `k ≥ 0`.
    pub stiffness: f64,
    /// The rest length `ℓ₀ ≥ 0`.
    pub rest_length: f64,
}

/// The springs of a system, one potential: `U = Σ_s ½ k_s (‖d_s‖ − ℓ₀_s)²`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Springs {
    /// The springs.
    pub springs: Vec<Spring>,
}

/// The point `x + R X` of `side` in space (`X` itself for the ground), over any scalar.
pub fn point_in_space<S: Scalar>(
    side: Option<usize>,
    point: &[f64; 3],
    rotations: &[S],
    positions: &[S],
) -> [S; 3] {
    let Some(i) = side else {
        return point.map(S::from);
    };
    std::array::from_fn(|j| {
        let row = &rotations[9 * i + 3 * j..9 * i + 3 * j + 3];
        positions[3 * i + j] + row[0] * point[0] + row[1] * point[1] + row[2] * point[2]
    })
}

impl Spring {
    /// `d = p_b − p_a` at the configuration.
    pub fn separation<S: Scalar>(&self, rotations: &[S], positions: &[S]) -> [S; 3] {
        let a = point_in_space(self.bodies[0], &self.points[0], rotations, positions);
        let b = point_in_space(self.bodies[1], &self.points[1], rotations, positions);
        std::array::from_fn(|j| b[j] - a[j])
    }

    /// `U = ½ k (‖d‖ − ℓ₀)²` (`½ k ‖d‖²` for `ℓ₀ = 0`).
    pub fn energy<S: Scalar>(&self, rotations: &[S], positions: &[S]) -> S {
        let d = self.separation(rotations, positions);
        let squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let half_k = S::from(0.5 * self.stiffness);
        if self.rest_length == 0.0 {
            return half_k * squared;
        }
        let stretch = squared.sqrt() - S::from(self.rest_length);
        half_k * stretch * stretch
    }

    /// `∂U/∂p_b = k (‖d‖ − ℓ₀) d/‖d‖` (`k d` for `ℓ₀ = 0`; zero at `d = 0` for `ℓ₀ > 0`, module
    /// docs): the force the spring pulls side `a` with, and pushes side `b` back with.
    pub fn tension(&self, rotations: &[f64], positions: &[f64]) -> [f64; 3] {
        let d = self.separation(rotations, positions);
        if self.rest_length == 0.0 {
            return d.map(|d| self.stiffness * d);
        }
        let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        if length == 0.0 {
            return [0.0; 3];
        }
        let scale = self.stiffness * (length - self.rest_length) / length;
        d.map(|d| scale * d)
    }
}

impl RigidPotential for Springs {
    fn value<S: Scalar>(&self, _t: S, rotations: &[S], positions: &[S]) -> S {
        let mut u = S::from(0.0);
        for spring in &self.springs {
            u += spring.energy(rotations, positions);
        }
        u
    }

    /// The chain rule of the module docs, summed over the springs (added to the zeroed buffers).
    fn gradient(
        &self,
        _t: f64,
        rotations: &[f64],
        positions: &[f64],
        d_rotations: &mut [f64],
        d_positions: &mut [f64],
    ) -> bool {
        for spring in &self.springs {
            let tension = spring.tension(rotations, positions);
            for (side, sign) in [(0, -1.0), (1, 1.0)] {
                let Some(i) = spring.bodies[side] else {
                    continue;
                };
                let point = &spring.points[side];
                for j in 0..3 {
                    let g = sign * tension[j];
                    d_positions[3 * i + j] += g;
                    for l in 0..3 {
                        d_rotations[9 * i + 3 * j + l] += g * point[l];
                    }
                }
            }
        }
        true
    }
}
