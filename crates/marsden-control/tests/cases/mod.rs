//! The areas of the tests, a file each.

mod bounds;
mod costates;
mod derivatives;
mod errors;
mod final_cost;
mod linear_quadratic;
mod path;
mod reproduction;
mod stages;
mod status;
pub mod swing_up;
