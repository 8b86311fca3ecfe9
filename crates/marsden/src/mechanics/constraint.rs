//! Holonomic constraints `φ(q) = 0`, written once over the scalar type.
//!
//! Concept of the notes (MW01): *constrained Lagrangian systems*. The constrained discrete Euler–Lagrange equations in
//! SHAKE form ([conventions](crate#conventions), [MW01] §3.5, [LMO08])
//!
//! ```text
//!     p_k + D₁L_d(q_k, q_{k+1}) + f_d⁻ − h Dφ(q_k)ᵀ λ_k = 0,     φ(q_{k+1}) = 0,
//! ```
//!
//! are solved for `(q_{k+1}, λ_k)` in one Newton system; the multipliers are the (scaled)
//! constraint forces. The RATTLE momentum projection, the checks and projections of initial
//! data, and ready-made constraints live in [`crate::holonomic`].
//!
//! [MW01]: crate#references
//! [LMO08]: crate#references

use crate::scalar::Scalar;

/// Holonomic constraints `φ: Q → ℝ^d`.
pub trait Constraint {
    /// Whether the type may constrain anything (`false` for [`Unconstrained`]: the integrator
    /// then skips compiling its constrained kernels). Default: `true`.
    const MAY_CONSTRAIN: bool = true;

    /// Number of constraints `d`.
    fn count(&self) -> usize;
    /// Writes `φ(q)` into `out` (length d).
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]);
    /// Checks that the constraints fit a system with `dof` coordinates (called once by
    /// [`crate::run::Problem::with_constraint`]; the default accepts every `dof`).
    fn validate(&self, _dof: usize) -> Result<(), crate::error::Error> {
        Ok(())
    }
}

/// No constraints (the default): `d = 0`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Unconstrained;

impl Constraint for Unconstrained {
    const MAY_CONSTRAIN: bool = false;
    fn count(&self) -> usize {
        0
    }
    fn constraint<S: Scalar>(&self, _q: &[S], _out: &mut [S]) {}
}

impl<C: Constraint + ?Sized> Constraint for &C {
    const MAY_CONSTRAIN: bool = C::MAY_CONSTRAIN;
    fn count(&self) -> usize {
        (**self).count()
    }
    #[inline(always)]
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        (**self).constraint(q, out)
    }
    fn validate(&self, dof: usize) -> Result<(), crate::error::Error> {
        (**self).validate(dof)
    }
}
