//! Group actions, momentum maps and Noether (continuous, discrete, with forces).

mod checks;
mod forced_noether;
mod kepler_noether;
mod rigid_body;
mod solar_system;
