//! Order studies of a problem file (`marsden order`): the [`Plan`] checked against the file
//! (`marsden_problem::order`), the runs of the file's engine ([`measure`]), the table.

pub mod table;

pub use marsden_engine::order_runner as runner;
pub use marsden_problem::order::*;

use crate::error::Error;
use crate::problem::RunSpec;

/// Runs the study of `plan` on the problem of `spec`, with the engine of its system.
///
/// # Errors
/// Status 2 for initial data the core rejects; status 1 if the reference solution cannot be
/// computed. A run that fails is a point with error `NaN` in its study, not an error.
pub fn measure(spec: &RunSpec, plan: &Plan) -> Result<runner::Results, Error> {
    crate::engine_for(spec).order_study(spec, plan)
}
