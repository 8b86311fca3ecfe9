//! The engine of problem files: everything that steps a system, generic over its Lagrangian
//! type, behind one object-safe trait ([`Engine`]).
//!
//! A problem file names its system at run time; the integrator's hot loops are compiled for
//! each Lagrangian type. This crate holds the generic code and instantiates none of it: the
//! catalog's systems are compiled in `marsden-engine-catalog`, the expression systems (and the
//! catalog's shared `exact` run) in `marsden-spec`, whose factory chooses the engine for a
//! file: the two compile side by side. The caller holds a `Box<dyn Engine>`: one indirect call per run, none per step.
//!
//! # Map of the crate
//!
//! | step | module | what |
//! |---|---|---|
//! | the seam | [`engine`] | [`Engine`]: `prepare`, `run`, `initial_tangent`, `order_study`; [`Typed`], [`ExactRun`], [`DiscreteEngine`] |
//! | caller's hold | [`controls`] | [`Progress`] callback and stop flag ([`Controls`]) |
//! | initial state | [`start`] | `p` from `v` (or back), projection, regularity, symmetry checks |
//! | before a run | [`step_system`] | the size of the step's Newton system, a warning when it is large |
//! | the run | [`solve`] | a `Problem` from the file's parts, stepped by the rule or by shooting |
//! | a file's own `L_d` | [`discrete`] | the run of a `discrete_lagrangian` file |
//! | a rigid body | [`rigid`] | the LGVI's run of a `rigid_body` file, its invariants and symmetry checks |
//! | forced runs | [`balance`] | the discrete energy balance of every step (R12) |
//! | forced runs | [`noether_balance`] | the forced Noether balance of every symmetry (MW01 §3.2) |
//! | on request | [`certify`] | symplecticity defect of the step map (on `T*N` when constrained), equivariance defect of `L_d` |
//! | events | [`events`] | `[[events]]` located along the run, their records streamed (`events.csv`) |
//! | per sample | [`observer`] | one row `t, q, p, energy, J…, residual`, [`diagnostics`] |
//! | derivatives | [`sensitivity`] | `[sensitivity]`: the tangent run's Jacobians |
//! | derivatives | [`sensitivity_writer`] | `sensitivity.npy` / `.csv`, continued after a checkpoint |
//! | order studies | [`order_runner`] | the reference solution and the runs of each method |
//!
//! The file's method is itself the rule ([`marsden::discrete::rules::chosen`]), and the
//! certificate, the tangent run and the order study build the run's own problem type, so each
//! system's integrator is compiled once. A run with `method = "exact"` goes through
//! [`ExactRun`], compiled once for the whole catalog (its shooting evaluates `L` thousands of
//! times per step, where a branch per evaluation costs little).

pub mod balance;
pub mod certify;
pub mod checkpoint;
pub mod controls;
pub mod diagnostics;
pub mod discrete;
pub mod engine;
pub mod events;
mod group_loop;
pub mod multibody;
pub mod noether_balance;
pub mod observer;
pub mod order_runner;
pub mod rigid;
pub mod samples;
pub mod sensitivity;
pub mod sensitivity_writer;
pub mod serialize;
pub mod solve;
pub mod start;
pub mod step_cost;
pub mod step_system;
pub mod tangent;

pub use controls::{CHECK_EVERY, Controls, Progress};
pub use engine::{DiscreteEngine, Engine, ExactRun, Typed};
pub use solve::{Destination, RunRecord};
