//! Dual numbers of fixed size with every part stored, for the step kernels of 2 to 4 degrees
//! of freedom (and the first-order one of 1).
//!
//! num-dual's vector duals (`HyperDualSVec64<N, N>`, `DualSVec64<2N>`) keep each derivative part
//! as an `Option` of a matrix, so that a constant costs nothing. In the small step kernels
//! ([`crate::small`], [`crate::small_constrained`]) every part is always present, and the
//! branches on the options and the products that are not inlined are a third of an evaluation
//! of the double pendulum's `L_d` (1 710 instructions per hyper-dual evaluation with
//! `HyperDualSVec64<2, 2>`, 1 110 with `HyperDual2`, callgrind). The types here are num-dual's
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
#![allow(clippy::suspicious_arithmetic_impl)]

use crate::small::{SmallDual, SmallGradient};
use num_dual::{DualNum, DualNumFloat, DualStruct};
// num-dual's exported macros call one another, and name these traits, by bare name: all of
// them must be in scope where `impl_dual!` and `impl_*_derivatives!` expand.
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

/// Writes `[a, b, …]`.
fn write_parts<T: fmt::Display>(f: &mut fmt::Formatter, parts: &[T]) -> fmt::Result {
    write!(f, "[")?;
    for (k, x) in parts.iter().enumerate() {
        if k > 0 {
            write!(f, ", ")?;
        }
        write!(f, "{x}")?;
    }
    write!(f, "]")
}

/// The quotient rule as `a / b = a · (1/b)`, the reciprocal by the type's chain rule.
macro_rules! quotient_by_reciprocal {
    ($name:ident) => {
        impl<T: DualNum> Div<&$name<T>> for &$name<T> {
            type Output = $name<T>;
            #[inline]
            fn div(self, other: &$name<T>) -> $name<T> {
                self * &other.recip()
            }
        }
    };
}

