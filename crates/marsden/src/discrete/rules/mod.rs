//! Rules: how a Lagrangian `L` (and a force `f_L`) becomes a discrete Lagrangian `L_d` (and
//! discrete forces `f_d^±`) by quadrature of the action over one step.
//!
//! Concept of the notes (MW01): *variational integrators — use approximations to the exact discrete
//! Lagrangian* ([MW01] §2.2, §4). Conventions as in the [crate documentation](crate#conventions),
//! with `v = (q₁ − q₀)/h`:
//!
//! | rule | `L_d(q₀, q₁)` | forces `(f_d⁻, f_d⁺)` | order |
//! |---|---|---|---|
//! | [`Midpoint`] | `h L(t₀ + h/2, (q₀+q₁)/2, v)` | `(h/2) f` at the midpoint, both | 2 |
//! | [`Trapezoid`] | `(h/2)[L(t₀, q₀, v) + L(t₀+h, q₁, v)]` | `(h/2) f` at each end | 2 |
//! | [`GeneralizedMidpoint`] α | `h L(t₀ + αh, (1−α)q₀ + αq₁, v)` | `h(1−α) f`, `hα f` at `q_α` | 1 (2 if α = ½) |
//! | [`SymmetrizedMidpoint`] α | `½(L_d^α + L_d^{1−α})` | average of the two | 2 |
//! | [`Galerkin`] `P_s`, r nodes | `h Σ b_i L(q(c_i h), q̇(c_i h))`, interior points as stages | `h Σ b_i ℓ_j(c_i) f` on point j | `min(2s, 2r)` Gauss, `min(2s, 2r−2)` Lobatto |
//! | [`Composition`] of a rule | `Σ_i L_d(Q_{i−1}, Q_i, γ_i h)`, interior points as stages | each substep's forces | the scheme's (4, 6, 8) |
//!
//! Midpoint is the α = ½ member of the generalised family and trapezoid the symmetrised α = 0
//! member; they share one implementation each ([`AlphaLd`], [`SymmetrizedLd`]).
//!
//! [MW01]: crate#references

mod alpha;
pub mod chosen;
pub mod composition;
pub mod galerkin;
pub mod method;
pub mod quadrature;
mod symmetrized;

pub use alpha::{AlphaForce, AlphaLd, GeneralizedMidpoint, Midpoint};
pub use chosen::{BaseForce, BaseLd, ChosenForce, ChosenLd};
pub use composition::{ComposedForce, ComposedLd, Composition, CompositionScheme};
pub use galerkin::{Galerkin, GalerkinForce, GalerkinLd};
pub use method::{BaseMethod, METHOD_GRAMMAR, Method, WithRule};
pub use quadrature::{Quadrature, QuadratureFamily};
pub use symmetrized::{SymmetrizedForce, SymmetrizedLd, SymmetrizedMidpoint, Trapezoid};

use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::error::InputError;
use crate::mechanics::{Force, Lagrangian};

/// A quadrature rule turning continuous objects into discrete ones.
pub trait Rule {
    /// The discrete Lagrangian (action) of `L` under this rule.
    type Discrete<L: Lagrangian>: DiscreteAction;
    /// The discrete forces of `f_L` under this rule.
    type DiscreteForce<F: Force>: DiscreteForce;
    /// `L ↦ L_d`.
    fn discretize<L: Lagrangian>(&self, lagrangian: L) -> Self::Discrete<L>;
    /// `f_L ↦ f_d^±`, by the same quadrature as `L_d`.
    fn discretize_force<F: Force>(&self, force: F, dof: usize) -> Self::DiscreteForce<F>;
    /// A short name, e.g. `"midpoint"`.
    fn name(&self) -> String;
    /// The classical order of the resulting integrator.
    fn order(&self) -> u32;
}

/// `alpha` if it lies in `[0, 1]`.
pub(crate) fn check_alpha(alpha: f64) -> Result<f64, crate::error::Error> {
    if (0.0..=1.0).contains(&alpha) {
        Ok(alpha)
    } else {
        Err(crate::error::Error::Input(InputError::InvalidOption {
            name: "alpha",
            value: alpha,
            reason: "must lie in [0, 1]",
        }))
    }
}

/// Calls `f(q_c, v)` at the node `q_c = q₀ + cΔ` with `v = Δ/h`, from the displacement
/// `Δ = q₁ − q₀` (no difference of rounded positions, see
/// [`crate::discrete::DiscreteLagrangian::discrete_lagrangian_offset`]).
#[inline(always)]
pub(crate) fn at_node<S: crate::scalar::Scalar, R>(
    c: f64,
    h: f64,
    q0: &[S],
    delta: &[S],
    f: impl FnOnce(&[S], &[S]) -> R,
) -> R {
    use crate::numerics::scratch::{Buffer, NODE};
    let (n, zero, inv_h) = (q0.len(), S::from(0.0), 1.0 / h);
    let position = |i: usize| match c {
        0.0 => q0[i],
        1.0 => q0[i] + delta[i],
        _ => q0[i] + delta[i] * c,
    };
    let mut q = Buffer::<S, NODE>::empty();
    let q = q.from_fn(n, zero, position);
    let mut v = Buffer::<S, NODE>::empty();
    let v = v.from_fn(n, zero, |i| delta[i] * inv_h);
    f(q, v)
}

/// Calls `f(q₁ − q₀)`.
#[inline(always)]
pub(crate) fn with_displacement<S: crate::scalar::Scalar, R>(
    q0: &[S],
    q1: &[S],
    f: impl FnOnce(&[S]) -> R,
) -> R {
    use crate::numerics::scratch::{Buffer, NODE};
    let mut d = Buffer::<S, NODE>::empty();
    let d = d.from_fn(q0.len(), S::from(0.0), |i| q1[i] - q0[i]);
    f(d)
}
