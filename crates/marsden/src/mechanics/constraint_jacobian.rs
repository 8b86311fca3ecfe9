//! The constraint values and Jacobian `(φ(q), Dφ(q))` by one first-order dual evaluation.
//!
//! Every constrained computation (the SHAKE step, the RATTLE projection, the checks of initial
//! data, the residual monitors) needs `φ` and `Dφ = ∂φ/∂q` at a point. For up to four
//! coordinates and four constraints the duals are statically sized (no heap, no AD chunking);
//! larger systems go through the general driver of [`crate::numerics::ad`].

use nalgebra::{Const, U1};
use num_dual::{Derivative, Dual64, DualSVec64};

use super::constraint::Constraint;
use crate::numerics::ad::{self, MultiFunction};
use crate::scalar::Scalar;

/// Largest number of constraints with statically sized duals.
pub(crate) const MAX_CONSTRAINTS: usize = 4;

/// A first-order dual number with an `N`-dimensional derivative part.
trait SmallFirstDual<const N: usize>: Scalar {
    /// `re` with derivative `e_i`.
    fn seeded(re: f64, i: usize) -> Self;
    /// Derivative component `j`.
    fn eps(&self, j: usize) -> f64;
}

impl SmallFirstDual<1> for Dual64 {
    #[inline(always)]
    fn seeded(re: f64, _i: usize) -> Self {
        Dual64::new(re, 1.0)
    }
    #[inline(always)]
    fn eps(&self, _j: usize) -> f64 {
        self.eps
    }
}

impl<const N: usize> SmallFirstDual<N> for DualSVec64<N> {
    #[inline(always)]
    fn seeded(re: f64, i: usize) -> Self {
        let mut x = DualSVec64::<N>::from_re(re);
        x.eps = Derivative::derivative_generic(Const::<N>, U1, i);
        x
    }
    #[inline(always)]
    fn eps(&self, j: usize) -> f64 {
        self.eps.0.as_ref().map_or(0.0, |m| m[j])
    }
}

fn small_constraint_jacobian<const N: usize, D: SmallFirstDual<N>, C: Constraint>(
    c: &C,
    q: &[f64],
    values: &mut [f64],
    jac: &mut [f64],
) {
    let x: [D; N] = std::array::from_fn(|i| D::seeded(q[i], i));
    let mut phi = [D::from(0.0); MAX_CONSTRAINTS];
    let d = values.len();
    c.constraint(&x, &mut phi[..d]);
    for (k, value) in phi[..d].iter().enumerate() {
        values[k] = value.re();
        for j in 0..N {
            jac[k * N + j] = value.eps(j);
        }
    }
}

/// `φ(q)` and `Dφ(q)` (row-major d × n) by one first-order dual evaluation with static sizes
/// for `n ≤ 4`, `d ≤ 4`; the general [`crate::integrator::equations`] driver otherwise.
pub(crate) fn constraint_jacobian<C: Constraint>(
    c: &C,
    q: &[f64],
    values: &mut [f64],
    jac: &mut [f64],
) {
    if values.len() > MAX_CONSTRAINTS {
        return constraint_jacobian_by_ad(c, q, values, jac);
    }
    match q.len() {
        1 => small_constraint_jacobian::<1, Dual64, C>(c, q, values, jac),
        2 => small_constraint_jacobian::<2, DualSVec64<2>, C>(c, q, values, jac),
        3 => small_constraint_jacobian::<3, DualSVec64<3>, C>(c, q, values, jac),
        4 => small_constraint_jacobian::<4, DualSVec64<4>, C>(c, q, values, jac),
        _ => constraint_jacobian_by_ad(c, q, values, jac),
    }
}

/// `Dφ(q)` (row-major d × n) and `φ(q)` of a constraint, by AD.
fn constraint_jacobian_by_ad<C: Constraint>(c: &C, q: &[f64], values: &mut [f64], jac: &mut [f64]) {
    struct Phi<'a, C>(&'a C, usize);
    impl<C: Constraint> MultiFunction for Phi<'_, C> {
        fn inputs(&self) -> usize {
            self.1
        }
        fn outputs(&self) -> usize {
            self.0.count()
        }
        fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
            self.0.constraint(x, out)
        }
    }
    ad::jacobian(&Phi(c, q.len()), q, 0..q.len(), values, jac);
}
