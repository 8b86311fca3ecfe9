//! The reference cases R1–R20 (closed forms, unit values, exact solutions, orders), one file per case, named after it.

mod r01_midpoint_oscillator;
mod r02_trapezoid_stormer_verlet;
mod r03_exact_by_shooting;
mod r03_exact_discrete_lagrangian;
mod r04_unit_values;
mod r05_generalized_midpoint_orders;
mod r06_galerkin_orders;
mod r06_regression_second_order;
mod r08_long_run_energy;
mod r09_free_fall_exact;
mod r10_kepler;
mod r12_damped_oscillator;
mod r17_certificate_symplecticity;
mod r17_reversibility_symplecticity;
mod r19_free_rigid_body;
mod r20_heavy_top;
