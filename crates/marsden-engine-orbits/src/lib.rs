//! The engine compiled for the catalog's orbits — Kepler, Hénon–Heiles, N bodies — and for
//! `method = "exact"` on any catalog system.
//!
//! See `marsden-engine-oscillators` for why the catalog is compiled in two crates.

use marsden::systems::{HenonHeiles, Kepler, NBody};
use marsden_engine::{Engine, ExactRun, Typed};
use marsden_problem::catalog::BuiltinSystem;

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

/// The engine of `system` for `method = "exact"`: the shooting through the one forwarding
/// type [`BuiltinSystem`] (compiled once for the catalog: a branch per evaluation of `L` costs
/// little beside the shooting's thousands of evaluations per step), everything else through
/// `rest`, the system's own engine.
pub fn exact<'a>(system: &'a BuiltinSystem, rest: Box<dyn Engine + 'a>) -> Box<dyn Engine + 'a> {
    Box::new(ExactRun {
        lagrangian: system,
        rest,
    })
}
