//! The planar double pendulum in angle coordinates (both angles from the downward vertical):
//!
//! ```text
//! L = ½(m₁+m₂) l₁² θ̇₁² + ½ m₂ l₂² θ̇₂² + m₂ l₁ l₂ θ̇₁ θ̇₂ cos(θ₁−θ₂)
//!     + (m₁+m₂) g l₁ cos θ₁ + m₂ g l₂ cos θ₂.
//! ```

use crate::mechanics::Lagrangian;
use crate::scalar::Scalar;

/// Double pendulum with point masses `m₁, m₂` on massless rods `l₁, l₂`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DoublePendulum {
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

impl Default for DoublePendulum {
    fn default() -> Self {
        Self {
            m1: 1.0,
            m2: 1.0,
            l1: 1.0,
            l2: 1.0,
            g: 1.0,
        }
    }
}

impl DoublePendulum {
    /// Cartesian positions `(x₁, y₁, x₂, y₂)` of the two bobs (y up).
    pub fn positions(&self, theta: &[f64]) -> [f64; 4] {
        let (s1, c1) = theta[0].sin_cos();
        let (s2, c2) = theta[1].sin_cos();
        let (x1, y1) = (self.l1 * s1, -self.l1 * c1);
        [x1, y1, x1 + self.l2 * s2, y1 - self.l2 * c2]
    }
}

impl Lagrangian for DoublePendulum {
    const FIXED_DOF: Option<usize> = Some(2);
    fn dof(&self) -> usize {
        2
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let kinetic = v[0] * v[0] * (0.5 * (m1 + m2) * l1 * l1)
            + v[1] * v[1] * (0.5 * m2 * l2 * l2)
            + v[0] * v[1] * (q[0] - q[1]).cos() * (m2 * l1 * l2);
        let potential = q[0].cos() * (-(m1 + m2) * g * l1) - q[1].cos() * (m2 * g * l2);
        kinetic - potential
    }
}
