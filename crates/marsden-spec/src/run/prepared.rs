//! A problem checked and its initial state prepared once, then run as often as asked: what a
//! binding holds for a problem it was given (Python's `Problem`), so that each run neither
//! reads the file again nor completes and checks the initial state again.

use super::controls::Controls;
use super::execute::{Outcome, PreparedRun, Store, execute_prepared};
use super::start::Start;
use crate::error::{Diagnostic, Error};
use crate::problem::{Overrides, RunSpec};

/// A validated problem with its complete, checked initial state ([`crate::prepare`]).
///
/// The engine ([`crate::engine_for`]) is not held: it borrows the spec it runs, so holding it
/// beside that spec would make the value refer to itself, and building it again is a `match`
/// and a box around references (the expressions were compiled when the spec was validated).
/// What is held is what costs: the validation and the preparation.
#[derive(Debug, Clone)]
pub struct Prepared {
    spec: RunSpec,
    start: Start,
}

impl Prepared {
    /// Prepares the initial state of `spec`.
    ///
    /// # Errors
    /// As [`crate::prepare`]: the core's objection to the initial state.
    pub fn new(spec: RunSpec) -> Result<Prepared, Diagnostic> {
        let start = crate::prepare(&spec)?;
        Ok(Prepared { spec, start })
    }

    /// The validated problem.
    pub fn spec(&self) -> &RunSpec {
        &self.spec
    }

    /// The complete initial state, with the warnings and symmetry checks of its preparation.
    pub fn start(&self) -> &Start {
        &self.start
    }

    /// This problem with `overrides` applied ([`RunSpec::with_overrides`]). Those of the output
    /// keep the prepared state (the initial state does not depend on them); those of the grid
    /// (`steps`, `h`) prepare it again, since what the preparation checks (the memory of the
    /// step system among them) depends on the grid.
    ///
    /// # Errors
    /// As [`RunSpec::with_overrides`], then as [`Prepared::new`] for the grid's overrides.
    pub fn with_overrides(&self, overrides: &Overrides) -> Result<Prepared, Diagnostic> {
        let spec = self.spec.with_overrides(overrides)?;
        match overrides.steps.is_some() || overrides.h.is_some() {
            true => Prepared::new(spec),
            false => Ok(Prepared {
                spec,
                start: self.start.clone(),
            }),
        }
    }

    /// Runs the problem as [`crate::execute`] does, from the prepared state.
    ///
    /// # Errors
    /// As [`crate::execute`].
    pub fn execute(&self, store: Store, controls: &Controls<'_>) -> Result<Outcome, Error> {
        let engine = crate::engine_for(&self.spec);
        let run = PreparedRun {
            engine: engine.as_ref(),
            spec: &self.spec,
            start: &self.start,
        };
        execute_prepared(run, store, controls, None)
    }
}
