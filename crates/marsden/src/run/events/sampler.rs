//! Samples of a run at chosen times: an observer that reads the states of the run at times
//! between its grid points off the step's cubic Hermite interpolant ([`super::interpolant`]).
//!
//! A requested time `τ` inside the step `(t_k, t_{k+1}]` is sampled as
//!
//! ```text
//! q(τ), v(τ) = the Hermite interpolant of (q_k, v_k), (q_{k+1}, v_{k+1}) at τ,   p(τ) = FL(q(τ), v(τ)),
//! ```
//!
//! with `v = FL⁻¹(q, p)` at both ends (the module docs of [`super::interpolant`] give the
//! interpolant's error: `O(h⁴)` in `q`, `O(h³)` in `v` and `p`, below the error of a method of
//! order ≤ 3, or ≤ 2 for the momenta); a `τ` equal to a grid time is that state itself, and a
//! `τ` equal to the initial time the initial state. The sampler is shown every step, but copies
//! a state only when the next requested time may lie in the step after it (the steps of a
//! [`crate::TimeGrid`] never grow), and computes velocities only at the two ends of a step that
//! contains a requested time — a run with a few sampled times costs little more than without.
//! Requested times before the run's start or after its end are never reached.
//!
//! [`TimeSampler::by_steps`] reaches a time inside a step instead by a variational step of its
//! own size from the grid point before it, taken aside ([`Observer::landing`]): the state a run
//! ending there would reach, exact to the method's order, at the cost of one step per time.
//!
//! ```
//! use marsden::run::events::TimeSampler;
//! use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid};
//! use marsden::systems::Pendulum;
//!
//! let pendulum = Pendulum::default();
//! let grid = TimeGrid::new(0.0, 0.01, 400)?;
//! let problem = Problem::new(pendulum, Initial::velocity(&[1.5], &[0.0]), grid)?;
//! // The quarter period K(sin²0.75) = 1.8252…, between grid points: θ = 0 there.
//! let quarter = pendulum.period(1.5)? / 4.0;
//! let mut sampler = TimeSampler::new(problem.lagrangian(), &[0.0, quarter, 4.0])?;
//! problem.solve_with(&Midpoint, &SolveOptions::default(), &mut sampler)?;
//! let samples = sampler.samples();
//! assert_eq!(samples.len(), 3);
//! assert_eq!(samples[0].q, [1.5]);
//! assert!(samples[1].q[0].abs() < 1e-4);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::ops::ControlFlow;

use super::interpolant::HermiteStep;
use super::legendre::LegendreMaps;
use crate::error::{Error, InputError};
use crate::mechanics::Lagrangian;
use crate::run::observer::{Observer, StepView};
use crate::run::trajectory::Termination;

/// The state of a run at a requested time.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Sample {
    /// The step it lies in (from `t_{step−1}` to `t_step`; 0 for the initial state).
    pub step: usize,
    /// The requested time.
    pub t: f64,
    /// Positions there.
    pub q: Vec<f64>,
    /// Velocities there.
    pub v: Vec<f64>,
    /// Momenta there.
    pub p: Vec<f64>,
}

/// A state of the run kept by the sampler (velocities computed only where a sample is taken).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct Kept {
    step: usize,
    t: f64,
    q: Vec<f64>,
    p: Vec<f64>,
}

impl Kept {
    fn empty(n: usize) -> Self {
        Self {
            step: 0,
            t: f64::NAN,
            q: vec![0.0; n],
            p: vec![0.0; n],
        }
    }

    fn set(&mut self, view: &StepView<'_>) {
        self.step = view.step;
        self.t = view.t;
        self.q.copy_from_slice(view.q);
        self.p.copy_from_slice(view.p);
    }
}

/// Takes [`Sample`]s of a run at requested times, off each step's cubic Hermite interpolant
/// ([`crate::run::events::interpolant`]), or by a step of its own length
/// ([`TimeSampler::by_steps`]): pass it to
/// [`crate::Problem::solve_with`] or [`crate::run::simulate()`], then read
/// [`TimeSampler::samples`].
#[derive(Debug)]
pub struct TimeSampler<'l, L> {
    legendre: LegendreMaps<'l, L>,
    /// The requested times, increasing.
    times: Vec<f64>,
    /// The first of `times` not sampled yet.
    next: usize,
    /// The last state copied: the start of the step being looked at whenever that step
    /// contains a requested time.
    before: Kept,
    /// The time of the last state seen.
    last_t: f64,
    /// Velocities at the two ends of a sampled step, and a point of the interpolant.
    v0: Vec<f64>,
    v1: Vec<f64>,
    samples: Vec<Sample>,
    failure: Option<Error>,
    /// Whether a requested time inside a step is reached by a step of its own size
    /// ([`TimeSampler::by_steps`]) rather than read off the interpolant.
    by_steps: bool,
}

