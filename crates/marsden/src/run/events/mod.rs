//! Events located inside the step: zero crossings of functions `g(t, q, v, p)` along a run,
//! recorded or ending the run.
//!
//! An [`Event`] is a function `g` ([`EventFunction`]) with the [`Direction`] of the crossings it
//! watches (`g` rising through zero, falling, or both), an [`Action`] (record each crossing, or
//! stop the run) and an optional count (stop at the n-th crossing; record at most n). The
//! [`EventDetector`] is an [`Observer`](super::Observer) that watches the steps inside the
//! stretches the run loop hands the stepper
//! ([`Observer::watch_steps`](super::Observer::watch_steps): a run with events is not taken
//! step by step through the loop): after each step it evaluates every event once at the new
//! state `(t_{k+1}, q_{k+1}, v_{k+1}, p_{k+1})` — one evaluation of each `g` per step while
//! nothing fires — and on a sign change locates the root inside the step on
//! the step's cubic Hermite interpolant ([`interpolant`]) with Brent's method
//! ([`crate::numerics::brent`]). The velocities `v = FL⁻¹(q, p)` cost an inverse Legendre
//! transform (a Newton solve for a Lagrangian without a declared mass matrix): they are computed
//! at every step only when some event's `g` reads them ([`Event::reads_velocity`]); otherwise
//! only at the two ends of a step where a sign change was found, for the interpolant, and `g`
//! is shown NaN velocities (so that a `g` wrongly declared not to read `v` fails the run with
//! [`StepError::EventNotFinite`](crate::error::StepError::EventNotFinite) instead of reading
//! stale numbers). A crossing becomes an
//! [`EventRecord`] `(event, t, q, v, p)`; a stopping event ends the run after its step with
//! [`Termination::Event`](super::Termination::Event).
//!
//! Conventions: an `Up` crossing is `g_k < 0 ≤ g_{k+1}`, a `Down` crossing `g_k > 0 ≥ g_{k+1}`,
//! so a state exactly on `g = 0` counts once (in the step that reached it) and the initial state
//! never fires. Two crossings of the same event inside one step (a sign change and back) are not
//! seen: take `h` small against the time between crossings.
//!
//! ```
//! use marsden::run::events::{Direction, Event, EventDetector};
//! use marsden::{Initial, Midpoint, Problem, SolveOptions, Termination, TimeGrid};
//! use marsden::systems::Pendulum;
//!
//! let pendulum = Pendulum::default();
//! let grid = TimeGrid::new(0.0, 0.01, 2000)?;
//! let problem = Problem::new(pendulum, Initial::velocity(&[1.5], &[0.0]), grid)?;
//! // θ falls through zero a quarter period after release, T/4 = K(sin²0.75) = 1.8252…
//! let theta = |_t: f64, q: &[f64], _v: &[f64], _p: &[f64]| q[0];
//! // g reads θ only: the velocities are computed at the crossing's step alone.
//! let events = vec![Event::stop(theta, Direction::Down).without_velocity()];
//! let mut detector = EventDetector::new(problem.lagrangian(), events)?;
//! let run = problem.solve_with(&Midpoint, &SolveOptions::default(), &mut detector)?;
//! let quarter = pendulum.period(1.5)? / 4.0;
//! assert!(matches!(run.termination, Termination::Event { event: 0, steps: 183, .. }));
//! assert!((detector.records()[0].t - quarter).abs() < 1e-4);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod detector;
pub mod interpolant;
mod legendre;
mod sampler;

pub use detector::{DetectorCheckpoint, EventDetector};
pub use sampler::{Sample, SamplerCheckpoint, TimeSampler};

/// A scalar function `g(t, q, v, p)` on the states of a run, whose zeros are events.
pub trait EventFunction {
    /// `g` at time `t`, positions `q`, velocities `v` and momenta `p`.
    fn value(&self, t: f64, q: &[f64], v: &[f64], p: &[f64]) -> f64;
}

/// Any closure `|t, q, v, p| -> f64` is an event function.
impl<F: Fn(f64, &[f64], &[f64], &[f64]) -> f64> EventFunction for F {
    fn value(&self, t: f64, q: &[f64], v: &[f64], p: &[f64]) -> f64 {
        self(t, q, v, p)
    }
}

/// Which sign changes of `g` are events.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Direction {
    /// `g` rises through zero (`g_k < 0 ≤ g_{k+1}`).
    Up,
    /// `g` falls through zero (`g_k > 0 ≥ g_{k+1}`).
    Down,
    /// Either.
    Both,
}

impl Direction {
    /// Whether going from `before` to `after` is a crossing in this direction.
    #[inline]
    pub fn crosses(self, before: f64, after: f64) -> bool {
        let up = before < 0.0 && after >= 0.0;
        let down = before > 0.0 && after <= 0.0;
        match self {
            Direction::Up => up,
            Direction::Down => down,
            Direction::Both => up || down,
        }
    }
}

/// What a crossing does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Action {
    /// Record it and go on.
    Record,
    /// Record it and end the run after the step it lies in.
    Stop,
}

/// An event: a function, the crossings it watches, what they do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event<G> {
    /// `g(t, q, v, p)`.
    pub function: G,
    /// The crossings watched.
    pub direction: Direction,
    /// What a crossing does.
    pub action: Action,
    /// `Stop`: stop at this crossing (1 = the first; the earlier ones are recorded).
    /// `Record`: record at most this many. `None`: 1 for `Stop`, no limit for `Record`.
    pub count: Option<usize>,
    /// Whether `g` reads the velocities `v` (its third argument). True unless declared
    /// otherwise ([`Event::without_velocity`]): if no event reads them, the detector computes
    /// them only at the ends of a step with a sign change, and `g` sees NaN in their place.
    pub reads_velocity: bool,
}

impl<G: EventFunction> Event<G> {
    /// Records every crossing of `function` in `direction`.
    pub fn record(function: G, direction: Direction) -> Self {
        Self {
            function,
            direction,
            action: Action::Record,
            count: None,
            reads_velocity: true,
        }
    }

    /// Stops the run at the first crossing of `function` in `direction`.
    pub fn stop(function: G, direction: Direction) -> Self {
        Self {
            function,
            direction,
            action: Action::Stop,
            count: None,
            reads_velocity: true,
        }
    }

    /// Stops at (or records up to) the `n`-th crossing (`n ≥ 1`, checked by
    /// [`EventDetector::new`]).
    pub fn count(self, n: usize) -> Self {
        Self {
            count: Some(n),
            ..self
        }
    }

    /// Declares that `g` reads only `t`, `q` and `p`, not `v`: the detector then skips the
    /// inverse Legendre transform at the steps where nothing fires (`g` is shown NaN
    /// velocities, so a `g` that reads them after all fails the run rather than reading stale
    /// numbers).
    pub fn without_velocity(self) -> Self {
        Self {
            reads_velocity: false,
            ..self
        }
    }
}

/// A located crossing.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EventRecord {
    /// Index of the event in the detector's list.
    pub event: usize,
    /// Which way `g` crossed (`Up` or `Down`).
    pub direction: Direction,
    /// The step it lies in (from `t_{step−1}` to `t_step`).
    pub step: usize,
    /// Its time.
    pub t: f64,
    /// Positions there (on the step's interpolant).
    pub q: Vec<f64>,
    /// Velocities there.
    pub v: Vec<f64>,
    /// Momenta there, `FL(q, v)`.
    pub p: Vec<f64>,
}
