//! Dual numbers of fixed size with every part stored, for the two-degree-of-freedom step kernel.
//!
//! num-dual's vector duals (`HyperDualSVec64<2, 2>`, `DualSVec64<4>`) keep each derivative part
//! as an `Option` of a matrix, so that a constant costs nothing. In the small step kernel
//! ([`crate::small`]) every part is always present, and the branches on the options and the
//! products that are not inlined are a third of an evaluation of the double pendulum's `L_d`
//! (1 710 instructions per hyper-dual evaluation with `HyperDualSVec64<2, 2>`, 1 110 with
//! `HyperDual2`, callgrind). The two types here are num-dual's scalar [`num_dual::HyperDual`]
//! and [`num_dual::Dual`] with the parts written out as fields: the sums, the elementary
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
//! Tests compare both with num-dual's vector types on a function that uses every kind of
//! operation, and the hyper-dual one with closed-form partials of a monomial.

// The product rule adds and the quotient multiplies by a reciprocal: not a slip of an operator.
#![allow(clippy::suspicious_arithmetic_impl)]

use crate::small::{SmallDual, SmallGradient};
use num_dual::{DualNum, DualNumFloat, DualStruct};
use num_dual::{
    chain_rule, first, forward_binop, impl_add_sub_rem, impl_assign_ops, impl_comparisons,
    impl_derivatives, impl_dual, impl_dual_struct, impl_first_derivatives, impl_float_const,
    impl_from_f, impl_from_primitive, impl_inv, impl_iterator, impl_neg, impl_num, impl_scalar_op,
    impl_second_derivatives, impl_signed, impl_zero_one, second, third, zeroth,
};
use num_traits::{FloatConst, FromPrimitive, Inv, Num, One, Signed, Zero};
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

/// A hyper-dual number with two-dimensional ε₁ and ε₂ parts: value, `∂/∂xᵢ` (ε₁),
/// `∂/∂yⱼ` (ε₂) and `∂²/∂xᵢ∂yⱼ` (ε₁ε₂), the layout of `HyperDualSVec64<2, 2>`.
#[derive(Copy, Clone, Debug)]
pub(crate) struct HyperDual2<T> {
    /// Value.
    pub re: T,
    /// ε₁ part 0.
    pub e1_0: T,
    /// ε₁ part 1.
    pub e1_1: T,
    /// ε₂ part 0.
    pub e2_0: T,
    /// ε₂ part 1.
    pub e2_1: T,
    /// ε₁ε₂ part (0, 0).
    pub e12_00: T,
    /// ε₁ε₂ part (0, 1).
    pub e12_01: T,
    /// ε₁ε₂ part (1, 0).
    pub e12_10: T,
    /// ε₁ε₂ part (1, 1).
    pub e12_11: T,
}

/// `HyperDual2` with `f64` parts.
pub(crate) type HyperDual2x64 = HyperDual2<f64>;

impl<T: DualNum> HyperDual2<T> {
    /// The number with the given value and parts `ε₁ = e1`, `ε₂ = e2`, `ε₁ε₂ = e12`.
    #[inline]
    pub fn from_parts(re: T, e1: [T; 2], e2: [T; 2], e12: [[T; 2]; 2]) -> Self {
        let [e1_0, e1_1] = e1;
        let [e2_0, e2_1] = e2;
        let [[e12_00, e12_01], [e12_10, e12_11]] = e12;
        Self {
            re,
            e1_0,
            e1_1,
            e2_0,
            e2_1,
            e12_00,
            e12_01,
            e12_10,
            e12_11,
        }
    }

    /// The number from its fields in declaration order (the form num-dual's macros call).
    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn new(re: T, e1_0: T, e1_1: T, e2_0: T, e2_1: T, e00: T, e01: T, e10: T, e11: T) -> Self {
        Self::from_parts(re, [e1_0, e1_1], [e2_0, e2_1], [[e00, e01], [e10, e11]])
    }

