//! Dual numbers of fixed size with every part stored, for the step kernels of 2 to 4 degrees
//! of freedom (and the first-order one of 1).
//!
//! num-dual's vector duals (`HyperDualSVec64<N, N>`, `DualSVec64<2N>`) keep each derivative part
//! as an `Option` of a matrix, so that a constant costs nothing. In the small step kernels
//! (`crate::integrator::small::unconstrained`, `crate::integrator::small::constrained`) every part is always present, and the
//! branches on the options and the products that are not inlined are a large part of an
//! evaluation (BENCHMARKS.md has the counts). The types here are num-dual's
//! scalar [`num_dual::HyperDual`] and [`num_dual::Dual`] with the parts written out as fields
//! (`hyper_dual!` and `gradient_dual!` below, for N = 2, 3, 4; `Dual2` for N = 1): the sums, the elementary
//! functions and the trait impls come from num-dual's own exported macros; only the product,
//! the quotient and the chain rule are spelled out (Fike & Alonso 2011, *The development of
//! hyper-dual numbers for exact second-derivative calculations*, AIAA 2011-886):
//!
//! ```text
//! (a·b).ε₁ᵢ     = a.ε₁ᵢ b.re + a.re b.ε₁ᵢ                         (ε₂ⱼ alike)
//! (a·b).ε₁ᵢε₂ⱼ  = a.ε₁ᵢε₂ⱼ b.re + a.re b.ε₁ᵢε₂ⱼ + a.ε₁ᵢ b.ε₂ⱼ + b.ε₁ᵢ a.ε₂ⱼ
//! f(a).ε₁ᵢ      = f′(a.re) a.ε₁ᵢ
//! f(a).ε₁ᵢε₂ⱼ   = f′(a.re) a.ε₁ᵢε₂ⱼ + f″(a.re) a.ε₁ᵢ a.ε₂ⱼ
//! a / b         = a · (1/b)
//! ```
//!
//! Tests compare every type with num-dual's vector type of the same size on a function that
//! uses every kind of operation, and `HyperDual2` with closed-form partials of a monomial;
//! `tests/static_kernel_equivalence.rs` runs the kernels against the general path for n = 2…4.

// The product rule adds and the quotient multiplies by a reciprocal: not a slip of an operator.

use nalgebra::{Const, U1};
use num_dual::{Derivative, HyperDual64, HyperDualSVec64};

use crate::scalar::Scalar;

pub mod compose;
mod fixed;
#[cfg(test)]
mod tests;

pub(crate) use fixed::{
    Dual2x64, Dual4x64, Dual6x64, Dual8x64, HyperDual2x64, HyperDual3x64, HyperDual4x64,
};

/// A hyper-dual number with `N`-dimensional eps₁ and eps₂ parts.
pub(crate) trait SmallDual<const N: usize>: Scalar {
    /// `re` with eps₁ = `e1 · e_i1` and eps₂ = `e_i2` (either optional).
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self;
    /// Real part.
    fn value(&self) -> f64;
    /// eps₁ component `i`.
    fn eps1(&self, i: usize) -> f64;
    /// eps₂ component `j`.
    fn eps2(&self, j: usize) -> f64;
    /// eps₁eps₂ component `(i, j)`.
    fn eps12(&self, i: usize, j: usize) -> f64;
}

impl SmallDual<1> for HyperDual64 {
    #[inline(always)]
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
        HyperDual64::new(
            re,
            eps1.map_or(0.0, |e| e.1),
            eps2.map_or(0.0, |_| 1.0),
            0.0,
        )
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn eps1(&self, _i: usize) -> f64 {
        self.eps1
    }
    #[inline(always)]
    fn eps2(&self, _j: usize) -> f64 {
        self.eps2
    }
    #[inline(always)]
    fn eps12(&self, _i: usize, _j: usize) -> f64 {
        self.eps1eps2
    }
}

/// num-dual's vector hyper-duals (the RATTLE projection's velocity jet for `n = 2 … 4`).
impl<const N: usize> SmallDual<N> for HyperDualSVec64<N, N> {
    #[inline(always)]
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
        let mut x = HyperDualSVec64::<N, N>::from_re(re);
        if let Some((i, c)) = eps1 {
            let mut d = Derivative::derivative_generic(Const::<N>, U1, i);
            if let Some(m) = d.0.as_mut() {
                m[i] = c;
            }
            x.eps1 = d;
        }
        if let Some(j) = eps2 {
            x.eps2 = Derivative::derivative_generic(U1, Const::<N>, j);
        }
        x
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn eps1(&self, i: usize) -> f64 {
        self.eps1.0.as_ref().map_or(0.0, |m| m[i])
    }
    #[inline(always)]
    fn eps2(&self, j: usize) -> f64 {
        self.eps2.0.as_ref().map_or(0.0, |m| m[j])
    }
    #[inline(always)]
    fn eps12(&self, i: usize, j: usize) -> f64 {
        self.eps1eps2.0.as_ref().map_or(0.0, |m| m[(i, j)])
    }
}

/// A dual number with `2N` parts: `∂/∂Q₀` in parts `0 … N−1` and `∂/∂Q₁` in parts `N … 2N−1`
/// (the residual and `p_{k+1}` of the step, without its Jacobian).
pub(crate) trait SmallGradient<const N: usize>: Scalar {
    /// `q₀ᵢ`: part `i` is 1 (`Q₀` moves, `Q₁` stays).
    fn position(re: f64, i: usize) -> Self;
    /// `Δᵢ = Q₁ᵢ − Q₀ᵢ`: part `i` is −1 and part `N + i` is 1.
    fn offset(re: f64, i: usize) -> Self;
    /// Real part.
    fn value(&self) -> f64;
    /// Part `k`.
    fn part(&self, k: usize) -> f64;
}
