//! Derivatives through the simulation: tangent maps against closed forms (R1, R12), symplecticity
//! of the tangent map, finite differences of whole runs, and adjoint gradients against tangents.

mod adjoint;
mod common;
mod constrained;
mod constrained_parameters;
mod finite_differences;
mod parameters;
mod separable_jacobian;
mod tangent;