    /// A constant (every part zero).
    #[inline]
    pub fn from_re(re: T) -> Self {
        let z = T::zero();
        Self::from_parts(
            re,
            [z.clone(), z.clone()],
            [z.clone(), z.clone()],
            [[z.clone(), z.clone()], [z.clone(), z]],
        )
    }

    /// The ε₁ parts.
    #[inline]
    pub fn e1(&self) -> [T; 2] {
        [self.e1_0.clone(), self.e1_1.clone()]
    }

    /// The ε₂ parts.
    #[inline]
    pub fn e2(&self) -> [T; 2] {
        [self.e2_0.clone(), self.e2_1.clone()]
    }

    /// The ε₁ε₂ parts.
    #[inline]
    pub fn e12(&self) -> [[T; 2]; 2] {
        [
            [self.e12_00.clone(), self.e12_01.clone()],
            [self.e12_10.clone(), self.e12_11.clone()],
        ]
    }

    /// `f(self)` from `f(re)`, `f′(re)`, `f″(re)`.
    #[inline]
    fn chain_rule(&self, f0: T, f1: T, f2: T) -> Self {
        let (a1, a2, a12) = (self.e1(), self.e2(), self.e12());
        Self::from_parts(
            f0,
            a1.clone().map(|x| x * f1.clone()),
            a2.clone().map(|y| y * f1.clone()),
            std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    a12[i][j].clone() * f1.clone() + a1[i].clone() * a2[j].clone() * f2.clone()
                })
            }),
        )
    }
}

/* product rule */
impl<T: DualNum> Mul<&HyperDual2<T>> for &HyperDual2<T> {
    type Output = HyperDual2<T>;
    #[inline]
    fn mul(self, other: &HyperDual2<T>) -> HyperDual2<T> {
        let (a, b) = (&self.re, &other.re);
        let (a1, a2, a12) = (self.e1(), self.e2(), self.e12());
        let (b1, b2, b12) = (other.e1(), other.e2(), other.e12());
        HyperDual2::from_parts(
            a.clone() * b.clone(),
            std::array::from_fn(|i| b1[i].clone() * a.clone() + a1[i].clone() * b.clone()),
            std::array::from_fn(|j| b2[j].clone() * a.clone() + a2[j].clone() * b.clone()),
            std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    b12[i][j].clone() * a.clone()
                        + a1[i].clone() * b2[j].clone()
                        + b1[i].clone() * a2[j].clone()
                        + a12[i][j].clone() * b.clone()
                })
            }),
        )
    }
}

/* quotient rule: a / b = a · (1/b), the reciprocal by the chain rule */
impl<T: DualNum> Div<&HyperDual2<T>> for &HyperDual2<T> {
    type Output = HyperDual2<T>;
    #[inline]
    fn div(self, other: &HyperDual2<T>) -> HyperDual2<T> {
        self * &other.recip()
    }
}

impl<T: DualNum> fmt::Display for HyperDual2<T> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "{} + [{}, {}]ε1 + [{}, {}]ε2 + [[{}, {}], [{}, {}]]ε1ε2",
            self.re,
            self.e1_0,
            self.e1_1,
            self.e2_0,
            self.e2_1,
            self.e12_00,
            self.e12_01,
            self.e12_10,
            self.e12_11
        )
    }
}

impl_second_derivatives!(
    HyperDual2,
    [e1_0, e1_1, e2_0, e2_1, e12_00, e12_01, e12_10, e12_11]
);
impl_dual!(
    HyperDual2,
    [e1_0, e1_1, e2_0, e2_1, e12_00, e12_01, e12_10, e12_11]
);

/// A dual number with four first-derivative parts, the layout of `DualSVec64<4>`.
#[derive(Copy, Clone, Debug)]
pub(crate) struct Dual4<T> {
    /// Value.
    pub re: T,
    /// Part 0.
    pub e0: T,
    /// Part 1.
    pub e1: T,
    /// Part 2.
    pub e2: T,
    /// Part 3.
    pub e3: T,
}

