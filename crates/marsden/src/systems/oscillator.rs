//! The harmonic oscillator `L = ½ m v² − ½ k q²`.

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// Harmonic oscillator with mass `m` and stiffness `k` (ω = √(k/m)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HarmonicOscillator {
    /// Mass (default 1).
    pub m: f64,
    /// Stiffness (default 1).
    pub k: f64,
}

impl Default for HarmonicOscillator {
    fn default() -> Self {
        Self { m: 1.0, k: 1.0 }
    }
}

impl HarmonicOscillator {
    /// Angular frequency `ω = √(k/m)`.
    pub fn omega(&self) -> f64 {
        (self.k / self.m).sqrt()
    }

    /// Energy `p²/2m + k q²/2`.
    pub fn energy(&self, q: f64, p: f64) -> f64 {
        0.5 * p * p / self.m + 0.5 * self.k * q * q
    }

    /// Exact solution `(q(t), p(t))` from `(q₀, p₀)` at time 0.
    pub fn exact(&self, q0: f64, p0: f64, t: f64) -> (f64, f64) {
        let w = self.omega();
        let (s, c) = (w * t).sin_cos();
        (q0 * c + p0 / (self.m * w) * s, p0 * c - q0 * self.m * w * s)
    }
}

impl Lagrangian for HarmonicOscillator {
    const FIXED_DOF: Option<usize> = Some(1);
    fn dof(&self) -> usize {
        1
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] * self.m - q[0] * q[0] * self.k) * 0.5
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m]),
        }
    }
}
