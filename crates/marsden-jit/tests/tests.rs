//! The native code's tests, in one binary.

// Helpers outside #[test] functions unwrap too; a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

// Compiled tapes against the interpreter, bit for bit: reference potentials, every function,
// special inputs, random expressions.
mod agreement;

// The compiled Verlet run against the same loop in Rust around the tape interpreter.
mod verlet;
