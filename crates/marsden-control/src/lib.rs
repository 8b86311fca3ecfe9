//! # marsden-control: discrete mechanics and optimal control (DMOC)
//!
//! Optimal control of mechanical systems with the forced discrete Euler–Lagrange equations as
//! the constraints ([OJM11]): find piecewise-constant controls `u_0 … u_{N−1}` and positions
//! `q_0 … q_N` minimising a discrete cost subject to
//!
//! ```text
//!     D₂L_d(q_{k−1}, q_k) + f_d⁺_{k−1} + D₁L_d(q_k, q_{k+1}) + f_d⁻_k = 0,     k = 1 … N−1,
//!     p_0 = −D₁L_d(q_0, q_1) − f_d⁻_0,     p_N = D₂L_d(q_{N−1}, q_N) + f_d⁺_{N−1},
//! ```
//!
//! with `L_d` and `f_d^±` the core's ([`marsden::Rule`]), so the constraints are exactly the
//! steps of [`marsden::Integrator`]: an optimal trajectory fed back to the integrator with its
//! controls reproduces itself ([`SampledControl`]).
//!
//! ```
//! use marsden_control::{Boundary, Effort, Horizon, InputMap, OptimalControl, SqpOptions};
//! use marsden::{Midpoint, systems::FreeFall};
//!
//! // Double integrator: L = ½q̇², force u, cost ∫½u², rest to rest from 0 to 1 in T = 1.
//! let problem = OptimalControl::new(
//!     FreeFall { m: 1.0, g: 0.0 },
//!     InputMap::full(1),
//!     Effort::default(),
//!     Horizon { t0: 0.0, duration: 1.0, steps: 20 },
//!     Boundary::rest(&[0.0]),
//!     Boundary::rest(&[1.0]),
//! )?;
//! let solution = problem.solve(&Midpoint, &SqpOptions::default())?;
//! assert!(solution.converged());
//! assert!((solution.cost - 6.0).abs() < 0.05); // continuous optimum: 6
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Solver
//!
//! A short SQP iteration ([`sqp`]) with the exact Hessian of the Lagrangian from the core's
//! automatic differentiation, each quadratic subproblem solved by Clarabel, a maintained
//! pure-Rust sparse interior-point solver, on compressed sparse column matrices (banded in
//! `k`). Chosen over IPOPT because it needs no system library: the IPOPT binding builds a C++
//! wrapper with cmake, bindgen and curl at build time and would add a system package to CI.
//!
//! ## Map
//!
//! | module | concept |
//! |---|---|
//! | [`model`] | `f(t, q, v, u)`, `C(t, q, v, u)`, `Φ(q_N, p_N)`, `g(t, q, v, u) ≤ 0`; ready-made input map and effort |
//! | [`problem`] | [`OptimalControl`]: system, horizon, boundary conditions, bounds, path inequalities, guess |
//! | [`transcription`] | unknowns, constraints, cost and their derivatives by AD |
//! | [`stages`] | one control value per step, or one per stage of the rule |
//! | [`qp`], [`sqp`] | the subproblem (Clarabel) and the SQP iteration |
//! | [`solve`], [`solution`] | the solve and its [`Solution`] |
//! | [`guess`] | initial guesses; controls as core forces |
//! | [`check`] | derivatives against central differences |
//!
//! ## References
//!
//! * **OJM11**: S. Ober-Blöbaum, O. Junge, J. E. Marsden, *Discrete mechanics and optimal
//!   control: an analysis*, ESAIM: COCV 17 (2011) 322–352.
//! * **NW06**: J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed. (2006).
//! * **GMS05**: P. E. Gill, W. Murray, M. A. Saunders, *SNOPT: an SQP algorithm for large-scale
//!   constrained optimization*, SIAM Review 47 (2005) 99–131.
//! * **BH75**: A. E. Bryson, Y.-C. Ho, *Applied Optimal Control* (1975).
//! * **GW08**: Griewank & Walther, *Evaluating Derivatives*, 2nd ed. (2008).
//! * **Sanz-Serna 2016**: J. M. Sanz-Serna, *Symplectic Runge–Kutta schemes for adjoint
//!   equations, automatic differentiation, optimal control and more*, SIAM Review 58 (2016).
//!
//! [OJM11]: crate#references

pub mod check;
pub mod error;
pub mod guess;
pub mod model;
pub mod problem;
pub mod qp;
pub mod solution;
pub mod solve;
pub mod sqp;
pub mod stages;
pub mod transcription;

pub use check::DerivativeCheck;
pub use error::ControlError;
pub use guess::{FrozenControl, SampledControl, StepControl};
pub use model::{
    ControlForce, Effort, FinalCost, InputMap, NoFinalCost, NoPath, PathConstraint, RunningCost,
};
pub use problem::{Boundary, Bounds, Guess, Horizon, OptimalControl, Rate};
pub use solution::{Failure, Infeasibility, Iteration, Solution, Status};
pub use sqp::SqpOptions;
pub use stages::{ControlStages, PathPoints, StagedControls};
