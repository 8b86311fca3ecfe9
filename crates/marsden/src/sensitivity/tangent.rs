//! Tangent (forward) sensitivities: the Jacobian of the state along a run.
//!
//! With `x_k = (q_k, p_k)` and the step `x_{k+1} = F(x_k; θ)`, the sensitivity
//! `S_k = ∂x_k/∂(x₀, θ)` (2n × (2n + P)) obeys the variational equation of the discrete map
//! ([MW01] §1.5; [HLW06] §VI.2)
//!
//! ```text
//!     S₀ = [I | 0],      S_{k+1} = DF_x(x_k) S_k + [0 | DF_θ(x_k)],
//! ```
//!
//! each `DF` exact by the implicit function theorem on the converged step
//! ([`crate::analysis::certificate::variational`]), not by differentiating Newton's iterations.
//! For a conservative run the `(q₀, p₀)` block is symplectic, `Sᵀ J S = J`, because each factor
//! is ([`crate::analysis::certificate`]).
//!
//! [MW01]: crate#references
//! [HLW06]: crate#references

use std::ops::ControlFlow;

use super::options::TangentOptions;
use super::step::SensitiveStep;
use crate::error::{Error, InputError};
use crate::integrator::IntegratorCheckpoint;
use crate::mechanics::State;
use crate::run::{Termination, TimeGrid};

/// The sensitivities of a run: the final state and `∂(q, p)/∂(q₀, p₀, θ)` at the final and the
/// kept states.
#[derive(Debug, Clone, PartialEq)]
pub struct Tangent {
    /// Degrees of freedom `n`.
    pub n: usize,
    /// Columns `2n + P`: `q₀`, `p₀`, then the parameters.
    pub columns: usize,
    /// The state the run reached.
    pub state: State,
    /// `∂(q_K, p_K)/∂(q₀, p₀, θ)`, row-major `2n × columns` (rows `q`, then `p`).
    pub jacobian: Vec<f64>,
    /// The kept states and their Jacobians ([`TangentOptions::every`]; a stopped run also
    /// keeps its last state).
    pub samples: Vec<TangentSample>,
    /// [`Termination::Completed`], or [`Termination::Stopped`] when the watcher of
    /// [`tangent_watched`] asked to stop (`state` and `jacobian` are then those of the last
    /// step taken). A failed step is an error, not a termination.
    pub termination: Termination,
}

/// A kept state of a tangent run and its sensitivity.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentSample {
    /// Step index `k`.
    pub step: usize,
    /// The state `x_k`.
    pub state: State,
    /// `∂(q_k, p_k)/∂(q₀, p₀, θ)`, row-major `2n × columns`.
    pub jacobian: Vec<f64>,
}

impl Tangent {
    /// Entry `∂x_row/∂column` of the final Jacobian.
    pub fn get(&self, row: usize, column: usize) -> f64 {
        self.jacobian[row * self.columns + column]
    }

    /// The `(q₀, p₀)` block of the final Jacobian (row-major 2n × 2n).
    pub fn state_block(&self) -> Vec<f64> {
        let m = 2 * self.n;
        (0..m * m)
            .map(|k| self.jacobian[(k / m) * self.columns + k % m])
            .collect()
    }
}

/// `S ← DF_x S + [0 | DF_θ]`: `step` is `[DF_x | DF_θ]` (2n × columns), `s` is 2n × columns,
/// `out` receives the product.
pub(super) fn propagate(step: &[f64], s: &[f64], m: usize, columns: usize, out: &mut [f64]) {
    for r in 0..m {
        let row = &step[r * columns..(r + 1) * columns];
        for c in 0..columns {
            let through: f64 = (0..m).map(|l| row[l] * s[l * columns + c]).sum();
            out[r * columns + c] = through + if c >= m { row[c] } else { 0.0 };
        }
    }
}

/// Runs `stepper` from `start` over `grid` and propagates the sensitivities with it.
///
/// On a failed step the error names the step ([`crate::error::StepFailure`]).
pub fn tangent<D: SensitiveStep + ?Sized>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    options: &TangentOptions,
) -> Result<Tangent, Error> {
    tangent_watched(stepper, start, grid, options, |_| ControlFlow::Continue(()))
}

/// [`tangent`], showing the number of steps taken to `watch` after every step (for a progress
/// display and a stop flag): [`ControlFlow::Break`] ends the run there, with
/// [`Termination::Stopped`] and the sensitivities of the steps taken.
pub fn tangent_watched<D, W>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    options: &TangentOptions,
    watch: W,
) -> Result<Tangent, Error>
where
    D: SensitiveStep + ?Sized,
    W: FnMut(usize) -> ControlFlow<()>,
{
    let mut samples = Vec::new();
    let mut run = tangent_streamed(stepper, start, grid, options, watch, &mut |sample| {
        samples.push(sample.clone());
    })?;
    run.samples = samples;
    Ok(run)
}

