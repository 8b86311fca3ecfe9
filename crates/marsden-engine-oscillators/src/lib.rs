//! The engine compiled for the catalog's oscillators and pendulums: harmonic oscillator, free
//! fall, pendulum, double pendulum.
//!
//! The run of every system is compiled once per Lagrangian type (the integrator's hot loops
//! see the system's own code), and the catalog's systems are most of that code. They are
//! named in two crates — this one and `marsden-engine-orbits` — that compile side by side with
//! `marsden-spec` (the expression systems), each as one optimised module: the split follows
//! the build's two cores, not the physics. `marsden_spec::engine_for` calls one function per
//! system.

use marsden::systems::{DoublePendulum, FreeFall, HarmonicOscillator, Pendulum};
use marsden_engine::{Engine, Typed};

/// The engine of a harmonic oscillator.
pub fn harmonic_oscillator(system: &HarmonicOscillator) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}

/// The engine of free fall.
pub fn free_fall(system: &FreeFall) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}

/// The engine of a pendulum.
pub fn pendulum(system: &Pendulum) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}

/// The engine of a double pendulum.
pub fn double_pendulum(system: &DoublePendulum) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}
