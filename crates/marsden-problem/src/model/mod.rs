//! The core's traits implemented by compiled expressions: a problem file's Lagrangian, forces,
//! constraints and symmetry generators become ordinary [`marsden::Lagrangian`],
//! [`marsden::Force`] and [`marsden::Constraint`] values, evaluated at `f64` or at the dual
//! numbers the integrator differentiates with.
//!
//! Expressions read one inputs slice per evaluation, laid out `[q₁ … qₙ, q̇₁ … q̇ₙ, t]` (see
//! [`slots`]); it is filled on the stack for n ≤ 8 ([`inputs::with_inputs`]), so an evaluation
//! does no string work and no allocation.

pub mod constraint;
pub mod control_table;
pub mod discrete_lagrangian;
pub mod force;
pub mod hamiltonian;
pub mod inputs;
pub mod lagrangian;
pub mod multibody;
pub mod multibody_potential;
pub mod observables;
pub mod parametric;
pub mod rigid;
pub mod symmetry;

pub use constraint::ExprConstraint;
pub use control_table::ControlTable;
pub use discrete_lagrangian::ExprDiscreteLagrangian;
pub use force::{ExprForce, ForceInputs, LagrangianForce};
pub use hamiltonian::{ExprHamiltonian, HamiltonianExprLagrangian};
pub use lagrangian::{ExprLagrangian, jit_compile_seconds};
pub use observables::{ExprEvent, Observables};
pub use parametric::{ExprParametric, ParametricTexts};
pub use symmetry::{MomentumMap, Symmetry};

/// Names and slots of the inputs of a Lagrangian or force expression.
pub mod slots {
    /// The velocity name of a coordinate: `theta` → `theta_dot`.
    pub fn velocity_name(coordinate: &str) -> String {
        format!("{coordinate}_dot")
    }

    /// Input names in slot order: the coordinates, their velocities, then `t`.
    pub fn tangent_inputs(coordinates: &[String]) -> Vec<String> {
        coordinates
            .iter()
            .cloned()
            .chain(coordinates.iter().map(|c| velocity_name(c)))
            .chain(std::iter::once("t".to_owned()))
            .collect()
    }
}
