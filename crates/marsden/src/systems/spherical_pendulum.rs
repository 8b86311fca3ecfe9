//! The spherical pendulum in Cartesian coordinates: a point mass `m` on `|q| = l` in gravity
//! `g` along `−z`,
//!
//! ```text
//!     L = ½ m |v|² − m g z,      φ(q) = ½ (|q|² − l²) = 0,
//! ```
//!
//! a constrained system on the sphere `S²` ([MW01] §3.5; [HLW06] §VII.1 uses it as the model
//! problem for SHAKE/RATTLE). Invariants: the energy `|p|²/2m + m g z` (for tangent `p`) and,
//! by rotational symmetry about the vertical axis, the vertical angular momentum
//! `J_z = x p_y − y p_x`, which the constrained midpoint and trapezoid schemes conserve exactly
//! (discrete Noether: `L_d` and `φ` are invariant and the constraint force `h q λ` is radial).
//!
//! [MW01]: crate#references
//! [HLW06]: crate#references

use crate::error::Error;
use crate::mechanics::{Constraint, Initial, Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// Spherical pendulum of mass `m` and length `l` in gravity `g`; it is both the [`Lagrangian`]
/// and the [`Constraint`] of the system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalPendulum {
    /// Bob mass (default 1).
    pub m: f64,
    /// Rod length (default 1).
    pub l: f64,
    /// Gravity (default 1).
    pub g: f64,
}

impl Default for SphericalPendulum {
    fn default() -> Self {
        Self {
            m: 1.0,
            l: 1.0,
            g: 1.0,
        }
    }
}

impl SphericalPendulum {
    /// Consistent initial data from spherical angles: polar angle `θ` from the downward vertical,
    /// azimuth `ϕ`, and their rates: `q = l (sin θ cos ϕ, sin θ sin ϕ, −cos θ)` and `v = q̇`
    /// (exactly tangent up to rounding).
    pub fn initial(&self, theta: f64, phi: f64, theta_dot: f64, phi_dot: f64) -> Initial {
        let l = self.l;
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let q = [l * st * cp, l * st * sp, -l * ct];
        let v = [
            l * (theta_dot * ct * cp - phi_dot * st * sp),
            l * (theta_dot * ct * sp + phi_dot * st * cp),
            l * theta_dot * st,
        ];
        Initial::velocity(&q, &v)
    }

    /// Energy `|p|²/2m + m g z` (the Hamiltonian for momenta tangent to the sphere).
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        let p2: f64 = p.iter().map(|x| x * x).sum();
        0.5 * p2 / self.m + self.m * self.g * q[2]
    }

    /// Vertical angular momentum `J_z = x p_y − y p_x`.
    pub fn vertical_angular_momentum(&self, q: &[f64], p: &[f64]) -> f64 {
        q[0] * p[1] - q[1] * p[0]
    }

    /// Distance from the suspension point, `|q|`.
    pub fn radius(q: &[f64]) -> f64 {
        q.iter().map(|x| x * x).sum::<f64>().sqrt()
    }
}

impl Lagrangian for SphericalPendulum {
    const FIXED_DOF: Option<usize> = Some(3);
    fn dof(&self) -> usize {
        3
    }
    /// Separable with a constant diagonal mass: RATTLE takes its closed form
    /// ([`crate::holonomic::Rattle`]).
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m; 3]),
        }
    }
    #[inline(always)]
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) * (0.5 * self.m) - q[2] * (self.m * self.g)
    }
}

impl Constraint for SphericalPendulum {
    fn count(&self) -> usize {
        1
    }
    #[inline(always)]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        out[0] = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] - self.l * self.l) * 0.5;
    }
    fn validate(&self, dof: usize) -> Result<(), Error> {
        Error::check_len("spherical pendulum coordinates (dof)", &[0.0; 3], dof)
    }
}
