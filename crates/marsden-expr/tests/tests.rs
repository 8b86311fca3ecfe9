//! The expression language's tests, in one binary (one link of the core, not five).

// Helpers outside #[test] functions unwrap too; a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

// Test models: each Lagrangian (or Hamiltonian) as an expression and as hand-written Rust.
mod common;
// Derivatives through dual numbers against hand-written Rust and finite differences (proptest).
mod derivatives;
// Every error class: the message text, where the caret points, "did you mean".
mod errors;
// Evaluation at f64 against hand-written Rust on random inputs (proptest).
mod eval;
// Structure read off a Lagrangian: separable or not, symbolic derivatives, the register machine.
mod structure;
// The register machine: fused instructions against the plain layout, bit for bit.
mod tape;
// Parser semantics: precedence, associativity, literals, functions, constants.
mod parse;
