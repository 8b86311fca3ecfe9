//! Discrete forces `f_d^±`: the forced discrete Legendre transforms
//! ([conventions](crate#conventions), [MW01] §3.2)
//!
//! ```text
//!     p_k     = −D₁L_d(q_k, q_{k+1}) − f_d⁻(q_k, q_{k+1}),
//!     p_{k+1} =  D₂L_d(q_k, q_{k+1}) + f_d⁺(q_k, q_{k+1}),
//! ```
//!
//! generalised to every control point of a step, so that Galerkin rules take forces too. A rule
//! turns a Lagrangian force [`crate::mechanics::Force`] into a [`DiscreteForce`] with its own
//! quadrature ([`crate::discrete::rules`]).
//!
//! [MW01]: crate#references

use crate::mechanics::NoForce;
use crate::scalar::Scalar;

/// Discrete forces on the control points of a step: `out = (f_d⁻, …, f_d⁺)`.
///
/// The control points are given as in [`crate::discrete::DiscreteAction`]: `q0 = Q₀` and the offsets
/// `Q_j − Q₀`.
pub trait DiscreteForce {
    /// Writes the generalised force on each control point `Q₀ … Q_s` into `out` (length
    /// `(s + 1)·n`, point by point).
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]);
    /// `false` for the no-op force, so the integrator can skip all force work.
    fn is_active(&self) -> bool {
        true
    }
}

impl DiscreteForce for NoForce {
    fn discrete_force<S: Scalar>(
        &self,
        _t0: f64,
        _h: f64,
        _q0: &[S],
        _offsets: &[S],
        out: &mut [S],
    ) {
        out.iter_mut().for_each(|f| *f = S::from(0.0));
    }
    fn is_active(&self) -> bool {
        false
    }
}