impl<'l, L: Lagrangian> TimeSampler<'l, L> {
    /// A sampler of the runs of `lagrangian` at `times` (whose Legendre transform gives the
    /// velocities of the interpolant).
    ///
    /// # Errors
    /// [`InputError::InvalidOption`] for times that are not finite or not strictly increasing;
    /// the error of a singular declared mass matrix.
    pub fn new(lagrangian: &'l L, times: &[f64]) -> Result<Self, Error> {
        if let Some(bad) = times.iter().find(|t| !t.is_finite()) {
            return Err(invalid(*bad, "a sampled time must be a finite number"));
        }
        if let Some(pair) = times.windows(2).find(|w| w[1] <= w[0]) {
            return Err(invalid(
                pair[1],
                "the sampled times must be strictly increasing",
            ));
        }
        let n = lagrangian.dof();
        Ok(Self {
            legendre: LegendreMaps::new(lagrangian)?,
            times: times.to_vec(),
            next: 0,
            before: Kept::empty(n),
            last_t: f64::NAN,
            v0: vec![0.0; n],
            v1: vec![0.0; n],
            samples: Vec::new(),
            failure: None,
            by_steps: false,
        })
    }

    /// The sampler that reaches each requested time `τ` inside a step `(t_k, t_{k+1})` by a
    /// variational step of its own size `τ − t_k` from the grid point before it, taken aside
    /// by the run loop ([`Observer::landing`]): the sample is, bit for bit, the end of the
    /// same run asked to end at `τ` ([`crate::TimeGrid::ending_at`]: its last step is that
    /// shorter step), exact to the method's order like every grid state, while the run itself
    /// goes on unchanged. Costs one step per requested time; needs a stepper that can be
    /// restored after the step aside ([`crate::run::Stepper::carried`]).
    #[must_use]
    pub fn by_steps(self) -> Self {
        Self {
            by_steps: true,
            ..self
        }
    }

    /// Whether requested times are reached by steps of their own size
    /// ([`TimeSampler::by_steps`]).
    pub fn is_by_steps(&self) -> bool {
        self.by_steps
    }

    /// The samples taken so far, in the order of their times.
    pub fn samples(&self) -> &[Sample] {
        &self.samples
    }

    /// The samples, the sampler consumed.
    pub fn into_samples(self) -> Vec<Sample> {
        self.samples
    }

    /// The requested times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Whether the next requested time may lie in the step after the state at `t`, reached
    /// by a step of `h`: the steps of a grid never grow, so a time more than `h` ahead is not
    /// reached by the next step (twice `h` leaves room for round-off in `h`).
    fn due_soon(&self, t: f64, h: f64) -> bool {
        self.times
            .get(self.next)
            .is_some_and(|&tau| tau <= t + 2.0 * h)
    }

    /// Samples the requested times in the step from `before` to the view's state.
    fn sample_step(&mut self, view: &StepView<'_>) -> Result<(), Error> {
        let before = &self.before;
        let h = view.t - before.t;
        // The secant is the general inverse's first guess at both ends: it depends on the two
        // states alone, so a run resumed from a checkpoint samples the same bits.
        for ((v0, v1), (q0, q1)) in
            (self.v0.iter_mut().zip(self.v1.iter_mut())).zip(before.q.iter().zip(view.q))
        {
            *v0 = (q1 - q0) / h;
            *v1 = *v0;
        }
        let legendre = &mut self.legendre;
        legendre.velocity(before.t, &before.q, &before.p, &mut self.v0)?;
        legendre.velocity(view.t, view.q, view.p, &mut self.v1)?;
        let step = HermiteStep {
            t0: before.t,
            h,
            q0: &before.q,
            v0: &self.v0,
            q1: view.q,
            v1: &self.v1,
        };
        while let Some(&tau) = self.times.get(self.next).filter(|&&tau| tau <= view.t) {
            self.next += 1;
            let sample = if tau == view.t {
                Sample {
                    step: view.step,
                    t: tau,
                    q: view.q.to_vec(),
                    v: self.v1.clone(),
                    p: view.p.to_vec(),
                }
            } else {
                let n = view.q.len();
                let (mut q, mut v, mut p) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
                step.at(tau, &mut q, &mut v);
                self.legendre.momentum(tau, &q, &v, &mut p);
                Sample {
                    step: view.step,
                    t: tau,
                    q,
                    v,
                    p,
                }
            };
            self.samples.push(sample);
        }
        Ok(())
    }

