//! Diagnostics: certificates of what a run preserved.
//!
//! * [`energy`]: the energy series of a trajectory, its maximum and final errors and its drift
//!   (least-squares slope against time) — bounded and drift-free for a symplectic method on a
//!   conservative system ([HLW06] ch. IX); also as a streaming [`EnergyMonitor`].
//! * [`balance`]: for forced systems, the energy change of each step against the discrete work
//!   of the forces ([`EnergyBalance`]; exact for R12).
//! * [`constraint`]: constraint residuals of positions and (hidden) velocity constraints,
//!   multiplier series, and a streaming [`ConstraintMonitor`].
//!
//! [HLW06]: Hairer, Lubich, Wanner, *Geometric Numerical Integration* (2006).

pub mod balance;
pub mod constraint;
pub mod energy;
mod slope;

pub use balance::EnergyBalance;
pub use constraint::{
    ConstraintMonitor, ConstraintReport, multiplier_series, projection_multiplier_series,
};
pub use energy::{EnergyMonitor, EnergyReport, energy_series};
pub use slope::{OnlineSlope, least_squares_slope};
