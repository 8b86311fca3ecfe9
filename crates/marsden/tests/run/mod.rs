//! Problems, runs, observers, ensembles, input files and bad input.

mod bad_input;
mod ensemble;
mod maps_and_runs;
mod nbody_file;
