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
use crate::error::Error;
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
    let n = stepper.dof();
    let (m, columns) = (2 * n, 2 * n + stepper.parameters());
    Error::check_len("q0", &start.q, n)?;
    Error::check_len("p0", &start.p, n)?;
    let s: Vec<f64> = (0..m * columns)
        .map(|k| f64::from(u8::from(k / columns == k % columns)))
        .collect();
    let (mut step, mut next) = (vec![0.0; m * columns], vec![0.0; m * columns]);
    let keep = |k: usize| options.every > 0 && (k.is_multiple_of(options.every) || k == grid.steps);
    let mut current = TangentSample {
        step: 0,
        state: start,
        jacobian: s,
    };
    if keep(0) {
        sink(&current);
    }
    let mut termination = Termination::Completed;
    for k in 0..grid.steps {
        stepper.step_with_sensitivity(&mut current.state, grid.step_size(k), &mut step)?;
        current.state.t = grid.time(k + 1);
        current.step = k + 1;
        propagate(&step, &current.jacobian, m, columns, &mut next);
        std::mem::swap(&mut current.jacobian, &mut next);
        let stop = watch(k + 1).is_break();
        if keep(k + 1) || (stop && options.every > 0) {
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
