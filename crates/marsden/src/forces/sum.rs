//! Sums of forces: `f = f₁ + f₂`, for continuous and for discrete forces.
//!
//! The Lagrange–d'Alembert principle is linear in the force, so forces add, and a rule's
//! quadrature of a sum is the sum of the quadratures: `(f₁ + f₂)_d^± = f₁_d^± + f₂_d^±`.

use crate::discrete::DiscreteForce;
use crate::error::Error;
use crate::mechanics::Force;
use crate::numerics::scratch::Buffer;
use crate::scalar::Scalar;

/// The sum `f₁ + f₂` of two forces (nest it, or use [`ForceExt::plus`], for more).
///
/// ```
/// use marsden::{Force, forces::{ConstantForce, ForceExt, LinearDamping}};
///
/// let f = LinearDamping::uniform(0.5).unwrap().plus(ConstantForce::new(&[1.0]).unwrap());
/// let mut out = [0.0];
/// f.force(0.0, &[0.0], &[2.0], &mut out);
/// assert_eq!(out, [0.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ForceSum<A, B>(pub A, pub B);

/// `f.plus(g)` for forces: builds a [`ForceSum`].
pub trait ForceExt: Sized {
    /// `self + other`.
    fn plus<B>(self, other: B) -> ForceSum<Self, B> {
        ForceSum(self, other)
    }
}

impl<F: Force> ForceExt for F {}

/// Inline capacity of the second summand's output (`n`, or `(s + 1)·n` for discrete forces).
const SCRATCH: usize = 16;

/// `out += second`, where `second` is filled by `fill`.
#[inline(always)]
fn add_into<S: Scalar>(out: &mut [S], fill: impl FnOnce(&mut [S])) {
    let zero = S::from(0.0);
    let mut second = Buffer::<S, SCRATCH>::empty();
    let second = second.filled(out.len(), zero);
    fill(second);
    out.iter_mut()
        .zip(second.iter())
        .for_each(|(o, &s)| *o += s);
}

impl<A: Force, B: Force> Force for ForceSum<A, B> {
    #[inline]
    fn force<S: Scalar>(&self, t: S, q: &[S], v: &[S], out: &mut [S]) {
        match (self.0.is_active(), self.1.is_active()) {
            (true, true) => {
                self.0.force(t, q, v, out);
                add_into(out, |second| self.1.force(t, q, v, second));
            }
            (true, false) => self.0.force(t, q, v, out),
            (false, true) => self.1.force(t, q, v, out),
            (false, false) => out.iter_mut().for_each(|o| *o = S::from(0.0)),
        }
    }

    fn is_active(&self) -> bool {
        self.0.is_active() || self.1.is_active()
    }

    fn validate(&self, dof: usize) -> Result<(), Error> {
        self.0.validate(dof)?;
        self.1.validate(dof)
    }
}

impl<A: DiscreteForce, B: DiscreteForce> DiscreteForce for ForceSum<A, B> {
    #[inline]
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        match (self.0.is_active(), self.1.is_active()) {
            (true, true) => {
                self.0.discrete_force(t0, h, q0, offsets, out);
                add_into(out, |second| {
                    self.1.discrete_force(t0, h, q0, offsets, second)
                });
            }
            (true, false) => self.0.discrete_force(t0, h, q0, offsets, out),
            (false, true) => self.1.discrete_force(t0, h, q0, offsets, out),
            (false, false) => out.iter_mut().for_each(|o| *o = S::from(0.0)),
        }
    }

    fn is_active(&self) -> bool {
        self.0.is_active() || self.1.is_active()
    }
}