/// A hyper-dual type `$name<T>` with `$n`-dimensional ε₁ and ε₂ parts and the `$n × $n`
/// ε₁ε₂ parts as fields (the layout of `HyperDualSVec64<$n, $n>`), and its use in the small
/// kernel ([`SmallDual`]).
macro_rules! hyper_dual {
    ($name:ident, $alias:ident, $n:literal,
     e1: [$($e1:ident),+], e2: [$($e2:ident),+], e12: [$([$($e12:ident),+]),+]) => {
        #[doc = concat!("A hyper-dual number with ", stringify!($n), "-dimensional ε₁ and ε₂ parts: ")]
        #[doc = "value, `∂/∂xᵢ` (ε₁), `∂/∂yⱼ` (ε₂) and `∂²/∂xᵢ∂yⱼ` (ε₁ε₂)."]
        #[derive(Copy, Clone, Debug)]
        pub(crate) struct $name<T> {
            /// Value.
            pub re: T,
            $(#[doc = "An ε₁ part."] pub $e1: T,)+
            $(#[doc = "An ε₂ part."] pub $e2: T,)+
            $($(#[doc = "An ε₁ε₂ part."] pub $e12: T,)+)+
        }

        #[doc = concat!("`", stringify!($name), "` with `f64` parts.")]
        pub(crate) type $alias = $name<f64>;

        impl<T: DualNum> $name<T> {
            /// The number with the given value and parts `ε₁ = e1`, `ε₂ = e2`, `ε₁ε₂ = e12`.
            #[inline]
            pub fn from_parts(re: T, e1: [T; $n], e2: [T; $n], e12: [[T; $n]; $n]) -> Self {
                let [$($e1),+] = e1;
                let [$($e2),+] = e2;
                let [$([$($e12),+]),+] = e12;
                Self { re, $($e1,)+ $($e2,)+ $($($e12,)+)+ }
            }

            /// The number from its fields in declaration order (the form num-dual's macros call).
            #[allow(clippy::too_many_arguments)]
            #[inline]
            fn new(re: T, $($e1: T,)+ $($e2: T,)+ $($($e12: T,)+)+) -> Self {
                Self { re, $($e1,)+ $($e2,)+ $($($e12,)+)+ }
            }

            /// A constant (every part zero).
            #[inline]
            pub fn from_re(re: T) -> Self {
                let zero = || std::array::from_fn(|_| T::zero());
                Self::from_parts(re, zero(), zero(), std::array::from_fn(|_| zero()))
            }

            /// The ε₁ parts.
            #[inline]
            pub fn e1(&self) -> [T; $n] {
                [$(self.$e1.clone()),+]
            }

            /// The ε₂ parts.
            #[inline]
            pub fn e2(&self) -> [T; $n] {
                [$(self.$e2.clone()),+]
            }

            /// The ε₁ε₂ parts.
            #[inline]
            pub fn e12(&self) -> [[T; $n]; $n] {
                [$([$(self.$e12.clone()),+]),+]
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
                            a12[i][j].clone() * f1.clone()
                                + a1[i].clone() * a2[j].clone() * f2.clone()
                        })
                    }),
                )
            }
        }

        /* product rule */
        impl<T: DualNum> Mul<&$name<T>> for &$name<T> {
            type Output = $name<T>;
            #[inline]
            fn mul(self, other: &$name<T>) -> $name<T> {
                let (a, b) = (&self.re, &other.re);
                let (a1, a2, a12) = (self.e1(), self.e2(), self.e12());
                let (b1, b2, b12) = (other.e1(), other.e2(), other.e12());
                $name::from_parts(
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

        quotient_by_reciprocal!($name);

        impl<T: DualNum> fmt::Display for $name<T> {
            fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "{} + ", self.re)?;
                write_parts(f, &self.e1())?;
                write!(f, "ε1 + ")?;
                write_parts(f, &self.e2())?;
                write!(f, "ε2 + ")?;
                write_parts(f, self.e12().as_flattened())?;
                write!(f, "ε1ε2")
            }
        }

        impl_second_derivatives!($name, [$($e1),+, $($e2),+, $($($e12),+),+]);
        impl_dual!($name, [$($e1),+, $($e2),+, $($($e12),+),+]);

        impl SmallDual<$n> for $alias {
            #[inline(always)]
            fn seeded(re: f64, eps1: Option<(usize, f64)>, eps2: Option<usize>) -> Self {
                let mut e1 = [0.0; $n];
                let mut e2 = [0.0; $n];
                if let Some((i, c)) = eps1 {
                    e1[i] = c;
                }
                if let Some(j) = eps2 {
                    e2[j] = 1.0;
                }
                Self::from_parts(re, e1, e2, [[0.0; $n]; $n])
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
    };
}

/// A dual type `$name<T>` with `2 · $n` first-derivative parts as fields (the layout of
/// `DualSVec64<2 · $n>`), and its use in the small kernel ([`SmallGradient`]).
macro_rules! gradient_dual {
    ($name:ident, $alias:ident, $n:literal, $m:literal, [$($e:ident),+]) => {
        #[doc = concat!("A dual number with ", stringify!($m), " first-derivative parts.")]
        #[derive(Copy, Clone, Debug)]
        pub(crate) struct $name<T> {
            /// Value.
            pub re: T,
            $(#[doc = "A derivative part."] pub $e: T,)+
        }

        #[doc = concat!("`", stringify!($name), "` with `f64` parts.")]
        pub(crate) type $alias = $name<f64>;

        impl<T: DualNum> $name<T> {
            /// The number with the given value and parts.
            #[inline]
            pub fn from_parts(re: T, eps: [T; $m]) -> Self {
                let [$($e),+] = eps;
                Self { re, $($e),+ }
            }

            /// The number from its fields in declaration order (the form num-dual's macros call).
            #[allow(clippy::too_many_arguments)]
            #[inline]
            fn new(re: T, $($e: T),+) -> Self {
                Self { re, $($e),+ }
            }

            /// A constant (every part zero).
            #[inline]
            pub fn from_re(re: T) -> Self {
                Self::from_parts(re, std::array::from_fn(|_| T::zero()))
            }

            /// The parts.
            #[inline]
            pub fn eps(&self) -> [T; $m] {
                [$(self.$e.clone()),+]
            }

            /// `f(self)` from `f(re)`, `f′(re)`.
            #[inline]
            fn chain_rule(&self, f0: T, f1: T) -> Self {
                Self::from_parts(f0, self.eps().map(|e| e * f1.clone()))
            }
        }

        /* product rule */
        impl<T: DualNum> Mul<&$name<T>> for &$name<T> {
            type Output = $name<T>;
            #[inline]
            fn mul(self, other: &$name<T>) -> $name<T> {
                let (a, b) = (&self.re, &other.re);
                let (ae, be) = (self.eps(), other.eps());
                $name::from_parts(
                    a.clone() * b.clone(),
                    std::array::from_fn(|k| be[k].clone() * a.clone() + ae[k].clone() * b.clone()),
                )
            }
        }

        quotient_by_reciprocal!($name);

        impl<T: DualNum> fmt::Display for $name<T> {
            fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "{} + ", self.re)?;
                write_parts(f, &self.eps())?;
                write!(f, "ε")
            }
        }

        impl_first_derivatives!($name, [$($e),+]);
        impl_dual!($name, [$($e),+]);

        impl SmallGradient<$n> for $alias {
            #[inline(always)]
            fn position(re: f64, i: usize) -> Self {
                let mut eps = [0.0; $m];
                eps[i] = 1.0;
                Self::from_parts(re, eps)
            }
            #[inline(always)]
            fn offset(re: f64, i: usize) -> Self {
                let mut eps = [0.0; $m];
                eps[i] = -1.0;
                eps[$n + i] = 1.0;
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
    };
}

hyper_dual!(HyperDual2, HyperDual2x64, 2,
    e1: [e1_0, e1_1], e2: [e2_0, e2_1], e12: [[e12_00, e12_01], [e12_10, e12_11]]);
hyper_dual!(HyperDual3, HyperDual3x64, 3,
    e1: [e1_0, e1_1, e1_2], e2: [e2_0, e2_1, e2_2],
    e12: [[e12_00, e12_01, e12_02], [e12_10, e12_11, e12_12], [e12_20, e12_21, e12_22]]);
hyper_dual!(HyperDual4, HyperDual4x64, 4,
    e1: [e1_0, e1_1, e1_2, e1_3], e2: [e2_0, e2_1, e2_2, e2_3],
    e12: [[e12_00, e12_01, e12_02, e12_03], [e12_10, e12_11, e12_12, e12_13],
          [e12_20, e12_21, e12_22, e12_23], [e12_30, e12_31, e12_32, e12_33]]);
gradient_dual!(Dual2, Dual2x64, 1, 2, [e0, e1]);
gradient_dual!(Dual4, Dual4x64, 2, 4, [e0, e1, e2, e3]);
gradient_dual!(Dual6, Dual6x64, 3, 6, [e0, e1, e2, e3, e4, e5]);
gradient_dual!(Dual8, Dual8x64, 4, 8, [e0, e1, e2, e3, e4, e5, e6, e7]);

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::{DualSVec64, HyperDualSVec64};

    /// Exercises products, quotients, powers and the elementary functions the macros supply,
    /// with every `xᵢ` meeting every `yⱼ`.
    fn mixed<S: crate::Scalar>(x: &[S], y: &[S]) -> S {
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
}
