//! The engine compiled for each system of the catalog (`marsden::systems`).
//!
//! The run of every system is compiled once per Lagrangian type (the integrator's hot loops
//! see the system's own code), and the catalog's seven systems are most of that code. Naming
//! them here, in a crate of their own, lets them compile beside `marsden-spec`, which names the
//! expression systems (and the shared `exact` run of the catalog): two optimised modules on
//! two cores. `marsden_spec::engine_for` calls one function per system.

use marsden::systems::{
    DoublePendulum, FreeFall, HarmonicOscillator, HenonHeiles, Kepler, NBody, Pendulum,
};
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

/// The engine of the Kepler problem.
pub fn kepler(system: &Kepler) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}

/// The engine of the Hénon–Heiles system.
pub fn henon_heiles(system: &HenonHeiles) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}

/// The engine of the N-body problem.
pub fn nbody(system: &NBody) -> Box<dyn Engine + '_> {
    Box::new(Typed(system))
}
