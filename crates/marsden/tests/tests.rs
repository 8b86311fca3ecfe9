//! The integration tests of the core, in one binary (one link of the crate instead of one per
//! file), grouped by area. Each reference case (listed in the crate documentation, Reference cases)
//! has its file in `reference/`, named after it.

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
/// Rigid bodies on SO(3): so(3) and Cayley, the body moment by AD, the exact free body, free and coupled bodies, failures.
mod lie;
/// Continuous mechanics and the catalog: AD against finite differences, Legendre transform, accelerations, hand-written potential derivatives, forces.
mod mechanics;
/// The reference cases R1–R20 (closed forms, unit values, exact solutions, orders), one file per case, named after it.
mod reference;
/// Rules of high order: compositions and Galerkin methods on long runs, with forces and constraints.
mod rules;
/// Problems, runs, observers, events, checkpoints, ensembles, input files and bad input.
mod run;
/// Derivatives through the simulation: tangent maps, finite differences of whole runs, adjoints.
mod sensitivity;
/// Group actions, momentum maps and Noether (continuous, discrete, with forces).
mod symmetry;
