//! Problems, runs, observers, events, checkpoints, ensembles, input files and bad input.

mod bad_input;
mod checkpoint;
mod ensemble;
mod events;
mod last_step;
mod maps_and_runs;
mod nbody_file;
mod sampled_by_steps;
mod sampled_times;
