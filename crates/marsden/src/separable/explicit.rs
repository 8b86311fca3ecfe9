//! The explicit fast path: the trapezoid rule on a separable Lagrangian is velocity
//! Störmer–Verlet.
//!
//! For `L = ½ vᵀ M v − V(t, q)` with constant `M`, the trapezoid discrete Lagrangian
//! `L_d = (h/2)[L(t₀, q₀, v) + L(t₁, q₁, v)]`, `v = (q₁ − q₀)/h`, gives ([MW01] §2.2.1; HLW06
//! §VI.6; [conventions](crate#conventions))
//!
//! ```text
//!     p_k     = −D₁L_d = M v − (h/2) ∂L/∂q(t₀, q_k)     ⇒   p½ = p_k + (h/2) ∂L/∂q(t₀, q_k),
//!                                                             q_{k+1} = q_k + h M⁻¹ p½,
//!     p_{k+1} =  D₂L_d = M v + (h/2) ∂L/∂q(t₁, q_{k+1}) ⇒   p_{k+1} = p½ + (h/2) ∂L/∂q(t₁, q_{k+1}),
//! ```
//!
//! since `∂L/∂q = −∇V` does not depend on `v`. No Newton iteration, and one gradient
//! ([`crate::mechanics::Lagrangian::potential_gradient`], AD unless written by hand) per step: the gradient
//! at `(t₁, q_{k+1})` that ends step k is kept in the [`ExplicitWorkspace`] and starts step k+1
//! ("first same as last"), as long as the next step starts from the same positions (bit for bit)
//! and the same time (to a few ulps: the run rewrites `t_k = t₀ + k h`, which may differ from
//! the accumulated `t + h` in the last bit). The integrator takes this path automatically for
//! the trapezoid rule when the Lagrangian declares [`crate::mechanics::Structure::Separable`] and there are
//! no forces or constraints; a test checks it against the general Newton path to round-off.
//!
//! A run of many steps ([`ExplicitStep::explicit_run`], behind
//! [`crate::integrator::Integrator::advance`]) takes the same steps in one loop: the gradient is simply
//! carried from one step to the next, the times are `t₀ + k h`, and for diagonal masses and
//! `n ≤ 4` the state lives in fixed-size arrays, so the loop is the bare kick–drift–kick of
//! `verlet.c`. It gives the same numbers, bit for bit, as repeated single steps (test
//! `explicit_run.rs`). A Lagrangian that brings its own run
//! ([`crate::mechanics::Lagrangian::verlet_kernel`], e.g. compiled from an expression) takes
//! the run's steps in it when the mass is diagonal and `n ≤ 4` (the fixed-size loop it
//! replaces), with the same numbers again; larger systems keep the generic loop.
//!
//! [MW01]: crate#references

use crate::mechanics::Lagrangian;
use crate::mechanics::kernel::{RunGrid, VerletKernel};
use crate::mechanics::structure::InverseMass;

/// A step that needs no nonlinear solve (object-safe: plain `f64` state).
pub trait ExplicitStep {
    /// One step from `(q, p)` at `t`: writes the offset `Δ = q_{k+1} − q_k` into `delta` and
    /// replaces `p` by `p_{k+1}`; `ws` holds buffers and the cached gradient. Returns the number
    /// of potential gradients evaluated (1 in a run, 2 on a fresh start).
    fn explicit_step(
        &self,
        t: f64,
        h: f64,
        q: &[f64],
        p: &mut [f64],
        delta: &mut [f64],
        ws: &mut ExplicitWorkspace,
    ) -> usize;

    /// `grid.steps` steps from `(q, p)` at the grid times `t_k = t₀ + k h`, in place. Stops before
    /// the first step whose new state is not finite, leaving `(q, p)` at the last finite state.
    ///
    /// Default: repeated [`ExplicitStep::explicit_step`].
    fn explicit_run(
        &self,
        grid: RunGrid,
        q: &mut [f64],
        p: &mut [f64],
        ws: &mut ExplicitWorkspace,
    ) -> ExplicitRun {
        run_by_steps(self, grid, q, p, ws)
    }
}

