//! A separable Lagrangian's own explicit run: velocity Störmer–Verlet steps taken by code the
//! Lagrangian brings (compiled at run time from a user's expression, for instance) instead of
//! the integrator's generic loop.
//!
//! The generic loop ([`crate::separable::explicit`]) calls
//! [`crate::mechanics::Lagrangian::potential_gradient`] once per step through a function call
//! that it cannot inline when the gradient is not Rust code; a kernel that has the gradient
//! inside its own loop keeps the state in registers across the whole run. It must compute the
//! same numbers as the generic loop, bit for bit: for a diagonal mass `M`, with `c = 0.5·h`,
//! `dᵢ = h·(1/mᵢ)` and `t_k = t₀ + k·h` (each product rounded, no fused multiply–add),
//!
//! ```text
//!     p½ = p_k − c ∇V(t_{k−1}, q_k),    q_{k+1} = q_k + d ⊙ p½,    p_{k+1} = p½ − c ∇V(t_k, q_{k+1}),
//! ```
//!
//! the trapezoid rule's discrete Euler–Lagrange equations for `L = ½ vᵀ M v − V(t, q)` ([MW01]
//! §2.2.1; [conventions](crate#conventions)), stopping before the first step whose
//! `(q_{k+1}, p_{k+1})` is not finite. Tests compare a kernel's runs with the generic loop's bit
//! for bit. The integrator calls a kernel for up to four degrees of freedom, the sizes whose
//! generic loop takes exactly these times (larger systems repeat single steps, at times
//! `t_{k−1} + h`).
//!
//! [MW01]: crate#references

/// The uniform time grid of a run of explicit steps: `steps` steps of size `h` from `t0`, at
/// the times `t_k = t₀ + k·h`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunGrid {
    /// The initial time `t₀`.
    pub t0: f64,
    /// The time step `h`.
    pub h: f64,
    /// The number of steps asked for.
    pub steps: usize,
}

/// Velocity Störmer–Verlet steps of a separable `L` with a diagonal mass, run by the
/// Lagrangian's own code ([`crate::mechanics::Lagrangian::verlet_kernel`]).
pub trait VerletKernel {
    /// Up to `grid.steps` steps from `(q, p)` at `t₀` on the grid `(t₀, h)`, in place (the
    /// equations of [`self`](crate::mechanics::kernel)); `drift[i] = h·(1/mᵢ)`; `grad` holds
    /// `∇V(t₀, q)` on entry and `∇V` at the state left in `(q, p)` on exit. Stops before the
    /// first step whose new state is not finite. Returns the steps completed.
    ///
    /// The slices all have the kernel's length `n`; the integrator checks
    /// [`VerletKernel::dof`] before calling.
    fn run(
        &self,
        grid: RunGrid,
        drift: &[f64],
        q: &mut [f64],
        p: &mut [f64],
        grad: &mut [f64],
    ) -> usize;

    /// The degrees of freedom `n` the kernel was built for.
    fn dof(&self) -> usize;
}
