//! Library part of the `marsden` command: the pieces the binary is built from.

pub mod expr;
