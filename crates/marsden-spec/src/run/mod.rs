//! Running a validated problem: build it, stream the samples to disk (or keep them in memory)
//! through an observer, then write the summary and the plots.
//!
//! | step | module | what |
//! |---|---|---|
//! | entry point | [`execute`](fn@execute) | the whole run ([`Store`]: files, memory or both) → [`Outcome`] |
//! | caller's hold | [`controls`] | [`Progress`] callback and stop flag ([`Controls`]) |
//! | initial state | [`start`] | `p` from `v` (or back), projection, regularity, symmetry warnings |
//! | before a run | [`step_system`] | the size of the step's Newton system, a warning when it is large |
//! | generic runner | [`solve`](fn@solve) | `Problem` from any `Lagrangian`, `Force`, `Constraint`; the method's rule |
//! | forced runs | [`balance`] | the discrete energy balance of every step (R12) |
//! | forced runs | [`noether_balance`] | the forced Noether balance of every symmetry (MW01 §3.2) |
//! | on request | [`certify`] | symplecticity defect of the step map (on `T*N` when constrained), equivariance defect of `L_d` |
//! | per sample | [`observer`] | one row `t, q, p, energy, J…, residual`, [`diagnostics`] |
//! | where rows go | [`output`], [`samples`] | columns and writers of the files; in-memory [`Samples`] |
//! | afterwards | [`summary`], [`plots`] | `summary.json`; the PNG plots (also `marsden plot`) |
//! | derivatives | [`sensitivity`] | `[sensitivity]`: the tangent run's Jacobians, `sensitivity.npy` |
//! | sweeps | [`sweep`], [`shard`], [`sweep_table`], [`sweep_writer`] | members in parallel ([`marsden::studies::ensemble`]), one row each, streamed to the table |
//!
//! Catalog systems and expressions reach the generic runner through
//! [`crate::catalog::WithLagrangian`]: one monomorphised run per Lagrangian type. The file's
//! method is itself the rule ([`marsden::discrete::rules::chosen`]), and the certificate, the
//! tangent run and the order study build the run's own problem type, so each system's
//! integrator is compiled once. A run with `method = "exact"` is compiled once for the whole
//! catalog ([`solve::Stepping`] fixes the kind of stepping by type;
//! [`crate::problem::LagrangianSpec::dispatch_shared`]): its shooting evaluates `L` thousands
//! of times per step, where a branch per evaluation costs little.

pub mod balance;
pub mod certify;
pub mod controls;
pub mod diagnostics;
pub mod discrete;
pub mod execute;
pub mod noether_balance;
pub mod observer;
pub mod output;
pub mod plots;
pub mod samples;
pub mod sensitivity;
pub mod shard;
pub mod solve;
pub mod start;
pub mod step_system;
pub mod summary;
pub mod sweep;
pub mod sweep_table;
pub mod sweep_writer;

pub use controls::{CHECK_EVERY, Controls, Progress};
pub use execute::{Outcome, Store, execute};
pub use samples::Samples;
pub use solve::{RunRecord, run_problem, solve};
pub use summary::{RunStatus, Summary};
