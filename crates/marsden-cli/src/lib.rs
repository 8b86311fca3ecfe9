//! The `marsden` command: mechanical systems described in TOML problem files — Lagrangians,
//! forces, constraints and symmetries written as formulas — run with the variational
//! integrators of the [`marsden`] crate, with results, summaries and plots on disk.
//!
//! Map of the crate (data flows down, as in DESIGN.md §5's "thin CLI in two stages"):
//!
//! | stage | module | what |
//! |---|---|---|
//! | command line | [`cli`] | clap: `run`, `check`, `order`, `systems`, `plot`; exit statuses |
//! | stage 1: raw file | [`problem::raw`] | serde mirror of the TOML, `deny_unknown_fields`, spans |
//! | stage 2: run spec | [`problem`] | every check, each [`error::Diagnostic`] pointing into the file ([`source`]) |
//! | systems | [`catalog`], [`model`] | catalog systems by name; expressions as `Lagrangian`, `Force`, `Constraint`, momentum maps |
//! | expressions | [`expr`] | parse once, compile, evaluate over any `Scalar` |
//! | run | [`run`] | generic runner, streaming observer, diagnostics, `summary.json`, report |
//! | order study | [`order`] | `marsden order`: methods × step sizes, errors against a reference, fitted orders |
//!
//! The problem-file schema and the outputs (`trajectory.csv` columns, `summary.json` fields,
//! exit statuses) are the contract of issue 5: extend, don't rename.

pub mod catalog;
pub mod cli;
pub mod error;
pub mod expr;
pub mod model;
pub mod order;
pub mod problem;
pub mod run;
pub mod source;
