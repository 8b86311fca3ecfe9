//! The planar pendulum `L = ½ m l² θ̇² + m g l cos θ` (θ from the downward vertical).

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::numerics::banded::Banded;
use crate::scalar::Scalar;
use crate::special::{self, SpecialError};

/// Planar pendulum of mass `m`, length `l` in gravity `g`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pendulum {
    /// Bob mass (default 1).
    pub m: f64,
    /// Rod length (default 1).
    pub l: f64,
    /// Gravity (default 1).
    pub g: f64,
}

impl Default for Pendulum {
    fn default() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 1.0,
        }
    }
}

impl Pendulum {
    /// Small-oscillation frequency `ω = √(g/l)`.
    pub fn omega(&self) -> f64 {
        (self.g / self.l).sqrt()
    }

    /// Exact period `4K(k²)/ω` of the libration with amplitude `θ_max`, `k = sin(θ_max/2)`
    /// (A&S 17.3; see [`special::pendulum::period`]).
    pub fn period(&self, amplitude: f64) -> Result<f64, SpecialError> {
        special::pendulum::period(amplitude, self.omega())
    }

    /// Exact solution `(θ(t), p(t))` from `(θ₀, p₀)` at time 0, through Jacobi elliptic
    /// functions (`sin(θ/2) = k sn(ωt + u₀, k²)` for librations; rotations too), see
    /// [`special::pendulum::Pendulum`].
    pub fn exact(&self, q0: f64, p0: f64, t: f64) -> Result<(f64, f64), SpecialError> {
        let inertia = self.m * self.l * self.l;
        let motion = special::pendulum::Pendulum::new(q0, p0 / inertia, self.omega())?;
        let (q, v) = motion.state(t)?;
        Ok((q, inertia * v))
    }

    /// Energy `p²/(2 m l²) − m g l cos θ`.
    pub fn energy(&self, q: f64, p: f64) -> f64 {
        0.5 * p * p / (self.m * self.l * self.l) - self.m * self.g * self.l * q.cos()
    }
}

impl Lagrangian for Pendulum {
    const FIXED_DOF: Option<usize> = Some(1);
    fn dof(&self) -> usize {
        1
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (m, l, g) = (self.m, self.l, self.g);
        v[0] * v[0] * (0.5 * m * l * l) + q[0].cos() * (m * g * l)
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m * self.l * self.l]),
        }
    }
    /// `∂V/∂θ = m g l sin θ`.
    #[inline]
    fn potential_gradient(&self, _t: f64, q: &[f64], grad: &mut [f64], _scratch: &mut Vec<f64>) {
        grad[0] = q[0].sin() * (self.m * self.g * self.l);
    }
    /// `∂²V/∂θ² = m g l cos θ`.
    #[inline]
    fn potential_hessian(&self, _t: f64, q: &[f64], hess: &mut Banded) {
        hess.set(0, 0, q[0].cos() * (self.m * self.g * self.l));
    }
}