/// [`ExplicitStep::explicit_run`] by repeated [`ExplicitStep::explicit_step`].
pub(crate) fn run_by_steps<E: ExplicitStep + ?Sized>(
    step: &E,
    grid: RunGrid,
    q: &mut [f64],
    p: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> ExplicitRun {
    let RunGrid { t0, h, steps } = grid;
    let mut buffers = std::mem::take(&mut ws.run);
    buffers.resize(2 * q.len(), 0.0);
    let (delta, p_next) = buffers.split_at_mut(q.len());
    let mut run = ExplicitRun::default();
    for k in 0..steps {
        p_next.copy_from_slice(p);
        let t = t0 + k as f64 * h;
        run.gradients += step.explicit_step(t, h, q, p_next, delta, ws);
        if !all_finite(delta, p_next) {
            ws.cache_valid = false;
            break;
        }
        q.iter_mut().zip(delta.iter()).for_each(|(x, d)| *x += d);
        p.copy_from_slice(p_next);
        run.steps += 1;
    }
    ws.run = buffers;
    run
}

/// What a run of explicit steps did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExplicitRun {
    /// Steps completed (fewer than asked when a step went non-finite).
    pub steps: usize,
    /// Potential gradients evaluated.
    pub gradients: usize,
}

/// Whether every entry of `a` and `b` is finite.
#[inline]
fn all_finite(a: &[f64], b: &[f64]) -> bool {
    a.iter().chain(b).all(|x| x.is_finite())
}

/// The gradient `∇V(t, q)` an explicit step leaves for the next one (its first half-kick).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct ExplicitCarry {
    grad: Vec<f64>,
    q: Vec<f64>,
    t: f64,
    valid: bool,
}

/// Buffers of the explicit step and the gradient that ended the last step.
#[derive(Debug, Clone, Default)]
pub struct ExplicitWorkspace {
    /// `∇V` at `(cache_t, cache_q)`.
    grad: Vec<f64>,
    cache_q: Vec<f64>,
    cache_t: f64,
    cache_valid: bool,
    q_next: Vec<f64>,
    /// Storage for [`Lagrangian::potential_gradient`].
    scratch: Vec<f64>,
    /// Storage for the dense mass solve.
    solve: Vec<f64>,
    /// Offsets and new momenta of [`ExplicitStep::explicit_run`]'s default loop.
    run: Vec<f64>,
    /// `h/mᵢ` for a [`VerletKernel`].
    drift: Vec<f64>,
}

impl ExplicitWorkspace {
    fn resize(&mut self, n: usize) {
        if self.grad.len() != n {
            self.grad.resize(n, 0.0);
            self.q_next.resize(n, 0.0);
            self.cache_q.resize(n, 0.0);
            self.drift.resize(n, 0.0);
            self.cache_valid = false;
        }
    }

    /// Marks the gradient held as the one at `(t, q)`.
    #[inline]
    fn remember(&mut self, t: f64, q: &[f64]) {
        self.cache_q.copy_from_slice(q);
        self.cache_t = t;
        self.cache_valid = true;
    }

    /// The gradient this workspace carries to the next step, as plain numbers (a checkpoint).
    pub(crate) fn carried(&self) -> ExplicitCarry {
        ExplicitCarry {
            grad: self.grad.clone(),
            q: self.cache_q.clone(),
            t: self.cache_t,
            valid: self.cache_valid,
        }
    }

    /// Takes back what [`ExplicitWorkspace::carried`] gave (buffers sized for its `n`).
    pub(crate) fn restore_carried(&mut self, carry: &ExplicitCarry) {
        let n = carry.grad.len();
        self.resize(n);
        if carry.q.len() == n {
            self.grad.copy_from_slice(&carry.grad);
            self.cache_q.copy_from_slice(&carry.q);
            self.cache_t = carry.t;
            self.cache_valid = carry.valid;
        }
    }