/// `Dual4` with `f64` parts.
pub(crate) type Dual4x64 = Dual4<f64>;

impl<T: DualNum> Dual4<T> {
    /// The number with the given value and parts.
    #[inline]
    pub fn from_parts(re: T, eps: [T; 4]) -> Self {
        let [e0, e1, e2, e3] = eps;
        Self { re, e0, e1, e2, e3 }
    }

    /// The number from its fields in declaration order (the form num-dual's macros call).
    #[inline]
    fn new(re: T, e0: T, e1: T, e2: T, e3: T) -> Self {
        Self { re, e0, e1, e2, e3 }
    }

    /// A constant (every part zero).
    #[inline]
    pub fn from_re(re: T) -> Self {
        Self::from_parts(re, std::array::from_fn(|_| T::zero()))
    }

    /// The parts.
    #[inline]
    pub fn eps(&self) -> [T; 4] {
        [
            self.e0.clone(),
            self.e1.clone(),
            self.e2.clone(),
            self.e3.clone(),
        ]
    }

    /// `f(self)` from `f(re)`, `f′(re)`.
    #[inline]
    fn chain_rule(&self, f0: T, f1: T) -> Self {
        Self::from_parts(f0, self.eps().map(|e| e * f1.clone()))
    }
}

/* product rule */
impl<T: DualNum> Mul<&Dual4<T>> for &Dual4<T> {
    type Output = Dual4<T>;
    #[inline]
    fn mul(self, other: &Dual4<T>) -> Dual4<T> {
        let (a, b) = (&self.re, &other.re);
        let (ae, be) = (self.eps(), other.eps());
        Dual4::from_parts(
            a.clone() * b.clone(),
            std::array::from_fn(|k| be[k].clone() * a.clone() + ae[k].clone() * b.clone()),
        )
    }
}

/* quotient rule: a / b = a · (1/b) */
impl<T: DualNum> Div<&Dual4<T>> for &Dual4<T> {
    type Output = Dual4<T>;
    #[inline]
    fn div(self, other: &Dual4<T>) -> Dual4<T> {
        self * &other.recip()
    }
}

impl<T: DualNum> fmt::Display for Dual4<T> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "{} + [{}, {}, {}, {}]ε",
            self.re, self.e0, self.e1, self.e2, self.e3
        )
    }
}

impl_first_derivatives!(Dual4, [e0, e1, e2, e3]);
impl_dual!(Dual4, [e0, e1, e2, e3]);

impl SmallDual<2> for HyperDual2x64 {
    #[inline(always)]
    fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
        let mut e1 = [0.0; 2];
        let mut e2 = [0.0; 2];
        if let Some((i, c)) = eps1 {
            e1[i] = c;
        }
        if let Some(j) = eps2 {
            e2[j] = 1.0;
        }
        Self::from_parts(re, e1, e2, [[0.0; 2]; 2])
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn eps1(&self, i: usize) -> f64 {
        self.e1()[i]
    }
    #[inline(always)]
    fn eps2(&self, j: usize) -> f64 {
        self.e2()[j]
    }
    #[inline(always)]
    fn eps12(&self, i: usize, j: usize) -> f64 {
        self.e12()[i][j]
    }
}

