//! The one place where a problem file's system becomes a type: [`engine_for`] returns the
//! [`Engine`] of the file's system, compiled for its Lagrangian type — a catalog system's in
//! `marsden-engine-oscillators` or `marsden-engine-orbits`, an expression system's here.
//! Everything after this call is non-generic.

use marsden_engine::{DiscreteEngine, Engine, ExactRun, Typed};

use crate::catalog::BuiltinSystem;
use crate::error::Diagnostic;
use crate::problem::{LagrangianSpec, RunSpec};
use crate::run::start::Start;

/// The engine of `spec`'s system. With `method = "exact"` its runs step the exact discrete
/// Lagrangian by shooting ([`ExactRun`]; the catalog's through the one forwarding type), and
/// every other computation is the system's own.
pub fn engine_for(spec: &RunSpec) -> Box<dyn Engine + '_> {
    let exact = spec.integrator.method.rule().is_none();
    match &spec.system.lagrangian {
        LagrangianSpec::Builtin { system, .. } => match exact {
            true => marsden_engine_orbits::exact(system, catalog_engine(system)),
            false => catalog_engine(system),
        },
        LagrangianSpec::Expression(l) => match exact {
            true => Box::new(ExactRun {
                lagrangian: l,
                rest: Box::new(Typed(l)),
            }),
            false => Box::new(Typed(l)),
        },
        LagrangianSpec::Hamiltonian(l) => match exact {
            true => Box::new(ExactRun {
                lagrangian: l,
                rest: Box::new(Typed(l)),
            }),
            false => Box::new(Typed(l)),
        },
        LagrangianSpec::Discrete(ld) => Box::new(DiscreteEngine(ld)),
    }
}

/// The engine of a catalog system, compiled in one of the two catalog crates.
fn catalog_engine(system: &BuiltinSystem) -> Box<dyn Engine + '_> {
    use marsden_engine_orbits as orbits;
    use marsden_engine_oscillators as oscillators;
    match system {
        BuiltinSystem::HarmonicOscillator(s) => oscillators::harmonic_oscillator(s),
        BuiltinSystem::FreeFall(s) => oscillators::free_fall(s),
        BuiltinSystem::Pendulum(s) => oscillators::pendulum(s),
        BuiltinSystem::DoublePendulum(s) => oscillators::double_pendulum(s),
        BuiltinSystem::Kepler(s) => orbits::kepler(s),
        BuiltinSystem::HenonHeiles(s) => orbits::henon_heiles(s),
        BuiltinSystem::NBody(s) => orbits::nbody(s),
    }
}

/// The complete initial state of `spec`, checked ([`Engine::prepare`] of its engine).
///
/// # Errors
/// The core's objection (a singular Lagrangian, a Legendre transform that cannot be
/// inverted), pointing at the Lagrangian or the initial data.
pub fn prepare(spec: &RunSpec) -> Result<Start, Diagnostic> {
    engine_for(spec).prepare(spec)
}
