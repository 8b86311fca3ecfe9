//! Adjoint (reverse) gradients of a loss summed over the states of a run.
//!
//! For `Λ = Σ_k ℓ_k(x_k)`, `x_k = (q_k, p_k)`, `x_{k+1} = F(x_k; θ)`, the discrete adjoint
//! ([GW08] §3; for variational integrators the adjoint of the discrete Hamiltonian map is again
//! a symplectic map, [Sanz-Serna 2016] §3) is
//!
//! ```text
//!     λ_K = ∇ℓ_K(x_K),     λ_k = DF_x(x_k)ᵀ λ_{k+1} + ∇ℓ_k(x_k),     g_θ = Σ_k DF_θ(x_k)ᵀ λ_{k+1},
//!     dΛ/dx₀ = λ₀,          dΛ/dθ = g_θ,
//! ```
//!
//! the transposed step Jacobians applied backwards: one vector–Jacobian product per step,
//! whatever the number of inputs (the tangent run, [`super::tangent`](fn@super::tangent), costs `2n + P` columns
//! per step). The reverse sweep needs the states backwards; [`super::checkpoints`] stores every
//! `m`-th one and recomputes the segment in between, so memory is `O(K/m + m)`.
//!
//! [GW08]: crate#references
//! [Sanz-Serna 2016]: crate#references

use std::ops::ControlFlow;

use super::checkpoints::{Checkpoints, Segment};
use super::options::{AdjointOptions, check_cotangent};
use super::step::SensitiveStep;
use crate::error::Error;
use crate::mechanics::State;
use crate::run::{Termination, TimeGrid};

/// The gradient of a loss over a run, and what the reverse sweep kept in memory.
#[derive(Debug, Clone, PartialEq)]
pub struct Gradient {
    /// Degrees of freedom `n`.
    pub n: usize,
    /// The state the run reached.
    pub state: State,
    /// `dΛ/d(q₀, p₀, θ)` (length `2n + P`); empty when the run was stopped.
    pub gradient: Vec<f64>,
    /// Checkpoints stored by the forward sweep.
    pub checkpoints: usize,
    /// Steps per recomputed segment (the states and Jacobians held at once).
    pub segment: usize,
    /// [`Termination::Completed`], or [`Termination::Stopped`] when the watcher of
    /// [`adjoint_watched`] asked to stop (no gradient then: it needs both sweeps whole; `state`
    /// is the last one the forward sweep reached). A failed step is an error, not a
    /// termination.
    pub termination: Termination,
}

/// `λ ← DF_xᵀ λ`, `g ← g + DF_θᵀ λ` for one step Jacobian `[DF_x | DF_θ]` (2n × columns);
/// `sums` has length `columns`.
///
/// Each entry of `[DF_x | DF_θ]ᵀ λ = Σ_r λ_r row_r` is summed over the rows in order from
/// `−0.0`, the start of `Iterator::sum` for `f64`, so the result is that of the column sums
/// `Σ_r DF_{rc} λ_r` bit for bit, read row by row.
pub(super) fn pull_back(
    jac: &[f64],
    m: usize,
    lambda: &mut [f64],
    g: &mut [f64],
    sums: &mut [f64],
) {
    let columns = m + g.len();
    sums.fill(-0.0);
    for (row, l) in jac.chunks_exact(columns).zip(lambda.iter()) {
        sums.iter_mut().zip(row).for_each(|(s, j)| *s += j * l);
    }
    let (through, direct) = sums.split_at(m);
    lambda.copy_from_slice(through);
    g.iter_mut().zip(direct).for_each(|(gp, s)| *gp += s);
}

/// The gradient of `Λ = Σ_k ℓ_k(q_k, p_k)` over the run of `stepper` from `start` on `grid`
/// with respect to `(q₀, p₀, θ)`.
///
/// `loss(k, x_k, out)` adds `∂ℓ_k/∂(q_k, p_k)` (the cotangent of sample `k`, `q` then `p`) into
/// `out` (length 2n, zero on entry); it is called once for every `k = 0 … K`, backwards, and
/// leaves `out` alone where the loss has no term.
pub fn adjoint<D, L>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    loss: L,
    options: &AdjointOptions,
) -> Result<Gradient, Error>
where
    D: SensitiveStep + Clone,
    L: FnMut(usize, &State, &mut [f64]),
{
    let watch = |_| ControlFlow::Continue(());
    adjoint_watched(stepper, start, grid, loss, options, watch)
}