    /// Whether the cached gradient was taken at `(t, q)`.
    #[inline]
    fn holds(&self, t: f64, h: f64, q: &[f64]) -> bool {
        let close = (t - self.cache_t).abs() <= 16.0 * f64::EPSILON * t.abs().max(h.abs());
        self.cache_valid && close && self.cache_q.as_slice() == q
    }
}

/// The drift `Δ = h M⁻¹ p`, written into `delta` (`scratch` for the dense solve). For a
/// diagonal mass it is `Δᵢ = (h/mᵢ) pᵢ`, the product a run loop hoists out of its steps.
#[inline]
fn drift(inverse: &InverseMass, h: f64, p: &[f64], delta: &mut [f64], scratch: &mut Vec<f64>) {
    match inverse {
        InverseMass::Diagonal(d) => delta
            .iter_mut()
            .zip(p.iter().zip(d))
            .for_each(|(x, (pi, di))| *x = (h * di) * pi),
        InverseMass::Dense(lu) => {
            delta.copy_from_slice(p);
            lu.solve(delta, scratch);
            delta.iter_mut().for_each(|x| *x *= h);
        }
    }
}

/// `p ← p − (h/2) ∇V`.
#[inline]
fn half_kick(h: f64, grad: &[f64], p: &mut [f64]) {
    let c = 0.5 * h;
    p.iter_mut().zip(grad).for_each(|(pi, g)| *pi -= c * g);
}

/// A separable Lagrangian `L = ½ vᵀ M v − V(t, q)` with the inverse of its constant mass: what
/// the velocity Störmer–Verlet steps need.
#[derive(Debug)]
pub(crate) struct Verlet<'a, L> {
    /// `L`, for its potential gradient `∇V(t, q)`.
    pub lagrangian: &'a L,
    /// `M⁻¹`.
    pub inverse_mass: &'a InverseMass,
}

