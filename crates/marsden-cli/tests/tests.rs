//! The `marsden` command end to end, in one test binary: each module runs the built binary on
//! fixture files (`tests/fixtures/`) or on `examples/`, in temporary directories.

// Helpers outside #[test] functions unwrap too; a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

// Helpers: run the binary, read back trajectory.csv and summary.json, compare numbers.
#[allow(dead_code)]
mod util;

// `marsden run` on malformed or impossible problem files: exit status 2, the message, the
// caret, "did you mean" (the fixtures in tests/fixtures/bad/); failing runs: status 1.
mod bad_input;
// Forced and time-dependent runs: the discrete energy balance instead of an energy error.
mod balance;
// `check`, `systems`, `plot` and usage errors.
mod commands;
// Constrained runs: orders, multipliers, projected starts, refusals, `order` with constraints.
mod constraints;
// `method = "exact"`: R3 through the problem file, refusals.
mod exact;
// `discrete_lagrangian`: R1 from the hand-written midpoint L_d, no energy, refusals.
mod discrete;
// `[[events]]` and observables: crossing times (R7, R10), a stop event, observables' columns,
// bad inputs.
mod events;
// Every file in examples/ runs with reduced steps, as README.md quotes them.
mod examples;
// The guide (docs/guide): every problem file it shows runs, and summary.json still gives the
// numbers its pages quote (docs/guide/examples/expected.toml).
mod guide;
// A `t_end` off the grid: one shorter last step.
mod last_step;
// Numbers written as constant expressions (`h = "2*pi/100"`).
mod numbers;
// `[output] times`: states at chosen times on the step's interpolant (R7), `.npy`, refusals.
mod sampled_times;
// Checkpoints and `marsden resume`: killed runs resumed byte for byte, refusals.
mod resume;
// A sweep's checkpoints: killed sweeps resumed byte for byte, shards.
mod resume_sweep;
// `[system] hamiltonian`: the same map as the Lagrangian, refusals.
mod hamiltonian;
// Silent wrong answers guarded: failed shootings fail, symmetries checked beyond the start,
// step systems larger than memory refused.
mod honest;
// Forces written in the momenta: f_L = f_H ∘ FL, refusals.
mod momentum_forces;
// `[analysis] every_step`: maxima over every step, or the number of samples said.
mod monitor;
// `marsden optimize`: the double integrator's closed form and order, the forced DEL equations on
// the written files, the swing-up against an independent solver, iteration limits, bad input.
mod optimize;
// `[system] control_table`: optimal controls fed to `marsden run` reproduce the optimal
// trajectory; tables that do not fit the run refused.
mod replay;
// `marsden order`: the table, the fitted orders, the CSV, the refused requests.
mod order;
// Plots: which pictures a run gets, angles wrapped and recorded, hostile ranges.
mod plots;
// Sweeps that keep what users need: grids, final states, momentum maps, the energy balance of
// forced members, `.npy` tables, the sweep plot.
mod sweep_results;
// `[system] rigid_body`: R19 and R20 through problem files, the Rust interface's bits, refusals.
mod rigid;
// `[[system.body]]`, `[[system.joint]]`: R21 orders from files against reduced coordinates, R22,
// the satellite's momentum, the chain's columns, refusals.
mod multibody;
mod multibody_springs;
// Particles among jointed bodies.
mod particles;
// `marsden run`: reference values read back from the trajectory, summary.json's fields, the
// expression path against the Rust path, the output formats.
mod run;
// `marsden run` on a file with [sweep]: the table, sweep.csv, shards, threads, failing members.
mod sweep;
// SIGTERM and SIGINT: an interrupted summary with the last state.
mod signals;
// A full disk, huge Newton systems said by `check`, counts too large, constant constraints.
mod robust;