/// [`tangent_watched`] handing each kept sample to `sink` as it is reached instead of keeping
/// it: a long run's Jacobians go to a file at the pace of the run, and memory holds two of
/// them (the returned [`Tangent`] has no `samples`).
pub fn tangent_streamed<D, W>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    options: &TangentOptions,
    mut watch: W,
    sink: &mut dyn FnMut(&TangentSample),
) -> Result<Tangent, Error>
where
    D: SensitiveStep + ?Sized,
    W: FnMut(usize) -> ControlFlow<()>,
{
    let columns = 2 * stepper.dof() + stepper.parameters();
    let from = TangentSample::start(start, columns);
    tangent_continued(stepper, from, grid, options, |_, s| watch(s.step), sink)
}

/// [`tangent_streamed`] from `from`, a sample of the run after `from.step` steps (the start,
/// or a [`TangentCheckpoint`]'s, with the stepper restored from it): the steps after it, with
/// `watch` shown the stepper and the sample after every step (where a caller checkpoints the
/// run: [`TangentCheckpoint::of`]). The sample `from` itself is not handed to `sink` again
/// unless it is the start.
///
/// # Errors
/// A failed step (naming it); [`InputError::DimensionMismatch`](crate::error::InputError) for a
/// `from` of other sizes than the stepper's, [`InputError::InvalidOption`] for one past the
/// grid's end.
pub fn tangent_continued<D, W>(
    stepper: &mut D,
    from: TangentSample,
    grid: &TimeGrid,
    options: &TangentOptions,
    mut watch: W,
    sink: &mut dyn FnMut(&TangentSample),
) -> Result<Tangent, Error>
where
    D: SensitiveStep + ?Sized,
    W: FnMut(&D, &TangentSample) -> ControlFlow<()>,
{
    let n = stepper.dof();
    let (m, columns) = (2 * n, 2 * n + stepper.parameters());
    Error::check_len("q0", &from.state.q, n)?;
    Error::check_len("p0", &from.state.p, n)?;
    Error::check_len("jacobian", &from.jacobian, m * columns)?;
    if from.step > grid.steps {
        return Err(Error::Input(InputError::InvalidOption {
            name: "tangent run's first step",
            value: from.step as f64,
            reason: "past the grid's last step",
        }));
    }
    let (mut step, mut next) = (vec![0.0; m * columns], vec![0.0; m * columns]);
    let keep = |k: usize| options.every > 0 && (k.is_multiple_of(options.every) || k == grid.steps);
    let mut current = from;
    if current.step == 0 && keep(0) {
        sink(&current);
    }
    let mut termination = Termination::Completed;
    for k in current.step..grid.steps {
        stepper.step_with_sensitivity(&mut current.state, grid.step_size(k), &mut step)?;
        current.state.t = grid.time(k + 1);
        current.step = k + 1;
        propagate(&step, &current.jacobian, m, columns, &mut next);
        std::mem::swap(&mut current.jacobian, &mut next);
        if keep(k + 1) {
            sink(&current);
        }
        let stop = watch(stepper, &current).is_break();
        if stop && options.every > 0 && !keep(k + 1) {
            sink(&current);
        }
        if stop {
            termination = Termination::Stopped { steps: k + 1 };
            break;
        }
    }
    Ok(Tangent {
        n,
        columns,
        state: current.state,
        jacobian: current.jacobian,
        samples: Vec::new(),
        termination,
    })
}

impl TangentSample {
    /// The start of a tangent run with `columns` columns: step 0 at `state`, `S₀ = [I | 0]`.
    pub fn start(state: State, columns: usize) -> Self {
        let m = 2 * state.q.len();
        let jacobian = (0..m * columns)
            .map(|k| f64::from(u8::from(k / columns == k % columns)))
            .collect();
        Self {
            step: 0,
            state,
            jacobian,
        }
    }
}

/// Everything a tangent run carries from one step to the next: the step reached, the state,
/// the sensitivity `S_k` and what the stepper carries ([`SensitiveStep::carried`]). Restored
/// into a freshly built stepper of the same problem, [`tangent_continued`] from
/// [`TangentCheckpoint::sample`] goes on bit for bit as the uninterrupted run.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TangentCheckpoint {
    /// Steps taken.
    pub step: usize,
    /// The time reached.
    pub t: f64,
    /// Positions.
    pub q: Vec<f64>,
    /// Momenta.
    pub p: Vec<f64>,
    /// `S_k`, row-major `2n × columns`.
    pub jacobian: Vec<f64>,
    /// What the stepper carries.
    pub integrator: IntegratorCheckpoint,
}

impl TangentCheckpoint {
    /// The checkpoint of `stepper` at `sample` (`None`: the stepper cannot be checkpointed).
    pub fn of<D: SensitiveStep + ?Sized>(stepper: &D, sample: &TangentSample) -> Option<Self> {
        Some(Self {
            step: sample.step,
            t: sample.state.t,
            q: sample.state.q.clone(),
            p: sample.state.p.clone(),
            jacobian: sample.jacobian.clone(),
            integrator: stepper.carried()?,
        })
    }

    /// The sample to continue from.
    pub fn sample(&self) -> TangentSample {
        TangentSample {
            step: self.step,
            state: State {
                t: self.t,
                q: self.q.clone(),
                p: self.p.clone(),
            },
            jacobian: self.jacobian.clone(),
        }
    }
}
