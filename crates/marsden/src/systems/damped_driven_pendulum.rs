//! The damped, driven pendulum `m l² θ̈ = −m g l sin θ − c θ̇ + A cos(ω t + φ)`:
//! `L = ½ m l² θ̇² + m g l cos θ` with the force (torque) `f = −c θ̇ + A cos(ω t + φ)`.
//!
//! With the defaults (`m = l = g = 1`, `c = 1/2`, `A = 3/2`, `ω = 2/3`) it is the chaotic
//! pendulum of Baker & Gollub, *Chaotic Dynamics: an introduction*, 2nd ed. (1996), ch. 3:
//! `θ̈ + θ̇/Q + sin θ = g_D cos(ω_D t)` with `Q = 2`, `g_D = 1.5`, `ω_D = 2/3`.

use crate::mechanics::{Force, Lagrangian};
use crate::scalar::Scalar;

/// Pendulum with viscous damping `c` and a periodic driving torque `A cos(ω t + φ)`; it is both
/// the [`Lagrangian`] and the [`Force`] of the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedDrivenPendulum {
    /// Bob mass (default 1).
    pub m: f64,
    /// Rod length (default 1).
    pub l: f64,
    /// Gravity (default 1).
    pub g: f64,
    /// Damping coefficient (default 0.5, i.e. quality factor Q = 2 for unit m, l, g).
    pub c: f64,
    /// Driving torque amplitude (default 1.5).
    pub amplitude: f64,
    /// Driving angular frequency (default 2/3).
    pub omega: f64,
    /// Driving phase (default 0).
    pub phase: f64,
}

impl Default for DampedDrivenPendulum {
    fn default() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 1.0,
            c: 0.5,
            amplitude: 1.5,
            omega: 2.0 / 3.0,
            phase: 0.0,
        }
    }
}

impl DampedDrivenPendulum {
    /// Energy of the pendulum alone, `p²/(2 m l²) − m g l cos θ`.
    pub fn energy(&self, q: f64, p: f64) -> f64 {
        0.5 * p * p / (self.m * self.l * self.l) - self.m * self.g * self.l * q.cos()
    }

    /// Period of the drive, `2π/ω`.
    pub fn drive_period(&self) -> f64 {
        std::f64::consts::TAU / self.omega
    }
}

impl Lagrangian for DampedDrivenPendulum {
    const FIXED_DOF: Option<usize> = Some(1);
    fn dof(&self) -> usize {
        1
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let (m, l, g) = (self.m, self.l, self.g);
        v[0] * v[0] * (0.5 * m * l * l) + q[0].cos() * (m * g * l)
    }
}

impl Force for DampedDrivenPendulum {
    #[inline(always)]
    fn force<S: Scalar>(&self, t: S, _q: &[S], v: &[S], out: &mut [S]) {
        out[0] = v[0] * (-self.c) + (t * self.omega + self.phase).cos() * self.amplitude;
    }
    fn validate(&self, dof: usize) -> Result<(), crate::error::Error> {
        crate::error::Error::check_len("damped driven pendulum force (dof)", &[0.0], dof)
    }
}
