//! The core's integration tests of the step and the mechanics under it: the fast paths against
//! the general one, holonomic constraints, the continuous mechanics and the catalog, the
//! Hamiltonian side. One of three test binaries of the crate (with `runs.rs` and
//! `geometry.rs`; ARCHITECTURE.md, Tests).

// Tests may unwrap and quote reference values with all their digits.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

/// Shared helpers: runs, fitted slopes, one-step matrices, tolerances.
mod common;
/// Holonomic constraints: SHAKE + RATTLE, the closed form, Cartesian pendulums, typed errors of bad constrained input.
mod constraints;
/// Every fast path against the general path (bit for bit or to round-off), and the work statistics.
mod fast_paths;
/// The Hamiltonian side: the same system as L and as H, the Legendre adapters.
mod hamiltonian;
/// Continuous mechanics and the catalog: AD against finite differences, Legendre transform, accelerations, hand-written potential derivatives, forces.
mod mechanics;
