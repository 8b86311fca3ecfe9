//! The core's integration tests of whole runs: problems, observers, events, checkpoints,
//! ensembles and input files; derivatives through the simulation; rules of high order on long
//! runs. One of three test binaries of the crate (with `geometry.rs` and `steps.rs`), grouped by
//! area so that they compile side by side (ARCHITECTURE.md, Tests).

// Tests may unwrap and quote reference values with all their digits.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

/// Shared helpers: runs, fitted slopes, one-step matrices, tolerances.
mod common;
/// Rules of high order: compositions and Galerkin methods on long runs, with forces and constraints.
mod rules;
/// Problems, runs, observers, events, checkpoints, ensembles, input files and bad input.
mod run;
/// Derivatives through the simulation: tangent maps, finite differences of whole runs, adjoints.
mod sensitivity;
