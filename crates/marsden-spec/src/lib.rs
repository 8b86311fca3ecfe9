//! Problem files as a library: mechanical systems described in TOML — Lagrangians, forces,
//! constraints and symmetries written as formulas — checked, run with the variational
//! integrators of the [`marsden`] crate, and summed up. The `marsden` command and the Python
//! package are thin front ends over the same entry points:
//!
//! ```no_run
//! use marsden_spec::{Controls, Overrides, Store};
//!
//! let spec = marsden_spec::load("examples/pendulum.toml".as_ref(), &Overrides::default())?;
//! let outcome = marsden_spec::execute(&spec, Store::Memory, &Controls::none())?;
//! let samples = outcome.samples.unwrap_or_default();
//! println!("{} samples, max |ΔE/E0| = {}", samples.len(), outcome.summary.energy.max_rel_error);
//! # Ok::<(), marsden_spec::Error>(())
//! ```
//!
//! Nothing here prints or exits; errors are values ([`Error`], its [`Diagnostic`] rendered with
//! the file's line and a caret).
//!
//! # Three crates behind one surface
//!
//! ```text
//! marsden-problem   TOML ──raw (serde, spans)──▶ RunSpec (its system a typed Lagrangian)
//! marsden-engine    Engine: prepare · run · initial_tangent · order_study, generic over L
//! marsden-engine-catalog   the engine compiled for the catalog's systems
//! marsden-spec      factory: RunSpec ──engine_for──▶ Box<dyn Engine> (the expression systems
//!                   compiled here); execute, sweeps, summary.json, plots, report texts
//! ```
//!
//! The language ([`problem`], [`model`], [`catalog`], [`error`], [`source`]) and the engine's
//! modules are re-exported here under the paths the front ends use ([`run`], [`order`]).
//!
//! | stage | module | what |
//! |---|---|---|
//! | file → spec | [`problem`] | every check → [`RunSpec`] (and [`SweepSpec`]); [`load`], [`from_toml_str`] |
//! | the seam | [`factory`] | [`engine_for`]: the [`marsden_engine::Engine`] of a file's system |
//! | run | [`run`] | [`execute`](fn@execute) with [`Controls`] → [`Outcome`]: files, [`Samples`] in memory, [`Summary`] |
//! | sweeps | [`run::sweep`] | members in parallel, one row each, `--shard` |
//! | order study | [`order`] | methods × step sizes, errors against a reference, fitted orders |
//! | texts | [`report`] | what `run`, `check` and `systems` print |
//!
//! The problem-file schema and the outputs (`trajectory.csv` columns, `summary.json` fields)
//! are a contract: extend, don't rename.

pub mod factory;
pub mod order;
pub mod report;
pub mod run;

pub use factory::{engine_for, prepare};
pub use marsden_problem::{
    Diagnostic, Error, ErrorKind, Overrides, RunSpec, SweepSpec, catalog, error, from_toml_str,
    load, model, problem, source,
};
pub use run::{
    Controls, Outcome, Prepared, Progress, RunStatus, Samples, Store, Summary, execute,
};
