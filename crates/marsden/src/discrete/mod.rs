//! Discrete mechanics: discrete Lagrangians, discrete forces, the discrete Legendre transforms,
//! the rules that build `L_d` from `L` by quadrature, and the exact discrete Lagrangian.
//!
//! | module | seed concept |
//! |---|---|
//! | [`lagrangian`] | `L_d: Q × Q → ℝ` ([`DiscreteLagrangian`]) and the discrete action of one step over its control points ([`DiscreteAction`]) |
//! | [`force`] | discrete forces `f_d^±` (discrete Lagrange–d'Alembert) |
//! | [`legendre`] | `D₁L_d`, `D₂L_d`, `F^±L_d`, the DEL residual |
//! | [`rules`] | midpoint, trapezoid, α and symmetrised α, Galerkin (Gauss, Lobatto), compositions |
//! | [`exact`] | the exact discrete Lagrangian `L_d^E` by shooting |

pub mod exact;
pub mod force;
pub mod lagrangian;
pub mod legendre;
pub mod rules;

pub use force::DiscreteForce;
pub use lagrangian::{DiscreteAction, DiscreteLagrangian};
pub use legendre::{d1, d2, del_residual, legendre_minus, legendre_plus};
