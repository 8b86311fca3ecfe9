//! Options of the sensitivity runs: which Jacobians to keep, how densely to checkpoint.

use crate::error::{Error, InputError};

/// Options of a tangent (forward) run, [`super::tangent`](fn@super::tangent).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TangentOptions {
    /// Keep the Jacobian of every `every`-th state (the initial and the final state always);
    /// `0` keeps the final Jacobian only.
    pub every: usize,
}

/// Options of an adjoint (reverse) gradient, [`super::adjoint`](fn@super::adjoint).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AdjointOptions {
    /// Store every `m`-th state in the forward sweep and recompute the `m` steps in between
    /// (with their Jacobians) in the reverse sweep; `0` chooses `m = ⌈√K⌉` for `K` steps, so
    /// the memory is `O(√K)` states and Jacobians and the work one extra run.
    pub checkpoint_every: usize,
}

impl AdjointOptions {
    /// The checkpoint spacing `m ≥ 1` for a run of `steps` steps.
    pub fn spacing(&self, steps: usize) -> usize {
        match self.checkpoint_every {
            0 => (steps as f64).sqrt().ceil().max(1.0) as usize,
            m => m,
        }
    }
}

/// The error of a loss cotangent of the wrong length.
pub(super) fn check_cotangent(cotangent: &[f64], expected: usize) -> Result<(), Error> {
    Error::check_len("loss cotangent", cotangent, expected)?;
    match cotangent.iter().position(|x| !x.is_finite()) {
        None => Ok(()),
        Some(index) => Err(Error::Input(InputError::NonFinite {
            what: "loss cotangent",
            index,
            value: cotangent[index],
        })),
    }
}
