//! The problem-file layer through its public entry points, without the binary: what a Python
//! binding calls. One test binary.

// Helpers outside #[test] functions unwrap too; a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

// Problem text from memory: the spec, and diagnostics with the file's line and caret.
mod load;
// Runs in memory, to files and both: the same samples bit for bit; summaries; sweeps.
mod memory;
// Expression Lagrangians recognised as separable: fast paths against the general path.
mod structure;
// A discrete Lagrangian written as an expression against the midpoint rule.
mod discrete;
// The controls of a run: the progress callback and the stop flag.
mod controls;
// Hostile inputs: limits, honest reports, safe outputs.
mod robust;
// Certificates and symmetries: named symmetries, certify = true, the forced Noether balance.
mod certify;
// `[sensitivity]`: Jacobians of the run against closed forms and finite differences.
mod sensitivity;

use std::path::{Path, PathBuf};

use marsden_spec::{Overrides, RunSpec};

/// The repository's `examples/` file `name`.
pub fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// `examples/<name>`, writing into `out` and with `steps` steps if given.
pub fn load_example(name: &str, out: &Path, steps: Option<u64>) -> RunSpec {
    let overrides = Overrides {
        steps,
        h: None,
        out: Some(out.to_owned()),
        checkpoint_every: None,
        every: None,
    };
    marsden_spec::load(&example(name), &overrides).unwrap_or_else(|d| panic!("{d}"))
}