/// [`adjoint`], showing the steps of work done to `watch` after every step of either sweep
/// (`1 … K` forwards, then `K + 1 … 2K` backwards: a progress display and a stop flag):
/// [`ControlFlow::Break`] ends the run there, with [`Termination::Stopped`] (`steps`: the
/// count shown last) and no gradient.
pub fn adjoint_watched<D, L, W>(
    stepper: &mut D,
    start: State,
    grid: &TimeGrid,
    loss: L,
    options: &AdjointOptions,
    mut watch: W,
) -> Result<Gradient, Error>
where
    D: SensitiveStep + Clone,
    L: FnMut(usize, &State, &mut [f64]),
    W: FnMut(usize) -> ControlFlow<()>,
{
    let n = stepper.dof();
    let m = 2 * n;
    Error::check_len("q0", &start.q, n)?;
    Error::check_len("p0", &start.p, n)?;
    let every = options.spacing(grid.steps);
    let (checkpoints, state, stopped) =
        Checkpoints::record(stepper, start.clone(), grid, every, &mut watch)?;
    let mut gradient = Gradient {
        n,
        state,
        gradient: Vec::new(),
        checkpoints: checkpoints.len(),
        segment: every.min(grid.steps),
        termination: Termination::Completed,
    };
    if let Some(steps) = stopped {
        gradient.termination = Termination::Stopped { steps };
        return Ok(gradient);
    }
    let sweep = Sweep {
        grid,
        start: &start,
        m,
        parameters: stepper.parameters(),
    };
    match sweep.reverse(&checkpoints, loss, watch)? {
        ControlFlow::Continue(g) => gradient.gradient = g,
        ControlFlow::Break(steps) => gradient.termination = Termination::Stopped { steps },
    }
    Ok(gradient)
}

/// What the reverse sweep needs besides the checkpoints: the grid, `x₀`, `2n` and `P`.
struct Sweep<'a> {
    grid: &'a TimeGrid,
    start: &'a State,
    m: usize,
    parameters: usize,
}

impl Sweep<'_> {
    /// `λ_k = DF_x(x_k)ᵀ λ_{k+1} + ∇ℓ_k(x_k)` and `g_θ` backwards over the recomputed
    /// segments, showing `K + 1 … 2K` to `watch`: `(λ₀, g_θ)` end to end, or the count at
    /// which `watch` asked to stop.
    fn reverse<D, L, W>(
        &self,
        checkpoints: &Checkpoints<D>,
        mut loss: L,
        mut watch: W,
    ) -> Result<ControlFlow<usize, Vec<f64>>, Error>
    where
        D: SensitiveStep + Clone,
        L: FnMut(usize, &State, &mut [f64]),
        W: FnMut(usize) -> ControlFlow<()>,
    {
        let m = self.m;
        let (mut lambda, mut g) = (vec![0.0; m], vec![0.0; self.parameters]);
        let (mut sums, mut cot) = (vec![0.0; m + self.parameters], vec![0.0; m]);
        let mut add = |k: usize, x: &State, lambda: &mut [f64]| -> Result<(), Error> {
            cot.fill(0.0);
            loss(k, x, &mut cot);
            check_cotangent(&cot, m)?;
            lambda.iter_mut().zip(&cot).for_each(|(l, c)| *l += c);
            Ok(())
        };
        let mut segment = Segment::default();
        let mut done = self.grid.steps;
        for c in (0..checkpoints.len()).rev() {
            checkpoints.recompute(c, self.grid, &mut segment)?;
            for (i, jac) in segment.jacobians.iter().enumerate().rev() {
                add(segment.first + i + 1, &segment.states[i + 1], &mut lambda)?;
                pull_back(jac, m, &mut lambda, &mut g, &mut sums);
                done += 1;
                if watch(done).is_break() {
                    return Ok(ControlFlow::Break(done));
                }
            }
        }
        add(0, self.start, &mut lambda)?;
        lambda.extend_from_slice(&g);
        Ok(ControlFlow::Continue(lambda))
    }
}
