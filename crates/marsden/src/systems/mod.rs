//! A catalog of canonical mechanical systems, each with documented defaults.
//!
//! Reused by tests, benchmarks, examples and the command-line tool (as GeometricProblems.jl and
//! diffsol's `test_models/` do). Every system implements [`crate::Lagrangian`]; closed-form
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
//! | [`PointRigidBody`] | `x₁ y₁ z₁ …` + distance constraints | tetrahedron, masses 1–4 | momentum, angular momentum |

mod chain;
mod double_pendulum;
mod free_fall;
mod henon_heiles;
mod kepler;
pub mod nbody;
mod oscillator;
mod pendulum;
mod rigid_body;

pub use chain::Chain;
pub use double_pendulum::DoublePendulum;
pub use free_fall::FreeFall;
pub use henon_heiles::HenonHeiles;
pub use kepler::Kepler;
pub use nbody::NBody;
pub use oscillator::HarmonicOscillator;
pub use pendulum::Pendulum;
pub use rigid_body::PointRigidBody;