/// One velocity Störmer–Verlet step of a separable `L` (the trapezoid variational step) from
/// `(q, p)` at `t`: `Δ = h M⁻¹ p½` into `delta`, `p ← p_{k+1}`; returns the gradients evaluated.
pub(crate) fn velocity_verlet<L: Lagrangian>(
    verlet: Verlet<'_, L>,
    t: f64,
    h: f64,
    q: &[f64],
    p: &mut [f64],
    delta: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> usize {
    let Verlet {
        lagrangian: l,
        inverse_mass,
    } = verlet;
    ws.resize(q.len());
    let mut gradients = 1;
    if !ws.holds(t, h, q) {
        l.potential_gradient(t, q, &mut ws.grad, &mut ws.scratch);
        gradients += 1;
    }
    half_kick(h, &ws.grad, p);
    drift(inverse_mass, h, p, delta, &mut ws.solve);
    ws.q_next
        .iter_mut()
        .zip(q.iter().zip(delta.iter()))
        .for_each(|(x, (qi, d))| *x = qi + d);
    l.potential_gradient(t + h, &ws.q_next, &mut ws.grad, &mut ws.scratch);
    half_kick(h, &ws.grad, p);
    std::mem::swap(&mut ws.cache_q, &mut ws.q_next);
    ws.cache_t = t + h;
    ws.cache_valid = true;
    gradients
}

/// The largest `n` run on fixed-size arrays.
const MAX_FIXED: usize = 4;

/// `grid.steps` velocity Störmer–Verlet steps of a separable `L` in one loop
/// ([`ExplicitStep::explicit_run`]): fixed-size arrays for a diagonal mass and `n ≤ 4`, else
/// `None` (the caller then repeats [`velocity_verlet`]).
pub(crate) fn velocity_verlet_run<L: Lagrangian>(
    verlet: Verlet<'_, L>,
    grid: RunGrid,
    q: &mut [f64],
    p: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> Option<ExplicitRun> {
    let Verlet {
        lagrangian: l,
        inverse_mass,
    } = verlet;
    let InverseMass::Diagonal(inverse) = inverse_mass else {
        return None;
    };
    // The kernel reproduces the fixed-size loop below (times `t₀ + k·h`), not the step-by-step
    // loop of larger systems (times `t_{k−1} + h`, different in the last bit).
    let kernel = (inverse.len() <= MAX_FIXED)
        .then(|| l.verlet_kernel())
        .flatten();
    if let Some(kernel) = kernel.filter(|k| k.dof() == inverse.len()) {
        return kernel_run(l, kernel, inverse, grid, q, p, ws);
    }
    match inverse.len() {
        1 => verlet_run_fixed::<L, 1>(l, inverse, grid, q, p, ws),
        2 => verlet_run_fixed::<L, 2>(l, inverse, grid, q, p, ws),
        3 => verlet_run_fixed::<L, 3>(l, inverse, grid, q, p, ws),
        4 => verlet_run_fixed::<L, 4>(l, inverse, grid, q, p, ws),
        _ => None,
    }
}

/// The run in the Lagrangian's own kernel ([`crate::mechanics::kernel`]), with the gradient
/// cache kept as [`verlet_run_fixed`] keeps it.
fn kernel_run<L: Lagrangian>(
    l: &L,
    kernel: &dyn VerletKernel,
    inverse: &[f64],
    grid: RunGrid,
    q: &mut [f64],
    p: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> Option<ExplicitRun> {
    let RunGrid { t0, h, steps } = grid;
    let n = inverse.len();
    if q.len() != n || p.len() != n {
        return None;
    }
    ws.resize(n);
    let mut run = ExplicitRun::default();
    if !ws.holds(t0, h, q) {
        l.potential_gradient(t0, q, &mut ws.grad, &mut ws.scratch);
        run.gradients += 1;
    }
    ws.drift
        .iter_mut()
        .zip(inverse)
        .for_each(|(d, m)| *d = h * m);
    let done = kernel.run(grid, &ws.drift, q, p, &mut ws.grad);
    run.steps = done;
    run.gradients += done + usize::from(done < steps);
    ws.remember(t0 + done as f64 * h, q);
    Some(run)
}

/// The run loop on `N`-arrays: kick, drift, gradient, kick, exactly as [`velocity_verlet`]
/// computes them (so bit for bit the same numbers), with the gradient carried in registers.
#[inline]
fn verlet_run_fixed<L: Lagrangian, const N: usize>(
    l: &L,
    inverse: &[f64],
    grid: RunGrid,
    q: &mut [f64],
    p: &mut [f64],
    ws: &mut ExplicitWorkspace,
) -> Option<ExplicitRun> {
    let RunGrid { t0, h, steps } = grid;
    let (Ok(q_out), Ok(p_out)) = (<&mut [f64; N]>::try_from(q), <&mut [f64; N]>::try_from(p))
    else {
        return None;
    };
    let (mut x, mut y) = (*q_out, *p_out);
    let hm: [f64; N] = std::array::from_fn(|i| h * inverse[i]);
    let c = 0.5 * h;
    ws.resize(N);
    let mut run = ExplicitRun::default();
    let mut g = [0.0; N];
    if ws.holds(t0, h, &x) {
        g.copy_from_slice(&ws.grad);
    } else {
        l.potential_gradient(t0, &x, &mut g, &mut ws.scratch);
        run.gradients += 1;
    }
    for k in 1..=steps {
        let p_half: [f64; N] = std::array::from_fn(|i| y[i] - c * g[i]);
        let q_next: [f64; N] = std::array::from_fn(|i| x[i] + hm[i] * p_half[i]);
        let mut g_next = [0.0; N];
        l.potential_gradient(t0 + k as f64 * h, &q_next, &mut g_next, &mut ws.scratch);
        run.gradients += 1;
        let p_next: [f64; N] = std::array::from_fn(|i| p_half[i] - c * g_next[i]);
        if !all_finite(&q_next, &p_next) {
            break;
        }
        (x, y, g) = (q_next, p_next, g_next);
        run.steps = k;
    }
    (*q_out, *p_out) = (x, y);
    ws.grad.copy_from_slice(&g);
    ws.remember(t0 + run.steps as f64 * h, &x);
    Some(run)
}
