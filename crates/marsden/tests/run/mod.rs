//! Problems, runs, observers, events, ensembles, input files and bad input.

mod bad_input;
mod ensemble;
mod events;
mod maps_and_runs;
mod nbody_file;
