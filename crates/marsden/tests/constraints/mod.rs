//! Holonomic constraints: SHAKE + RATTLE, the closed form, Cartesian pendulums, typed errors of bad constrained input.

mod double_pendulum_cartesian;
mod errors;
mod rattle_closed_form;
mod spherical_pendulum;
mod stage_constraints;
