//! # marsden: discrete mechanics and variational integrators
//!
//! Write a Lagrangian once, generic over a dual-number [`Scalar`], and simulate it with a
//! variational integrator that preserves its geometry (Marsden & West, *Discrete mechanics and
//! variational integrators*, Acta Numerica 2001).
//!
//! ```
//! use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid, systems::Pendulum};
//! use marsden::diagnostics::EnergyReport;
//!
//! let pendulum = Pendulum::default();
//! let problem = Problem::new(pendulum, Initial::velocity(&[1.5], &[0.0]), TimeGrid::new(0.0, 0.05, 2000)?)?;
//! let trajectory = problem.solve(&Midpoint, &SolveOptions::default())?;
//! let energy = EnergyReport::of(&pendulum, &trajectory)?;
//! assert!(energy.max_rel_error < 2e-3); // R8: 8.99e-5 / 0.0707 for h = 0.05
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Map of the crate (data flows down)
//!
//! | stage | module | seed concept |
//! |---|---|---|
//! | scalar | [`scalar`] | one generic axis: `f64` or dual numbers |
//! | system | [`lagrangian`], [`force`], [`constraint`], [`systems`] | `L(t, q, v)`, `f_L`, `φ(q)`, the catalog |
//! | forces | [`forces`] | damping, driving, controls, sums, `f_H ∘ FL`, user `f_d^±` |
//! | constraints | [`holonomic`] | SHAKE + RATTLE, initial data on `T*N`, distance constraints |
//! | continuous mechanics | [`mechanics`] | Legendre transform, energy, Euler–Lagrange, regularity |
//! | discrete Lagrangian | [`discrete`], [`rules`] | `L_d`, `D₁L_d`, `D₂L_d`, `F^±L_d`, DEL; midpoint, trapezoid, α-rules, Galerkin (Gauss, Lobatto), compositions |
//! | exact discrete Lagrangian | [`exact`] | `L_d^E` by shooting, `F^±L_d^E = FL`, local (variational) error |
//! | step | [`step`], [`small`], [`small_constrained`], [`small_dual`], [`dispatch`], [`explicit`], [`separable`], [`potential`], [`newton`], [`linalg`], [`banded`], [`ad`] | discrete Hamiltonian map solved by Newton with AD Jacobians; structure-aware fast paths (explicit Störmer–Verlet, `M/h + (h/4)∇²V`, band solves); x86-64-v3 code chosen at run time |
//! | integrator | [`integrator`], [`compensated`], [`maps`] | rule + forces + constraints + solver + buffers; compensated summation of the update; `F_{L_d}`, `F̃_{L_d}` |
//! | run | [`problem`], [`simulate`], [`trajectory`] | problem → trajectory, stride, observers, failures |
//! | order of convergence | [`order`] | empirical order (log–log slope before round-off), references |
//! | diagnostics | [`diagnostics`] | energy error and drift; momentum maps (Noether) and the force balance; energy balance with forces; constraint residuals and multipliers |
//! | symmetry | [`symmetry`] | group actions, generators and lifts, `J_L`, `J_H`, `J^±_{L_d}`, symmetry checks |
//! | Hamiltonian side | [`hamiltonian`] | `H(q, p)`, `X_H`, implicit midpoint, Störmer–Verlet, Legendre adapters |
//! | certificates | [`certificate`] | exact Jacobian of the step map, symplecticity defect `‖DFᵀJDF − J‖` |
//! | known answers | [`special`] | elliptic functions, exact pendulum, Kepler and oscillator solutions |
//!
//! Conventions (`q, v, p, h, t, n`) and the discrete Legendre transforms
//! `p_k = −D₁L_d(q_k, q_{k+1}) − f_d⁻`, `p_{k+1} = D₂L_d(q_k, q_{k+1}) + f_d⁺` follow DESIGN.md §3.

pub mod analysis;
pub mod discrete;
pub mod error;
pub mod forces;
pub mod hamiltonian;
pub mod holonomic;
pub mod integrator;
pub mod mechanics;
pub mod numerics;
pub mod run;
pub mod scalar;
pub mod separable;
pub mod special;
pub mod studies;
pub mod symmetry;
pub mod systems;

pub use discrete::rules::{GeneralizedMidpoint, Midpoint, Rule, SymmetrizedMidpoint, Trapezoid};
pub use discrete::{DiscreteAction, DiscreteForce, DiscreteLagrangian};
pub use error::Error;
pub use integrator::{Integrator, Statistics, StepReport};
pub use mechanics::{
    Constraint, Force, Initial, Lagrangian, MassMatrix, NoForce, State, Structure, Unconstrained,
};
pub use numerics::newton::NewtonOptions;
pub use run::{
    Observer, Problem, RunFailure, RunOptions, SolveOptions, StepView, Termination, TimeGrid,
    Trajectory, simulate,
};
pub use scalar::Scalar;
