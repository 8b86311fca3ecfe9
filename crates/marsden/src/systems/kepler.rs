//! The Kepler problem in the plane, `L = ½|v|² + μ/|q|` (HLW06 §I.2).

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::numerics::banded::Banded;
use crate::scalar::Scalar;
use crate::special::SpecialError;
use crate::special::kepler::KeplerOrbit;

/// Planar Kepler problem with gravitational parameter `μ` (unit mass).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kepler {
    /// Gravitational parameter (default 1).
    pub mu: f64,
}

impl Default for Kepler {
    fn default() -> Self {
        Self { mu: 1.0 }
    }
}

impl Kepler {
    /// Pericentre initial data of eccentricity `e` with semi-major axis 1 (for μ = 1):
    /// `q = (1 − e, 0)`, `p = (0, √((1+e)/(1−e)))` (period 2π, energy −½, angular momentum √(1−e²)).
    pub fn pericentre(e: f64) -> ([f64; 2], [f64; 2]) {
        ([1.0 - e, 0.0], [0.0, ((1.0 + e) / (1.0 - e)).sqrt()])
    }

    /// Exact solution `(q(t), p(t))` from `(q₀, p₀)` at time 0 (bound orbits), by Kepler's
    /// equation `E − e sin E = M` (see [`KeplerOrbit`]).
    pub fn exact(
        &self,
        q0: [f64; 2],
        p0: [f64; 2],
        t: f64,
    ) -> Result<([f64; 2], [f64; 2]), SpecialError> {
        KeplerOrbit::new(self.mu, q0, p0)?.state(t)
    }

    /// Energy `½|p|² − μ/|q|`.
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        0.5 * (p[0] * p[0] + p[1] * p[1]) - self.mu / q[0].hypot(q[1])
    }

    /// Angular momentum `q₁p₂ − q₂p₁`.
    pub fn angular_momentum(q: &[f64], p: &[f64]) -> f64 {
        q[0] * p[1] - q[1] * p[0]
    }
}

impl Lagrangian for Kepler {
    const FIXED_DOF: Option<usize> = Some(2);
    fn dof(&self) -> usize {
        2
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] + v[1] * v[1]) * 0.5 + (q[0] * q[0] + q[1] * q[1]).sqrt().recip() * self.mu
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![1.0, 1.0]),
        }
    }
    /// `∇V = μ q / |q|³` (one square root, one division).
    #[inline]
    fn potential_gradient(&self, _t: f64, q: &[f64], grad: &mut [f64], _scratch: &mut Vec<f64>) {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let c = self.mu / (r2 * r2.sqrt());
        grad[0] = c * q[0];
        grad[1] = c * q[1];
    }
    /// `∇²V = μ (I/|q|³ − 3 q qᵀ/|q|⁵)`.
    #[inline]
    fn potential_hessian(&self, _t: f64, q: &[f64], hess: &mut Banded) {
        let r2 = q[0] * q[0] + q[1] * q[1];
        let c = self.mu / (r2 * r2.sqrt());
        let d = 3.0 * c / r2;
        for i in 0..2 {
            for j in 0..2 {
                let identity = if i == j { c } else { 0.0 };
                hess.set(i, j, identity - d * q[i] * q[j]);
            }
        }
    }
}
