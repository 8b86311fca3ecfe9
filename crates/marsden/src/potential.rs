//! The potential of a separable Lagrangian, `L = ½ vᵀ M v − V(t, q)`: its gradient `∇V` and
//! Hessian `∇²V`, by automatic differentiation unless the system writes them by hand.
//!
//! The structure-aware steps need only these two derivatives ([`crate::explicit`]: the
//! trapezoid rule is velocity Störmer–Verlet, one `∇V` per step; [`crate::separable`]: the
//! midpoint rule is a Newton solve with Jacobian `M/h + (h/4)∇²V`, [MW01] §2.2.1, [HLW06]
//! §VI.3). They are provided methods of [`crate::Lagrangian`]:
//!
//! | method | default | override when |
//! |---|---|---|
//! | [`crate::Lagrangian::potential_gradient`] | [`gradient_by_ad`]: AD of `−L(t, q, 0)` | AD is too slow (N-body: `O(n)` AD chunks of an `O(n²)` function) |
//! | [`crate::Lagrangian::potential_bandwidth`] | `None` (dense) | `V` is a sum of local terms (a chain: `Some(1)`) |
//! | [`crate::Lagrangian::potential_hessian`] | [`hessian_by_ad`]: dense AD Hessian | with a bandwidth, or a cheap closed form |
//!
//! A hand-written gradient must agree with the AD default (tests do this for every catalog
//! system that overrides it). Both defaults differentiate `−L(t, q, 0)`, which is `V(t, q)`
//! up to a constant exactly when the declared structure holds.
//!
//! [MW01]: Marsden & West, Acta Numerica 10 (2001). [HLW06]: Hairer, Lubich, Wanner, *Geometric
//! Numerical Integration* (2006).

use crate::ad::{self, HessianParts, MultiFunction};
use crate::banded::Banded;
use crate::scratch::{NODE, with_buffer};
use crate::{Lagrangian, Scalar};

/// `q ↦ −L(t, q, 0)`: the potential `V(t, q)` of a separable Lagrangian.
pub(crate) struct PotentialOf<'a, L: ?Sized> {
    /// The Lagrangian.
    pub lagrangian: &'a L,
    /// Time.
    pub t: f64,
}

impl<L: Lagrangian + ?Sized> MultiFunction for PotentialOf<'_, L> {
    fn inputs(&self) -> usize {
        self.lagrangian.dof()
    }
    fn outputs(&self) -> usize {
        1
    }
    #[inline]
    fn eval<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        with_buffer::<S, NODE, ()>(
            q.len(),
            zero,
            |_| zero,
            |v| out[0] = -self.lagrangian.lagrangian(S::from(self.t), q, v),
        );
    }
}

/// `∇V(t, q)` by AD of `−L(t, q, 0)` (the default of
/// [`crate::Lagrangian::potential_gradient`]); `grad` has length n.
pub fn gradient_by_ad<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64], grad: &mut [f64]) {
    let mut value = [0.0];
    ad::jacobian(
        &PotentialOf { lagrangian: l, t },
        q,
        0..q.len(),
        &mut value,
        grad,
    );
}

/// `V(t, q) = −L(t, q, 0)` at `f64` (a constant offset of `V` is irrelevant to the dynamics).
pub fn potential<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64]) -> f64 {
    let mut value = [0.0];
    ad::eval_f64(&PotentialOf { lagrangian: l, t }, q, &mut value);
    value[0]
}

/// `∇²V(t, q)` by AD of `−L(t, q, 0)`, dense, written into the band of `hess` (the default of
/// [`crate::Lagrangian::potential_hessian`]; entries outside the band are dropped, so give
/// `hess` the full bandwidth `n − 1` unless the potential is known to be banded).
pub fn hessian_by_ad<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64], hess: &mut Banded) {
    let n = q.len();
    let mut parts = HessianParts::default();
    ad::partial_hessian(&PotentialOf { lagrangian: l, t }, q, 0..n, 0..n, &mut parts);
    hess.fill_zero();
    for i in 0..n {
        for j in hess.columns(i) {
            hess.set(i, j, parts.hess[i * n + j]);
        }
    }
}

/// Largest difference between a hand-written gradient and the AD default at `(t, q)`,
/// relative to the size of the gradient: what tests assert to be at round-off.
pub fn gradient_defect<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64]) -> f64 {
    let n = q.len();
    let (mut hand, mut by_ad) = (vec![0.0; n], vec![0.0; n]);
    l.potential_gradient(t, q, &mut hand, &mut Vec::new());
    gradient_by_ad(l, t, q, &mut by_ad);
    let scale = by_ad.iter().fold(f64::MIN_POSITIVE, |m, g| m.max(g.abs()));
    hand.iter()
        .zip(&by_ad)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max)
        / scale
}

/// Largest difference between a hand-written Hessian and the dense AD Hessian at `(t, q)`,
/// relative to the size of the Hessian (entries outside the declared band count in full).
pub fn hessian_defect<L: Lagrangian + ?Sized>(l: &L, t: f64, q: &[f64]) -> f64 {
    let n = q.len();
    let b = l.potential_bandwidth().unwrap_or(n.saturating_sub(1));
    let mut hand = Banded::new(n, b);
    l.potential_hessian(t, q, &mut hand);
    let mut full = Banded::new(n, n.saturating_sub(1));
    hessian_by_ad(l, t, q, &mut full);
    let mut scale = f64::MIN_POSITIVE;
    let mut defect = 0.0_f64;
    for i in 0..n {
        for j in 0..n {
            let exact = full.get(i, j);
            scale = scale.max(exact.abs());
            defect = defect.max((hand.get(i, j) - exact).abs());
        }
    }
    defect / scale
}