    /// The initial state, if a requested time is the start (earlier ones are passed over).
    fn sample_start(&mut self, initial: &StepView<'_>) -> Result<(), Error> {
        while self
            .times
            .get(self.next)
            .is_some_and(|&tau| tau < initial.t)
        {
            self.next += 1;
        }
        if self.times.get(self.next) != Some(&initial.t) {
            return Ok(());
        }
        self.next += 1;
        let mut v = initial.q.to_vec();
        v.fill(0.0);
        self.legendre
            .velocity(initial.t, initial.q, initial.p, &mut v)?;
        self.samples.push(Sample {
            step: 0,
            t: initial.t,
            q: initial.q.to_vec(),
            v,
            p: initial.p.to_vec(),
        });
        Ok(())
    }
}

/// The error of a bad list of times.
fn invalid(value: f64, reason: &'static str) -> Error {
    Error::Input(InputError::InvalidOption {
        name: "times",
        value,
        reason,
    })
}

impl<L: Lagrangian> Observer for TimeSampler<'_, L> {
    fn start(&mut self, initial: &StepView<'_>) {
        self.samples.clear();
        (self.next, self.failure) = (0, None);
        self.before.set(initial);
        self.last_t = initial.t;
        if let Err(error) = self.sample_start(initial) {
            self.failure = Some(error);
        }
    }

    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        if self.failure.is_some() {
            return ControlFlow::Break(());
        }
        if self.times.get(self.next).is_some_and(|&tau| tau <= view.t)
            && let Err(error) = self.sample_step(view)
        {
            self.failure = Some(error);
            return ControlFlow::Break(());
        }
        let h = view.t - self.last_t;
        self.last_t = view.t;
        if self.due_soon(view.t, h) {
            self.before.set(view);
        }
        ControlFlow::Continue(())
    }

    fn landing(&self, _step: usize, t: f64, next: f64) -> Option<f64> {
        let tau = *self.times.get(self.next)?;
        (self.by_steps && self.failure.is_none() && t < tau && tau < next).then_some(tau)
    }

    /// Keeps the state of the step aside as the sample at its time, its velocity from the
    /// inverse Legendre transform started from the secant of the step to it.
    fn landed(&mut self, reached: Result<&StepView<'_>, &Error>) -> ControlFlow<()> {
        let view = match reached {
            Ok(view) => view,
            Err(error) => {
                self.failure = Some(error.clone());
                return ControlFlow::Break(());
            }
        };
        self.next += 1;
        let h = view.t - self.before.t;
        let mut v: Vec<f64> = (view.q.iter().zip(&self.before.q))
            .map(|(q1, q0)| (q1 - q0) / h)
            .collect();
        if let Err(error) = self.legendre.velocity(view.t, view.q, view.p, &mut v) {
            self.failure = Some(error);
            return ControlFlow::Break(());
        }
        self.samples.push(Sample {
            step: view.step,
            t: view.t,
            q: view.q.to_vec(),
            v,
            p: view.p.to_vec(),
        });
        ControlFlow::Continue(())
    }

    fn termination(&self) -> Option<Termination> {
        self.failure.clone().map(Termination::Failed)
    }
}

/// What a [`TimeSampler`] carries from one step to the next ([`TimeSampler::checkpoint`]).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SamplerCheckpoint {
    next: usize,
    before: Kept,
    last_t: f64,
    samples: Vec<Sample>,
}

impl<L: Lagrangian> TimeSampler<'_, L> {
    /// What the sampler carries to the next step, for a checkpoint of the run: the requested
    /// times reached, the last state copied, and the samples taken.
    pub fn checkpoint(&self) -> SamplerCheckpoint {
        SamplerCheckpoint {
            next: self.next,
            before: self.before.clone(),
            last_t: self.last_t,
            samples: self.samples.clone(),
        }
    }

    /// Restores a [`TimeSampler::checkpoint`] of a sampler of the same times: the next step is
    /// looked at as the checkpointed sampler would have.
    ///
    /// # Errors
    /// [`InputError::DimensionMismatch`] if the checkpoint has another number of coordinates
    /// or has reached past the requested times; the sampler is then unchanged.
    pub fn restore(&mut self, checkpoint: &SamplerCheckpoint) -> Result<(), Error> {
        let sizes = [
            (
                "checkpoint coordinates",
                self.before.q.len(),
                checkpoint.before.q.len(),
            ),
            (
                "checkpoint sampled times",
                self.times.len().min(checkpoint.next),
                checkpoint.next,
            ),
        ];
        for (what, expected, found) in sizes {
            if expected != found {
                return Err(Error::Input(InputError::DimensionMismatch {
                    what,
                    expected,
                    found,
                }));
            }
        }
        self.next = checkpoint.next;
        self.before.clone_from(&checkpoint.before);
        self.last_t = checkpoint.last_t;
        self.samples.clone_from(&checkpoint.samples);
        self.failure = None;
        Ok(())
    }
}
