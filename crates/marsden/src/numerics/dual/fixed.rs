//! The fixed-size dual types (see the parent module for the rules they implement).

#![allow(clippy::suspicious_arithmetic_impl)]

use super::{SmallDual, SmallGradient};
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
