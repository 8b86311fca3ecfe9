//! Rules of high order: compositions and Galerkin methods on long runs, with forces and constraints.

mod chosen_rule;
mod composition_orders;
mod high_order_forces_constraints;
mod kepler_high_order;
