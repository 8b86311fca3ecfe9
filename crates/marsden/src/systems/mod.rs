//! A catalog of canonical mechanical systems, each with documented defaults.
//!
//! Reused by tests, benchmarks, examples and the command-line tool (as GeometricProblems.jl and
//! diffsol's `test_models/` do). Every system implements [`crate::mechanics::Lagrangian`]; closed-form
//! invariants and exact solutions sit next to it where they exist.
//!
//! | system | coordinates | defaults | known answers |
//! |---|---|---|---|
//! | [`HarmonicOscillator`] | `q` | m = k = 1 | exact flow |
//! | [`FreeFall`] | `q` | m = 1, g = 9.81 | exact parabola (VIs are exact) |
//! | [`Pendulum`] | `θ` | m = l = g = 1 | energy; period `4K(k)/√(g/l)` |
//! | [`DoublePendulum`] | `θ₁, θ₂` | unit masses, lengths, g | energy |
//! | [`Kepler`] | `x, y` | μ = 1 | energy, angular momentum, exact orbit |
//! | [`HenonHeiles`] | `x, y` | λ = 1 | energy |
//! | [`NBody`] | `x₁ y₁ z₁ …` | G = 1, softening 0 | energy, momentum, angular momentum |
//! | [`Chain`] | `q₁ … q_n` | FPU-β: m = k = β = 1, α = 0, ends fixed | energy |
//! | [`DampedOscillator`] | `q` | m = k = 1, c = 0.1 (+ force `−c v`) | exact damped solution; R12 energy balance |
//! | [`DampedDrivenPendulum`] | `θ` | m = l = g = 1, c = ½, A = 3/2, ω = 2/3 (+ force) | chaotic (Baker–Gollub) |
//! | [`SphericalPendulum`] | `x, y, z`, `\|q\| = l` | m = l = g = 1 (+ constraint) | energy, vertical angular momentum |
//! | [`CartesianPendulum`] | `x, y`, `\|q\| = l` | m = l = g = 1 (+ constraint) | same motion as [`Pendulum`] |
//! | [`CartesianDoublePendulum`] | `x₁ y₁ x₂ y₂`, two rods | as [`DoublePendulum`] (+ constraints) | same motion as [`DoublePendulum`] |
//! | [`PendulumOnCart`] | `x, θ` | M = 1, m = 0.1, l = 0.5, g = 9.8, A = 1, ω = 3 (+ force) | horizontal momentum balance |
//! | [`PointRigidBody`] | `x₁ y₁ z₁ …` + distance constraints | tetrahedron, masses 1–4 | momentum, angular momentum |
//!
//! Systems with forces or constraints implement [`crate::mechanics::Force`] or [`crate::mechanics::Constraint`]
//! themselves, so `Problem::new(sys, …)?.with_force(sys)` / `.with_constraint(sys)?` sets them up.

mod cartesian_double_pendulum;
mod cartesian_pendulum;
mod chain;
mod damped_driven_pendulum;
mod damped_oscillator;
mod double_pendulum;
mod free_fall;
mod henon_heiles;
mod kepler;
pub mod nbody;
mod oscillator;
mod pendulum;
mod pendulum_on_cart;
mod rigid_body;
mod spherical_pendulum;

pub use cartesian_double_pendulum::CartesianDoublePendulum;
pub use cartesian_pendulum::CartesianPendulum;
pub use chain::Chain;
pub use damped_driven_pendulum::DampedDrivenPendulum;
pub use damped_oscillator::DampedOscillator;
pub use double_pendulum::DoublePendulum;
pub use free_fall::FreeFall;
pub use henon_heiles::HenonHeiles;
pub use kepler::Kepler;
pub use nbody::NBody;
pub use oscillator::HarmonicOscillator;
pub use pendulum::Pendulum;
pub use pendulum_on_cart::PendulumOnCart;
pub use rigid_body::PointRigidBody;
pub use spherical_pendulum::SphericalPendulum;
