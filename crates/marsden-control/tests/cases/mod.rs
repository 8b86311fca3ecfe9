//! The areas of the tests, a file each.

mod bounds;
mod costates;
mod derivatives;
mod errors;
mod linear_quadratic;
mod reproduction;
mod status;
mod swing_up;
