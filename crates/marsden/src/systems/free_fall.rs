//! Free fall in a uniform field, `L = ½ m v² − m g q` (reference case R9).

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// A particle in a linear potential; every variational integrator is exact here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeFall {
    /// Mass (default 1).
    pub m: f64,
    /// Field strength (default 9.81).
    pub g: f64,
}

impl Default for FreeFall {
    fn default() -> Self {
        Self { m: 1.0, g: 9.81 }
    }
}

impl FreeFall {
    /// Exact solution `(q(t), p(t))` from `(q₀, p₀)` at time 0.
    pub fn exact(&self, q0: f64, p0: f64, t: f64) -> (f64, f64) {
        (
            q0 + p0 / self.m * t - 0.5 * self.g * t * t,
            p0 - self.m * self.g * t,
        )
    }
}

impl Lagrangian for FreeFall {
    const FIXED_DOF: Option<usize> = Some(1);
    fn dof(&self) -> usize {
        1
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        v[0] * v[0] * (0.5 * self.m) - q[0] * (self.m * self.g)
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m]),
        }
    }
}
