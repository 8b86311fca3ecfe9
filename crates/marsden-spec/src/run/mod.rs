//! Running a validated problem: the engine of its system ([`crate::engine_for`]) streams the
//! samples to disk (or keeps them in memory) through its observer, then the summary and the
//! plots are written. The engine's own modules are re-exported here. The modules are the
//! crate's own: the front ends reach what they use through the list in `lib.rs`.
//!
//! | step | module | what |
//! |---|---|---|
//! | entry point | [`execute`](fn@execute) | the whole run ([`Store`]: files, memory or both) → [`Outcome`] |
//! | once per problem | [`prepared`] | [`Prepared`]: checked and its initial state prepared once, run as often as asked |
//! | long runs | [`resume`] | checkpoints every `checkpoint_every` steps; a run continued from its last one |
//! | caller's hold | [`controls`] | [`Progress`] callback and stop flag ([`Controls`]) |
//! | initial state | [`start`] | `p` from `v` (or back), projection, regularity, symmetry warnings |
//! | the run | [`solve`] | a `Problem` from the file's parts, stepped by the rule or by shooting |
//! | forced runs | [`balance`], [`noether_balance`] | the discrete energy and forced Noether balances |
//! | on request | [`certify`] | symplecticity defect of the step map, equivariance defect of `L_d` |
//! | per sample | [`marsden_engine::observer`] | one row `t, q, p, energy, J…, residual`, [`diagnostics`] |
//! | where rows go | [`output`], [`samples`] | columns and writers of the files; in-memory [`Samples`] |
//! | events | [`event_outputs`] | `events.csv`, in-memory [`EventSamples`](event_outputs::EventSamples), `section.png`, `observables.png` |
//! | stepping | [`segment`] | a run continued from a state `(t, q, p)` for some steps or to a time (Python's `Simulation`) |
//! | chosen times | [`sampled_times`] | `[output] times`: `samples.csv`, in-memory [`SampledStates`](sampled_times::SampledStates) |
//! | afterwards | [`summary`] ([`summary_bodies`]), [`plots`], [`rigid_plots`], [`multibody_plots`] | `summary.json`; the PNG plots (also `marsden plot`) |
//! | derivatives | [`sensitivity`] | `[sensitivity]`: the tangent run's Jacobians, `sensitivity.npy` |
//! | sweeps | [`sweep`], [`shard`], [`sweep_table`], [`sweep_writer`] | members in parallel ([`marsden::studies::ensemble`]), one row each, streamed to the table |

pub(crate) mod event_outputs;
pub(crate) mod execute;
pub(crate) mod multibody_plots;
pub(crate) mod output;
pub(crate) mod plots;
pub(crate) mod prepared;
pub(crate) mod resume;
pub(crate) mod rigid_plots;
pub(crate) mod sampled_times;
pub(crate) mod samples;
pub(crate) mod segment;
pub(crate) mod shard;
pub(crate) mod summary;
pub(crate) mod summary_bodies;
pub(crate) mod sweep;
pub(crate) mod sweep_checkpoint;
pub(crate) mod sweep_table;
pub(crate) mod sweep_writer;

pub use execute::{Outcome, Store, execute};
pub use marsden_engine::{
    CHECK_EVERY, Controls, Progress, balance, certify, controls, diagnostics, noether_balance,
    sensitivity, solve, start,
};
pub use prepared::Prepared;
pub use samples::Samples;
pub use summary::{RunStatus, Summary};
