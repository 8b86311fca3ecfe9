//! The fixed-size duals against num-dual's vector types (the reference).

use nalgebra::SVector;
use num_dual::{Derivative, DualSVec64, HyperDualSVec64};

use super::*;

/// Exercises products, quotients, powers and the elementary functions the macros supply,
/// with every `xᵢ` meeting every `yⱼ`.
fn mixed<S: crate::scalar::Scalar>(x: &[S], y: &[S]) -> S {
    let mut acc = S::from(0.0);
    for &xi in x {
        for (j, &yj) in y.iter().enumerate() {
            let (s, c) = (xi - yj * (j as f64 + 1.0)).sin_cos();
            acc += s * c * yj / (xi * xi + 1.0).sqrt() + (xi * 0.3).exp() * yj.powi(3)
                - (yj * xi + 3.0).ln()
                + xi.tanh() / (yj - 5.0)
                + xi.atan2(yj);
        }
    }
    acc
}

const X: [f64; 4] = [0.7, -0.4, 0.25, -0.9];
const Y: [f64; 4] = [1.3, 0.9, 0.6, 1.45];

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-14 * (1.0 + b.abs())
}

/// `A` and `B` (the reference) give the same value and parts on `mixed`.
fn hyper_duals_agree<const N: usize, A: SmallDual<N>, B: SmallDual<N>>() {
    fn at<const N: usize, D: SmallDual<N>>() -> D {
        let x: [D; N] = std::array::from_fn(|i| D::seeded(X[i], Some((i, 1.0)), None));
        let y: [D; N] = std::array::from_fn(|j| D::seeded(Y[j], None, Some(j)));
        mixed(&x, &y)
    }
    let (ours, theirs) = (at::<N, A>(), at::<N, B>());
    assert!(close(ours.value(), theirs.value()));
    for i in 0..N {
        assert!(close(ours.eps1(i), theirs.eps1(i)), "N = {N}, ε₁ {i}");
        assert!(close(ours.eps2(i), theirs.eps2(i)), "N = {N}, ε₂ {i}");
        for j in 0..N {
            let (o, r) = (ours.eps12(i, j), theirs.eps12(i, j));
            assert!(close(o, r), "N = {N}, ε₁ε₂ ({i}, {j}): {o} vs {r}");
        }
    }
}

#[test]
fn hyper_duals_match_num_dual_vector_types() {
    hyper_duals_agree::<2, HyperDual2x64, HyperDualSVec64<2, 2>>();
    hyper_duals_agree::<3, HyperDual3x64, HyperDualSVec64<3, 3>>();
    hyper_duals_agree::<4, HyperDual4x64, HyperDualSVec64<4, 4>>();
}

/// `A` and `B` (the reference) give the same value and parts on `mixed(q₀, Δ)` seeded as
/// the kernel seeds them.
fn gradients_agree<const N: usize, A: SmallGradient<N>, B: SmallGradient<N>>() {
    fn at<const N: usize, G: SmallGradient<N>>() -> G {
        let q: [G; N] = std::array::from_fn(|i| G::position(X[i], i));
        let d: [G; N] = std::array::from_fn(|i| G::offset(Y[i], i));
        mixed(&q, &d)
    }
    let (a, b) = (at::<N, A>(), at::<N, B>());
    assert!(close(a.value(), b.value()));
    for k in 0..2 * N {
        assert!(close(a.part(k), b.part(k)), "N = {N}, part {k}");
    }
}

#[test]
fn gradient_duals_match_num_dual_vector_types() {
    gradients_agree::<1, Dual2x64, DualSVec64<2>>();
    gradients_agree::<2, Dual4x64, DualSVec64<4>>();
    gradients_agree::<3, Dual6x64, DualSVec64<6>>();
    gradients_agree::<4, Dual8x64, DualSVec64<8>>();
}

/// `f = x₀ x₁ y₀ y₁²` at (2, 3; 5, 7): the gradient and the mixed partials
/// `∂²f/∂xᵢ∂yⱼ = [[x₁y₁², 2x₁y₀y₁], [x₀y₁², 2x₀y₀y₁]]`, exact in floating point.
#[test]
fn hyper_dual_2_mixed_partials_of_a_monomial() {
    let x0 = HyperDual2x64::seeded(2.0, Some((0, 1.0)), None);
    let x1 = HyperDual2x64::seeded(3.0, Some((1, 1.0)), None);
    let y0 = HyperDual2x64::seeded(5.0, None, Some(0));
    let y1 = HyperDual2x64::seeded(7.0, None, Some(1));
    // Both orders: the product rule's ε₁ε₂ part has a term for each side's ε₁.
    for f in [x0 * x1 * y0 * y1 * y1, y1 * y1 * y0 * x1 * x0] {
        assert_eq!(f.re, 1470.0);
        assert_eq!(f.e1(), [735.0, 490.0]);
        assert_eq!(f.e2(), [294.0, 420.0]);
        assert_eq!(f.e12(), [[147.0, 210.0], [98.0, 140.0]]);
    }
}

#[test]
fn display_lists_every_part() {
    let x = HyperDual2x64::seeded(1.5, Some((1, 2.0)), Some(0));
    assert_eq!(
        x.to_string(),
        "1.5 + [0, 2]ε1 + [1, 0]ε2 + [0, 0, 0, 0]ε1ε2"
    );
    let g = Dual4x64::offset(0.5, 1);
    assert_eq!(g.to_string(), "0.5 + [0, -1, 0, 1]ε");
}

// The reference implementations: num-dual's vector duals in the kernels' traits.

macro_rules! small_gradient {
    ($n:literal, $m:literal) => {
        impl SmallGradient<$n> for DualSVec64<$m> {
            #[inline(always)]
            fn position(re: f64, i: usize) -> Self {
                DualSVec64::new(re, Derivative::some(SVector::<f64, $m>::ith(i, 1.0)))
            }
            #[inline(always)]
            fn offset(re: f64, i: usize) -> Self {
                let mut eps = SVector::<f64, $m>::zeros();
                eps[i] = -1.0;
                eps[$n + i] = 1.0;
                DualSVec64::new(re, Derivative::some(eps))
            }
            #[inline(always)]
            fn value(&self) -> f64 {
                self.re
            }
            #[inline(always)]
            fn part(&self, k: usize) -> f64 {
                self.eps.0.as_ref().map_or(0.0, |m| m[k])
            }
        }
    };
}
small_gradient!(1, 2);
small_gradient!(2, 4);
small_gradient!(3, 6);
small_gradient!(4, 8);
