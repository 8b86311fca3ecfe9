//! Fence 1: the structure-aware steps of a separable Lagrangian `L = ½ vᵀMv − V(t, q)` with a
//! constant mass matrix `M`. The traits the discrete Lagrangians implement to offer them are
//! defined here, so that the concepts above import the machinery, never the reverse.
//!
//! | module | what |
//! |---|---|
//! | [`explicit`] | the trapezoid rule is velocity Störmer–Verlet: one `∇V` per step, explicit |
//! | [`alpha`] | the α rules: Newton for the offset alone, Jacobian `M/h + hα(1−α)∇²V`, reused while it contracts; band storage for chains |
//! | [`jacobian`] | the step Jacobian of the α and symmetrised α rules from `M` and `∇²V` (implicit function theorem, one `n × n` solve) |
//! | `alpha_small` | the same on stack arrays for `n ≤ 4` and a diagonal mass |
//! | `jacobian_small` | the step Jacobian on stack arrays for `n ≤ 4`, bit for bit the band one |
//! | `step` | what a rule offers ([`SeparableStep`]), one step's data ([`Frame`]), the buffers ([`SeparableWorkspace`]) |
//!
//! The integrator takes these paths only for unforced, unconstrained two-point steps, and
//! `Integrator::with_fast_paths(false)` switches them off; tests compare them with the general
//! path to round-off.

pub mod alpha;
mod alpha_small;
pub mod explicit;
pub mod jacobian;
mod jacobian_small;
mod step;

pub(crate) use explicit::ExplicitCarry;
pub use explicit::{ExplicitRun, ExplicitStep, ExplicitWorkspace};
pub use jacobian::{JacobianWorkspace, SeparableJacobian};
pub(crate) use step::SeparableCarry;
pub use step::{Frame, SeparableStep, SeparableWorkspace};
