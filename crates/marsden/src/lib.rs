//! marsden: discrete mechanics and variational integrators.

pub mod scalar;
pub mod special;

pub use scalar::Scalar;
