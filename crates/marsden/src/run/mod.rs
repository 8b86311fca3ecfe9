//! From a problem to a trajectory: the validated problem, the time grid, one run loop over any
//! [`Stepper`] with its observers, and the stored solution.
//!
//! | module | what |
//! |---|---|
//! | [`problem`] | system + initial data + grid, validated once; `solve` |
//! | [`grid`] | `t_k = t₀ + k h`, storage stride |
//! | [`observer`] | watching each step: monitors, writers, progress, stopping |
//! | [`events`] | zero crossings of `g(t, q, v, p)` located inside the step: recorded, or ending the run |
//! | [`stepper`] | what the loop steps: the Lagrangian and the Hamiltonian integrators |
//! | [`simulate`](mod@simulate) | the one run loop |
//! | [`trajectory`] | stored samples, per-step reports, why the run ended |

pub mod events;
pub mod grid;
pub mod observer;
pub mod problem;
pub mod simulate;
pub mod stepper;
pub mod trajectory;

pub use grid::{RunOptions, TimeGrid};
pub use observer::{Observer, StepView, WatchedSteps, next_multiple};
pub use problem::{Problem, SolveOptions};
pub use simulate::{Resumed, simulate, simulate_from};
pub use stepper::Stepper;
pub use trajectory::{RunFailure, StepMultipliers, Termination, Trajectory};
