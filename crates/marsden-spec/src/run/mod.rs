//! Running a validated problem: the engine of its system ([`crate::engine_for`]) streams the
//! samples to disk (or keeps them in memory) through its observer, then the summary and the
//! plots are written. The engine's own modules are re-exported here.
//!
//! | step | module | what |
//! |---|---|---|
//! | entry point | [`execute`](fn@execute) | the whole run ([`Store`]: files, memory or both) → [`Outcome`] |
//! | long runs | [`resume`] | checkpoints every `checkpoint_every` steps; a run continued from its last one |
//! | caller's hold | [`controls`] | [`Progress`] callback and stop flag ([`Controls`]) |
//! | initial state | [`start`] | `p` from `v` (or back), projection, regularity, symmetry warnings |
//! | the run | [`solve`] | a `Problem` from the file's parts, stepped by the rule or by shooting |
//! | forced runs | [`balance`], [`noether_balance`] | the discrete energy and forced Noether balances |
//! | on request | [`certify`] | symplecticity defect of the step map, equivariance defect of `L_d` |
//! | per sample | [`observer`] | one row `t, q, p, energy, J…, residual`, [`diagnostics`] |
//! | where rows go | [`output`], [`samples`] | columns and writers of the files; in-memory [`Samples`] |
//! | events | [`event_outputs`] | `events.csv`, in-memory [`EventSamples`](event_outputs::EventSamples), `section.png`, `observables.png` |
//! | stepping | [`segment`] | a run continued from a state `(t, q, p)` for some steps or to a time (Python's `Simulation`) |
//! | chosen times | [`sampled_times`] | `[output] times`: `samples.csv`, in-memory [`SampledStates`](sampled_times::SampledStates) |
//! | afterwards | [`summary`] ([`summary_bodies`]), [`plots`], [`rigid_plots`], [`multibody_plots`] | `summary.json`; the PNG plots (also `marsden plot`) |
//! | derivatives | [`sensitivity`] | `[sensitivity]`: the tangent run's Jacobians, `sensitivity.npy` |
//! | sweeps | [`sweep`], [`shard`], [`sweep_table`], [`sweep_writer`] | members in parallel ([`marsden::studies::ensemble`]), one row each, streamed to the table |

pub mod event_outputs;
pub mod execute;
pub mod multibody_plots;
pub mod output;
pub mod plots;
pub mod prepared;
pub mod resume;
pub mod rigid_plots;
pub mod sampled_times;
pub mod samples;
pub mod segment;
pub mod shard;
pub mod summary;
pub mod summary_bodies;
pub mod sweep;
pub mod sweep_checkpoint;
pub mod sweep_table;
pub mod sweep_writer;

pub use execute::{Outcome, Store, execute, execute_from};
pub use prepared::Prepared;
pub use marsden_engine::{
    CHECK_EVERY, Controls, Progress, RunRecord, balance, certify, checkpoint, controls,
    diagnostics, discrete, engine, noether_balance, observer, sensitivity, solve, start,
    step_system,
};
pub use samples::Samples;
pub use summary::{RunStatus, Summary};
