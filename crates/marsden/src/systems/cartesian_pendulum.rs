//! The planar pendulum in Cartesian coordinates: a point mass `m` on `|q| = l` in the plane,
//! gravity `g` along `−y`,
//!
//! ```text
//!     L = ½ m |v|² − m g y,      φ(q) = ½ (|q|² − l²) = 0.
//! ```
//!
//! The same motion as [`crate::systems::Pendulum`] (`θ` from the downward vertical,
//! `q = l (sin θ, −cos θ)`), written with a distance constraint; it is the benchmark problem
//! "pendulum with distance constraint" of `bench/README.md` (trep's constrained MidpointVI).

use crate::error::Error;
use crate::mechanics::{Constraint, Initial, Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// Planar pendulum in Cartesian coordinates; it is both the [`Lagrangian`] and the
/// [`Constraint`] of the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartesianPendulum {
    /// Bob mass (default 1).
    pub m: f64,
    /// Rod length (default 1).
    pub l: f64,
    /// Gravity (default 1).
    pub g: f64,
}

impl Default for CartesianPendulum {
    fn default() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 1.0,
        }
    }
}

impl CartesianPendulum {
    /// Consistent initial data from the angle `θ` (from the downward vertical) and its rate:
    /// `q = l (sin θ, −cos θ)`, `v = l θ̇ (cos θ, sin θ)`.
    pub fn initial(&self, theta: f64, theta_dot: f64) -> Initial {
        let (s, c) = theta.sin_cos();
        let l = self.l;
        Initial::velocity(&[l * s, -l * c], &[l * theta_dot * c, l * theta_dot * s])
    }

    /// The angle `θ = atan2(x, −y)` of a position.
    pub fn angle(q: &[f64]) -> f64 {
        q[0].atan2(-q[1])
    }

    /// Energy `|p|²/2m + m g y` (the Hamiltonian for momenta tangent to the circle).
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        0.5 * (p[0] * p[0] + p[1] * p[1]) / self.m + self.m * self.g * q[1]
    }
}

impl Lagrangian for CartesianPendulum {
    const FIXED_DOF: Option<usize> = Some(2);
    fn dof(&self) -> usize {
        2
    }
    /// Separable with a constant diagonal mass: RATTLE takes its closed form
    /// ([`crate::holonomic::Rattle`]).
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m; 2]),
        }
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] + v[1] * v[1]) * (0.5 * self.m) - q[1] * (self.m * self.g)
    }
}

impl Constraint for CartesianPendulum {
    fn count(&self) -> usize {
        1
    }
    #[inline(always)]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] - self.l * self.l) * 0.5;
    }
    fn validate(&self, dof: usize) -> Result<(), Error> {
        Error::check_len("Cartesian pendulum coordinates (dof)", &[0.0; 2], dof)
    }
}
