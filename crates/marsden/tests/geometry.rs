//! The core's integration tests of geometry and the reference cases: rigid bodies on SO(3),
//! group actions and momentum maps, and each reference case (listed in the crate documentation,
//! Reference cases) in its file in `reference/`, named after it. One of three test binaries of
//! the crate (with `runs.rs` and `steps.rs`; ARCHITECTURE.md, Tests).

// Tests may unwrap and quote reference values with all their digits.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

/// Shared helpers: runs, fitted slopes, one-step matrices, tolerances.
mod common;
/// Rigid bodies on SO(3): so(3) and Cayley, the body moment by AD, the exact free body, free and coupled bodies, failures.
mod lie;
/// The reference cases R1–R20 (closed forms, unit values, exact solutions, orders), one file per case, named after it.
mod reference;
/// Group actions, momentum maps and Noether (continuous, discrete, with forces).
mod symmetry;
