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
//! # Map of the crate
//!
//! Data flows down.
//!
//! | stage | module | what |
//! |---|---|---|
//! | stage 1: raw file | [`problem::raw`] | serde mirror of the TOML, `deny_unknown_fields`, spans |
//! | stage 2: run spec | [`problem`] | every check → [`RunSpec`] (and [`SweepSpec`]); [`load`], [`from_toml_str`] |
//! | errors | [`error`], [`source`] | [`Diagnostic`] pointing into the file, [`Error`] with its [`ErrorKind`] |
//! | systems | [`catalog`], [`model`] | catalog systems by name; expressions as `Lagrangian`, `Force`, `Constraint`, momentum maps |
//! | run | [`run`] | [`execute`](fn@execute) with [`Controls`] → [`Outcome`]: files, [`Samples`] in memory, [`Summary`] |
//! | sweeps | [`run::sweep`] | members in parallel, one row each, `--shard` |
//! | order study | [`order`] | methods × step sizes, errors against a reference, fitted orders |
//! | texts | [`report`] | what `run`, `check` and `systems` print |
//!
//! The expressions themselves are the [`marsden_expr`] crate. The problem-file schema and the
//! outputs (`trajectory.csv` columns, `summary.json` fields) are a contract: extend, don't
//! rename.

pub mod catalog;
pub mod error;
pub mod model;
pub mod order;
pub mod problem;
pub mod report;
pub mod run;
pub mod source;

pub use error::{Diagnostic, Error, ErrorKind};
pub use problem::{Overrides, RunSpec, SweepSpec, from_toml_str, load};
pub use run::{Controls, Outcome, Progress, RunStatus, Samples, Store, Summary, execute};
