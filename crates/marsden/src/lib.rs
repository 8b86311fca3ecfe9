//! marsden: discrete mechanics and variational integrators.

pub mod scalar;

pub use scalar::Scalar;
