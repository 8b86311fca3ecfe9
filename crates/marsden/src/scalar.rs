//! The one generic axis of the crate: the scalar type physics code is written over.
//!
//! Every Lagrangian, force, constraint and group action is written once as a function generic
//! over [`Scalar`]; evaluating it at `f64` gives values, at num-dual's dual numbers gives exact
//! derivatives (forward-mode automatic differentiation). `Scalar` is a short name for
//! `num_dual::DualNum<Primitive = f64> + Copy`, so user code needs a single bound.

pub use num_dual::DualNum;

/// A real number or a (hyper-)dual number over `f64` with static size.
///
/// Implemented for every type that satisfies the bound (blanket impl); you never implement it.
///
/// ```
/// use marsden::Scalar;
/// fn potential<S: Scalar>(q: S) -> S {
///     -q.cos()
/// }
/// assert_eq!(potential(0.0_f64), -1.0);
/// ```
pub trait Scalar: DualNum<Primitive = f64> + Copy {}

impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}

/// Lift a constant into any scalar type.
#[inline(always)]
pub fn constant<S: Scalar>(x: f64) -> S {
    S::from(x)
}
