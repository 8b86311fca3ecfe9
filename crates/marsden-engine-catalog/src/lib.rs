//! The engine compiled for each catalog system ([`marsden_problem::catalog::BuiltinSystem`]).
//!
//! The run of every system is compiled once per Lagrangian type (the integrator's hot loops
//! see the system's own code). The catalog's seven systems are most of that code; naming them
//! here, in a crate of their own, lets them compile beside the expression systems, which
//! `marsden-spec`'s factory names.

use marsden_engine::{Engine, ExactRun, Typed};
use marsden_problem::catalog::BuiltinSystem;

/// The engine of `system`, for every computation by the core's rules.
pub fn engine(system: &BuiltinSystem) -> Box<dyn Engine + '_> {
    match system {
        BuiltinSystem::HarmonicOscillator(s) => Box::new(Typed(s)),
        BuiltinSystem::FreeFall(s) => Box::new(Typed(s)),
        BuiltinSystem::Pendulum(s) => Box::new(Typed(s)),
        BuiltinSystem::DoublePendulum(s) => Box::new(Typed(s)),
        BuiltinSystem::Kepler(s) => Box::new(Typed(s)),
        BuiltinSystem::HenonHeiles(s) => Box::new(Typed(s)),
        BuiltinSystem::NBody(s) => Box::new(Typed(s)),
    }
}

/// The engine of `system` for `method = "exact"`: the shooting through the one forwarding
/// type [`BuiltinSystem`] (compiled once for the catalog: a branch per evaluation of `L` costs
/// little beside the shooting's thousands of evaluations per step), everything else through
/// the system's own [`engine`].
pub fn exact_engine(system: &BuiltinSystem) -> Box<dyn Engine + '_> {
    Box::new(ExactRun {
        lagrangian: system,
        rest: engine(system),
    })
}