impl SmallGradient<2> for Dual4x64 {
    #[inline(always)]
    fn position(re: f64, i: usize) -> Self {
        let mut eps = [0.0; 4];
        eps[i] = 1.0;
        Self::from_parts(re, eps)
    }
    #[inline(always)]
    fn offset(re: f64, i: usize) -> Self {
        let mut eps = [0.0; 4];
        eps[i] = -1.0;
        eps[2 + i] = 1.0;
        Self::from_parts(re, eps)
    }
    #[inline(always)]
    fn value(&self) -> f64 {
        self.re
    }
    #[inline(always)]
    fn part(&self, k: usize) -> f64 {
        self.eps()[k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Const, U1};
    use num_dual::{Derivative, DualSVec64, HyperDualSVec64};

    /// Exercises products, quotients, powers and the elementary functions the macros supply.
    fn mixed<S: crate::Scalar>(x: [S; 2], y: [S; 2]) -> S {
        let (s, c) = (x[0] - y[1]).sin_cos();
        let r = (x[0] * x[0] + y[0] * y[0] + 1.0).sqrt();
        s * c * y[0] / r + (x[1] * 0.3).exp() * y[1].powi(3) - (y[0] * y[1] + 2.0).ln()
            + x[1].tanh() / (y[1] - 3.0)
            + x[0].atan2(y[0])
    }

    fn hyper_reference(x: [f64; 2], y: [f64; 2]) -> HyperDualSVec64<2, 2> {
        let xs = std::array::from_fn(|i| {
            let mut v = HyperDualSVec64::<2, 2>::from_re(x[i]);
            v.eps1 = Derivative::derivative_generic(Const::<2>, U1, i);
            v
        });
        let ys = std::array::from_fn(|j| {
            let mut v = HyperDualSVec64::<2, 2>::from_re(y[j]);
            v.eps2 = Derivative::derivative_generic(U1, Const::<2>, j);
            v
        });
        mixed(xs, ys)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-14 * (1.0 + b.abs())
    }

    #[test]
    fn hyper_dual_2_matches_num_dual_vector_type() {
        let (x, y) = ([0.7, -0.4], [1.3, 0.9]);
        let e1 = |i| {
            [
                1.0 * f64::from(u8::from(i == 0)),
                f64::from(u8::from(i == 1)),
            ]
        };
        let xs = std::array::from_fn(|i| {
            HyperDual2x64::from_parts(x[i], e1(i), [0.0; 2], [[0.0; 2]; 2])
        });
        let ys = std::array::from_fn(|j| {
            HyperDual2x64::from_parts(y[j], [0.0; 2], e1(j), [[0.0; 2]; 2])
        });
        let ours = mixed(xs, ys);
        let theirs = hyper_reference(x, y);
        assert!(close(ours.re, theirs.re));
        for i in 0..2 {
            assert!(close(
                ours.eps1(i),
                theirs.eps1.0.as_ref().map_or(0.0, |m| m[i])
            ));
            assert!(close(
                ours.eps2(i),
                theirs.eps2.0.as_ref().map_or(0.0, |m| m[i])
            ));
            for j in 0..2 {
                let r = theirs.eps1eps2.0.as_ref().map_or(0.0, |m| m[(i, j)]);
                assert!(
                    close(ours.eps12(i, j), r),
                    "({i}, {j}): {} vs {r}",
                    ours.eps12(i, j)
                );
            }
        }
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
    fn dual_4_matches_num_dual_vector_type() {
        let v = [0.7, -0.4, 1.3, 0.9];
        let ours = {
            let d: [Dual4x64; 4] = std::array::from_fn(|k| {
                let mut eps = [0.0; 4];
                eps[k] = 1.0;
                Dual4x64::from_parts(v[k], eps)
            });
            mixed([d[0], d[1]], [d[2], d[3]])
        };
        let theirs = {
            let d: [DualSVec64<4>; 4] = std::array::from_fn(|k| {
                DualSVec64::<4>::new(v[k], Derivative::derivative_generic(Const::<4>, U1, k))
            });
            mixed([d[0], d[1]], [d[2], d[3]])
        };
        assert!(close(ours.re, theirs.re));
        for k in 0..4 {
            let r = theirs.eps.0.as_ref().map_or(0.0, |m| m[k]);
            assert!(close(ours.part(k), r), "part {k}: {} vs {r}", ours.part(k));
        }
    }
}
