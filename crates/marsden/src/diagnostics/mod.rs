//! Diagnostics: certificates of what a run preserved.
//!
//! * [`energy`]: the energy series of a trajectory, its maximum and final errors and its drift
//!   (least-squares slope against time) — bounded and drift-free for a symplectic method on a
//!   conservative system ([HLW06] ch. IX); also as a streaming [`EnergyMonitor`].
//!
//! [HLW06]: Hairer, Lubich, Wanner, *Geometric Numerical Integration* (2006).

pub mod energy;
mod slope;

pub use energy::{EnergyMonitor, EnergyReport, energy_series};
pub use slope::{OnlineSlope, least_squares_slope};
