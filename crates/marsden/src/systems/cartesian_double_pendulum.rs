//! The planar double pendulum in Cartesian coordinates with two distance constraints:
//! `q = (x₁, y₁, x₂, y₂)`, gravity `g` along `−y`,
//!
//! ```text
//!     L = ½ m₁ |v₁|² + ½ m₂ |v₂|² − g (m₁ y₁ + m₂ y₂),
//!     φ₁ = ½ (|x₁|² − l₁²) = 0,      φ₂ = ½ (|x₂ − x₁|² − l₂²) = 0.
//! ```
//!
//! The same system as [`crate::systems::DoublePendulum`] in angle coordinates (both angles from
//! the downward vertical): `x₁ = l₁ (sin θ₁, −cos θ₁)`, `x₂ = x₁ + l₂ (sin θ₂, −cos θ₂)`
//! ([`CartesianDoublePendulum::initial`] maps angle data to consistent Cartesian data). The two
//! descriptions give the same motion; their discretisations differ at `O(h²)`.

use super::DoublePendulum;
use crate::error::Error;
use crate::mechanics::{Constraint, Initial, Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// Cartesian double pendulum; it is both the [`Lagrangian`] and the [`Constraint`] (two rods) of
/// the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianDoublePendulum {
    /// Upper mass (default 1).
    pub m1: f64,
    /// Lower mass (default 1).
    pub m2: f64,
    /// Upper rod length (default 1).
    pub l1: f64,
    /// Lower rod length (default 1).
    pub l2: f64,
    /// Gravity (default 1).
    pub g: f64,
}

impl Default for CartesianDoublePendulum {
    fn default() -> Self {
        Self::from(DoublePendulum::default())
    }
}

impl From<DoublePendulum> for CartesianDoublePendulum {
    fn from(p: DoublePendulum) -> Self {
        Self {
            m1: p.m1,
            m2: p.m2,
            l1: p.l1,
            l2: p.l2,
            g: p.g,
        }
    }
}

impl CartesianDoublePendulum {
    /// Consistent Cartesian initial data from angles `θ = (θ₁, θ₂)` and rates `θ̇`: positions as
    /// in [`DoublePendulum::positions`] and their time derivatives.
    pub fn initial(&self, theta: [f64; 2], theta_dot: [f64; 2]) -> Initial {
        let (s1, c1) = theta[0].sin_cos();
        let (s2, c2) = theta[1].sin_cos();
        let (l1, l2) = (self.l1, self.l2);
        let q = [l1 * s1, -l1 * c1, l1 * s1 + l2 * s2, -l1 * c1 - l2 * c2];
        let (u1, w1) = (l1 * theta_dot[0] * c1, l1 * theta_dot[0] * s1);
        let v = [
            u1,
            w1,
            u1 + l2 * theta_dot[1] * c2,
            w1 + l2 * theta_dot[1] * s2,
        ];
        Initial::velocity(&q, &v)
    }

    /// The angles `(θ₁, θ₂)` of a Cartesian configuration.
    pub fn angles(q: &[f64]) -> [f64; 2] {
        [q[0].atan2(-q[1]), (q[2] - q[0]).atan2(q[1] - q[3])]
    }

    /// Energy `|p₁|²/2m₁ + |p₂|²/2m₂ + g (m₁ y₁ + m₂ y₂)` (for tangent momenta).
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        let kinetic = 0.5 * (p[0] * p[0] + p[1] * p[1]) / self.m1
            + 0.5 * (p[2] * p[2] + p[3] * p[3]) / self.m2;
        kinetic + self.g * (self.m1 * q[1] + self.m2 * q[3])
    }
}

impl Lagrangian for CartesianDoublePendulum {
    const FIXED_DOF: Option<usize> = Some(4);
    fn dof(&self) -> usize {
        4
    }
    /// Separable with a constant diagonal mass: RATTLE takes its closed form
    /// ([`crate::holonomic::Rattle`]).
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m1, self.m1, self.m2, self.m2]),
        }
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let kinetic = (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m1)
            + (v[2] * v[2] + v[3] * v[3]) * (0.5 * self.m2);
        kinetic - (q[1] * self.m1 + q[3] * self.m2) * self.g
    }
}

impl Constraint for CartesianDoublePendulum {
    fn count(&self) -> usize {
        2
    }
    #[inline(always)]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let (dx, dy) = (q[2] - q[0], q[3] - q[1]);
        out[0] = (q[0] * q[0] + q[1] * q[1] - self.l1 * self.l1) * 0.5;
        out[1] = (dx * dx + dy * dy - self.l2 * self.l2) * 0.5;
    }
    fn validate(&self, dof: usize) -> Result<(), Error> {
        Error::check_len(
            "Cartesian double pendulum coordinates (dof)",
            &[0.0; 4],
            dof,
        )
    }
}
