//! PNG plots of a trajectory, drawn with plotters into memory and encoded with `png`.
//!
//! * [`plot_phase_portrait`] — `p_i` against `q_i`, one panel per coordinate (first few).
//! * [`plot_energy_error`] — relative energy error against time (linear, scientific ticks).
//! * [`plot_momentum_drift`] — `J(t) − J(t₀)` per momentum map, with legend.
//! * [`plot_constraint_residual`] — residual against time (log axis when positive).
//! * [`plot_run`] — all of the above from a [`Table`](crate::Table) named by the
//!   `trajectory.csv` convention.
//!
//! Text uses DejaVu Sans embedded in the crate (see [`FONT_FAMILY`]); no font is looked up
//! on the machine. Long series are reduced (min/max per bucket) so spikes survive; empty,
//! constant and non-finite data produce a plot with a note rather than an error.
//!
//! Internals: `axis` (ranges, tick labels), `downsample`, `font`, `prepare` (checks, notes),
//! `render` (panels → PNG).

mod axis;
mod constraint;
mod downsample;
mod energy;
mod font;
mod momentum;
mod multipliers;
mod options;
mod phase;
mod prepare;
mod render;
mod run;

pub use constraint::plot_constraint_residual;
pub use energy::{plot_energy_balance, plot_energy_error};
pub use font::FAMILY as FONT_FAMILY;
pub use momentum::plot_momentum_drift;
pub use multipliers::plot_multipliers;
pub use options::{PhaseCurve, PlotOptions, PlotReport, Series};
pub use phase::plot_phase_portrait;
pub use run::{
    CONSTRAINT_RESIDUAL_PNG, ENERGY_ERROR_PNG, MOMENTUM_DRIFT_PNG, MULTIPLIERS_PNG,
    PHASE_PORTRAIT_PNG, plot_run,
};
