//! The tests of marsden-control, one binary; a file per area.

mod bounds;
mod costates;
mod derivatives;
mod errors;
mod linear_quadratic;
mod reproduction;
mod swing_up;
