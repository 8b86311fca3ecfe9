//! Problem files as data: a mechanical system described in TOML — a catalog system or a
//! Lagrangian, forces, constraints and symmetries written as formulas — read, checked and
//! turned into a [`RunSpec`] whose system is a typed [`marsden::Lagrangian`] (a catalog system,
//! or a compiled expression: [`model`]). Nothing here runs: the runs are `marsden-engine`'s,
//! chosen for the file's system by `marsden-spec`'s factory.
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
//! | order studies | [`order`] | the [`order::Plan`] of `marsden order`, checked against the file |
//!
//! The expressions themselves are the [`marsden_expr`] crate. The problem-file schema is a
//! contract: extend, don't rename.

pub mod catalog;
pub mod error;
pub mod model;
pub mod order;
pub mod problem;
pub mod source;

pub use error::{Diagnostic, Error, ErrorKind};
pub use problem::{Overrides, RunSpec, SweepSpec, from_toml_str, load};
