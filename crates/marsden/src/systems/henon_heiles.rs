//! The Hénon–Heiles system `L = ½(ẋ² + ẏ²) − ½(x² + y²) − λ(x²y − y³/3)` (HLW06 §I.3).

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// Hénon–Heiles with coupling `λ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HenonHeiles {
    /// Cubic coupling (default 1).
    pub lambda: f64,
}

impl Default for HenonHeiles {
    fn default() -> Self {
        Self { lambda: 1.0 }
    }
}

impl HenonHeiles {
    /// Energy `½|p|² + ½(x² + y²) + λ(x²y − y³/3)`.
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        let (x, y) = (q[0], q[1]);
        0.5 * (p[0] * p[0] + p[1] * p[1])
            + 0.5 * (x * x + y * y)
            + self.lambda * (x * x * y - y * y * y / 3.0)
    }
}

impl Lagrangian for HenonHeiles {
    const FIXED_DOF: Option<usize> = Some(2);
    fn dof(&self) -> usize {
        2
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (x, y) = (q[0], q[1]);
        let potential = (x * x + y * y) * 0.5 + (x * x * y - y * y * y * (1.0 / 3.0)) * self.lambda;
        (v[0] * v[0] + v[1] * v[1]) * 0.5 - potential
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![1.0, 1.0]),
        }
    }
}
