//! `marsden systems [NAME]`: the catalog with coordinates, parameters and defaults.

use marsden_spec::report;

use crate::error::{CliError, Status};

/// Prints the catalog (or one entry).
pub fn systems(name: Option<&str>) -> Result<Status, CliError> {
    print!("{}", report::systems::render(name)?);
    Ok(Status::Completed)
}
