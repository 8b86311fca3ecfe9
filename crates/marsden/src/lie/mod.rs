//! Rigid bodies on SO(3) (× ℝ³): the Lie group variational integrator of Lee, Leok &
//! McClamroch ([LLM05], [LLM07]).
//!
//! The configuration of body `i` is its attitude `R_i ∈ SO(3)` (body → space; `Ṙ = R Ω^`, `Ω`
//! the body angular velocity) and, for a free body, its centre of mass `x_i ∈ ℝ³`. The momenta
//! are `Π = JΩ` (body frame) and `p = m ẋ`. The step ([`lgvi`]) solves three Cayley parameters
//! per body by Newton ([`cayley`]); the attitude is updated by multiplication with an exact
//! rotation, so `R` stays on SO(3) to round-off without projection.
//!
//! * [`so3`]: hat, vee, exp, log, Cayley, quaternions, re-orthonormalisation;
//! * [`body`]: the inertia tensor (validated) and a body, fixed or free;
//! * [`potential`]: potentials generic over [`crate::Scalar`], external loads, the body moment
//!   `M` by automatic differentiation;
//! * [`state`]: a system of bodies and its state `(t, R, Π, x, p)`;
//! * [`lgvi`]: the step and its compositions of order 4, 6, 8;
//! * [`invariants`]: energy, spatial and body momenta, Casimir, orthogonality defect;
//! * [`trajectory`]: a sampled run;
//! * [`multibody`]: bodies joined by joints (spherical, revolute, prismatic, fixed, distance),
//!   springs and dampers.
//!
//! ```
//! use marsden::lie::{body::{Inertia, RigidBody}, potential::NoPotential, so3,
//!     state::{BodyInitial, RigidState, RigidSystem}, lgvi::{Lgvi, LgviOptions}, invariants};
//! let body = RigidBody::fixed_point(Inertia::principal_unphysical([2.0, 1.0, 2.0 / 3.0])?);
//! let system = RigidSystem::new(vec![body], NoPotential);
//! let pi0 = so3::Vec3::new(1.1_f64.cos(), 0.0, 1.1_f64.sin());
//! let state = RigidState::new(&system, 0.0, &[BodyInitial::rotating(&so3::Mat3::identity(), &pi0)])?;
//! let mut lgvi = Lgvi::new(system, state, 0.1, LgviOptions::default())?;
//! for _ in 0..100 { lgvi.step()?; }
//! assert!((invariants::casimir(lgvi.state(), 0) - 1.0).abs() < 1e-13); // R19
//! # Ok::<(), marsden::Error>(())
//! ```
//!
//! [LLM05]: crate#references
//! [LLM07]: crate#references

pub mod body;
pub mod cayley;
pub mod invariants;
pub mod lgvi;
pub mod multibody;
pub mod potential;
pub mod so3;
pub mod state;
pub mod trajectory;
