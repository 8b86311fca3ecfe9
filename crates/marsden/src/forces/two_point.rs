//! User-written discrete forces `f_d^±(q₀, q₁)` as a first-class input.
//!
//! Concept of the notes (MW01): *discrete variational mechanics with forces*. The discrete Lagrange–d'Alembert
//! principle only needs the two discrete forces `f_d⁻(q₀, q₁) ∈ T*_{q₀}Q` and
//! `f_d⁺(q₀, q₁) ∈ T*_{q₁}Q` ([MW01] §3.2); they need not come from a quadrature of a continuous
//! force. Implement [`TwoPointForce`] and wrap it in [`TwoPoint`] to hand it to an
//! [`crate::integrator::Integrator`] (`Integrator::new(ld).with_force(TwoPoint(my_forces))`). With rules
//! that have internal control points (Galerkin), `f_d⁻` acts on `Q₀ = q_k`, `f_d⁺` on
//! `Q_s = q_{k+1}` and nothing on the internal points.
//!
//! [MW01]: crate#references

use crate::discrete::DiscreteForce;
use crate::numerics::scratch::{Buffer, NODE};
use crate::scalar::Scalar;

/// Discrete forces `(f_d⁻, f_d⁺)` of one step `(q₀, q₁)` from `t₀` to `t₀ + h`.
///
/// ```
/// use marsden::{DiscreteForce, Scalar, forces::{TwoPoint, TwoPointForce}};
///
/// /// Midpoint damping of R12, written by hand: f_d^± = −(c/2)(q₁ − q₀).
/// struct Damping(f64);
/// impl TwoPointForce for Damping {
///     fn two_point_force<S: Scalar>(
///         &self, _t0: f64, _h: f64, q0: &[S], q1: &[S], minus: &mut [S], plus: &mut [S],
///     ) {
///         minus[0] = (q1[0] - q0[0]) * (-0.5 * self.0);
///         plus[0] = minus[0];
///     }
/// }
/// let mut out = [0.0; 2];
/// TwoPoint(Damping(0.1)).discrete_force(0.0, 0.1, &[1.0], &[0.5], &mut out);
/// assert_eq!(out, [-0.025, -0.025]);
/// ```
pub trait TwoPointForce {
    /// Writes `f_d⁻(q₀, q₁)` into `minus` and `f_d⁺(q₀, q₁)` into `plus` (length n each).
    fn two_point_force<S: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[S],
        q1: &[S],
        minus: &mut [S],
        plus: &mut [S],
    );

    /// The same from the displacement `Δ = q₁ − q₀` given exactly (the integrator steps
    /// displacements; see [`crate::discrete::DiscreteLagrangian::discrete_lagrangian_offset`] for why).
    /// The default forms `q₁ = q₀ + Δ`; override it when the forces depend on `q₁ − q₀`.
    fn two_point_force_offset<S: Scalar>(
        &self,
        t0: f64,
        h: f64,
        q0: &[S],
        delta: &[S],
        minus: &mut [S],
        plus: &mut [S],
    ) {
        let zero = S::from(0.0);
        let mut q1 = Buffer::<S, NODE>::empty();
        let q1 = q1.from_fn(q0.len(), zero, |i| q0[i] + delta[i]);
        self.two_point_force(t0, h, q0, q1, minus, plus);
    }
}

/// A [`TwoPointForce`] as the [`DiscreteForce`] of a step (`f_d⁻` on `Q₀`, `f_d⁺` on `Q_s`, zero
/// on internal control points).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TwoPoint<T>(pub T);

impl<T: TwoPointForce> DiscreteForce for TwoPoint<T> {
    #[inline]
    fn discrete_force<S: Scalar>(&self, t0: f64, h: f64, q0: &[S], offsets: &[S], out: &mut [S]) {
        let n = q0.len();
        let last = offsets.len().saturating_sub(n);
        out.iter_mut().for_each(|o| *o = S::from(0.0));
        let (minus, rest) = out.split_at_mut(n.min(out.len()));
        let plus_start = rest.len().saturating_sub(n);
        let plus = &mut rest[plus_start..];
        self.0
            .two_point_force_offset(t0, h, q0, &offsets[last..], minus, plus);
    }
}
