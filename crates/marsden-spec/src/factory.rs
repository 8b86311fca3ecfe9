//! The one place where a problem file's system becomes a type: [`engine_for`] returns the
//! [`Engine`] of the file's system, compiled for its Lagrangian type — a catalog system's in
//! `marsden-engine-catalog`, an expression system's (and the catalog's shared `exact` run) here.
//! Everything after this call is non-generic.

use marsden::Lagrangian;
use marsden_engine::multibody::MultibodyEngine;
use marsden_engine::rigid::RigidEngine;
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
            true => Box::new(ExactRun {
                lagrangian: system,
                rest: catalog_engine(system),
            }),
            false => catalog_engine(system),
        },
        LagrangianSpec::Expression(l) => expression_engine(l, exact),
        LagrangianSpec::Hamiltonian(h) => match &h.separable {
            Some(l) => expression_engine(l, exact),
            None => expression_engine(&h.general, exact),
        },
        LagrangianSpec::Discrete(ld) => Box::new(DiscreteEngine(ld)),
        LagrangianSpec::Rigid(body) => Box::new(RigidEngine(body)),
        LagrangianSpec::Multibody(bodies) => Box::new(MultibodyEngine(bodies)),
    }
}

/// The engine of an expression system (compiled here): by the rules, or by shooting with
/// `exact`, the rest by the rules.
fn expression_engine<L: Lagrangian>(l: &L, exact: bool) -> Box<dyn Engine + '_> {
    match exact {
        true => Box::new(ExactRun {
            lagrangian: l,
            rest: Box::new(Typed(l)),
        }),
        false => Box::new(Typed(l)),
    }
}

/// The engine of a catalog system, compiled in `marsden-engine-catalog`.
fn catalog_engine(system: &BuiltinSystem) -> Box<dyn Engine + '_> {
    use marsden_engine_catalog as catalog;
    match system {
        BuiltinSystem::HarmonicOscillator(s) => catalog::harmonic_oscillator(s),
        BuiltinSystem::FreeFall(s) => catalog::free_fall(s),
        BuiltinSystem::Pendulum(s) => catalog::pendulum(s),
        BuiltinSystem::DoublePendulum(s) => catalog::double_pendulum(s),
        BuiltinSystem::Kepler(s) => catalog::kepler(s),
        BuiltinSystem::HenonHeiles(s) => catalog::henon_heiles(s),
        BuiltinSystem::NBody(s) => catalog::nbody(s),
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
