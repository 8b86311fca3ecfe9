//! PNG plots of a trajectory, drawn with plotters into memory and encoded with `png`.
//!
//! * [`plot_phase_portrait`] — `p_i` against `q_i`, one panel per coordinate (first few).
//! * [`plot_time_series`] — `q_i(t)` and `p_i(t)`.
//! * [`plot_sweep`] — per-member quantities of a sweep against the swept value;
//!   [`plot_sweep_grid`] for a grid, one curve per value of the other axes.
//! * [`plot_configuration`] — paths in a plane with equal axes (orbits, N-body bodies).
//! * [`plot_energy_error`] — relative energy error against time (linear, scientific ticks).
//! * [`plot_momentum_drift`] — `J(t) − J(t₀)` per momentum map, with legend.
//! * [`plot_constraint_residual`] — residual against time (log axis when positive);
//!   [`plot_constraint_residuals`] with the hidden constraint's `|Dφ(q)·v|` as a second curve.
//! * [`plot_lines`] — named series against a common abscissa, linear or log panels.
//! * [`plot_section`] — a Poincaré section's points as dots; [`plot_observables`] — named
//!   observables against time.
//! * [`plot_run`] — all of the above from a [`Table`](crate::Table) named by the
//!   `trajectory.csv` convention.
//!
//! Text uses DejaVu Sans embedded in the crate (see [`FONT_FAMILY`]); no font is looked up
//! on the machine. Long series are reduced (min/max per bucket) so spikes survive; empty,
//! constant and non-finite data produce a plot with a note rather than an error.
//!
//! Internals: `angle` (wrapping to (−π, π]), `axis` (ranges, tick labels), `downsample`, `font`, `prepare` (checks, notes),
//! `render` (panels → PNG).

mod angle;
mod axis;
mod columns;
mod configuration;
mod constraint;
mod downsample;
mod energy;
mod font;
mod legend;
mod lines;
mod momentum;
mod multipliers;
mod options;
mod phase;
mod plane;
mod prepare;
mod render;
mod run;
mod section;
mod sweep;
mod sweep_grid;
mod time_series;

pub use configuration::{Orbit, Plane, plot_configuration};
pub use constraint::{plot_constraint_residual, plot_constraint_residuals};
pub use energy::{plot_energy_balance, plot_energy_error};
pub use font::FAMILY as FONT_FAMILY;
pub use legend::MAX_LEGEND;
pub use lines::{LinePanel, plot_lines};
pub use momentum::plot_momentum_drift;
pub use multipliers::plot_multipliers;
pub use options::{PhaseCurve, PlotOptions, PlotReport, Series};
pub use phase::plot_phase_portrait;
pub use run::{
    CONFIGURATION_PNG, CONSTRAINT_RESIDUAL_PNG, ENERGY_ERROR_PNG, MOMENTUM_DRIFT_PNG,
    MULTIPLIERS_PNG, PHASE_PORTRAIT_PNG, TIME_SERIES_PNG, plot_run,
};
pub use section::{plot_observables, plot_section};
pub use sweep::plot_sweep;
pub use sweep_grid::{MAX_CURVES, plot_sweep_grid};
pub use time_series::plot_time_series;
