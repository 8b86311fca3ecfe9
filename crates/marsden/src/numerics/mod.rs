//! Numerical machinery with no mechanics in it: automatic differentiation, dual numbers,
//! Newton's method with its one stopping rule, a bracketing root finder, dense and banded linear algebra, scratch buffers.
//!
//! | module | what |
//! |---|---|
//! | [`ad`] | the only module that seeds dual numbers: gradients, Jacobians, mixed Hessian blocks |
//! | [`dual`] | fixed-size dual numbers for the small step kernels; [`dual::compose`] evaluates a function at them from its Taylor data |
//! | [`newton`] | Newton's method, its options, and the [`newton::Convergence`] rule every Newton loop uses |
//! | [`dense`] | LU with partial pivoting in caller-owned buffers |
//! | [`banded`] | band matrices and their LU (large chains in `O(n)`) |
//! | [`brent`] | Brent's bracketing root finder (event location) |
//! | [`scratch`] | stack buffers for the hot path |

pub mod ad;
pub mod banded;
pub mod brent;
pub mod dense;
pub mod dual;
pub mod newton;
pub mod scratch;
pub mod short;
