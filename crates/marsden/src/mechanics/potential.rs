//! The potential of a separable Lagrangian, `L = ½ vᵀ M v − V(t, q)`: its gradient `∇V` and
//! Hessian `∇²V`, by automatic differentiation unless the system writes them by hand.
//!
//! The structure-aware steps need only these two derivatives ([`crate::separable::explicit`]: the
//! trapezoid rule is velocity Störmer–Verlet, one `∇V` per step; [`crate::separable::alpha`]: the
//! midpoint rule is a Newton solve with Jacobian `M/h + (h/4)∇²V`, [MW01] §2.2.1, [HLW06]
//! §VI.3). They are provided methods of [`crate::mechanics::Lagrangian`]:
//!
//! | method | default | override when |
//! |---|---|---|
//! | [`crate::mechanics::Lagrangian::potential_gradient`] | [`gradient_by_ad`]: AD of `−L(t, q, 0)` | AD is too slow (N-body: `O(n)` AD chunks of an `O(n²)` function) |
//! | [`crate::mechanics::Lagrangian::potential_bandwidth`] | `None` (dense) | `V` is a sum of local terms (a chain: `Some(1)`) |
//! | [`crate::mechanics::Lagrangian::potential_hessian`] | [`hessian_by_ad`]: dense AD Hessian | with a bandwidth, or a cheap closed form |
//!
//! A hand-written gradient must agree with the AD default (tests do this for every catalog
//! system that overrides it). Both defaults differentiate `−L(t, q, 0)`, which is `V(t, q)`
//! up to a constant exactly when the declared structure holds.
//!
//! [MW01]: crate#references
//! [HLW06]: crate#references

use super::lagrangian::{Lagrangian, gradient_by_ad, hessian_by_ad};
use crate::numerics::banded::Banded;

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
        .fold(0.0, crate::numerics::dense::max_or_nan)
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
