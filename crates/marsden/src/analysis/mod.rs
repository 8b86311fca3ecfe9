//! What a run preserved, certified by numbers: energy error and drift, momentum maps and force
//! balances, the energy balance with forces, constraint residuals and multipliers
//! ([`diagnostics`]); the exact Jacobian of the step map and its symplecticity defect
//! ([`certificate`]).

pub mod certificate;
pub mod diagnostics;
