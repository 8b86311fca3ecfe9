//! Diagnostics: certificates of what a run preserved.
//!
//! * [`energy`]: the energy series of a trajectory, its maximum and final errors and its drift
//!   (least-squares slope against time) — bounded and drift-free for a symplectic method on a
//!   conservative system ([HLW06] ch. IX); also as a streaming [`EnergyMonitor`].
//! * [`energy_balance`]: for forced systems, the energy change of each step against the
//!   discrete work of the forces ([`EnergyBalance`]; exact for R12).
//! * [`noether`]: every declared momentum map as a series with its maximum drift (discrete
//!   Noether: constant to solver tolerance for invariant `L_d`); also as a streaming
//!   [`NoetherMonitor`].
//! * [`balance`]: Noether with forces, per step: `J_{k+1} − J_k` equals the discrete impulse of
//!   the forces along the generator ([`force_balance`], [`BalanceMonitor`]).
//! * [`constraint`]: constraint residuals of positions and (hidden) velocity constraints,
//!   multiplier series, and a streaming [`ConstraintMonitor`].
//! * The symplecticity certificate of the step map lives in [`crate::analysis::certificate`].
//!
//! [HLW06]: crate#references

pub mod balance;
pub mod constraint;
pub mod energy;
pub mod energy_balance;
pub mod noether;
mod slope;

pub use balance::{BalanceMonitor, BalanceReport, MonitorCarry, force_balance};
pub use constraint::{
    ConstraintMonitor, ConstraintReport, multiplier_series, projection_multiplier_series,
    residuals_at,
};
pub use energy::{EnergyAccumulator, EnergyMonitor, EnergyReport, energy_series};
pub use energy_balance::EnergyBalance;
pub use noether::{NoetherMonitor, NoetherReport, momentum_series};
pub use slope::{OnlineSlope, least_squares_slope};
