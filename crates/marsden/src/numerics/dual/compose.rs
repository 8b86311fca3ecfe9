//! A function at dual inputs from its Taylor data at their real parts.
//!
//! A function given by its value, gradient and Hessian at a point (compiled symbolic
//! derivatives, say) can be evaluated at hyper-dual inputs without hyper-dual arithmetic: since
//! `ε₁² = ε₂² = 0`, Taylor's formula stops at second order and is exact (Fike & Alonso 2011,
//! *The development of hyper-dual numbers for exact second-derivative calculations*, AIAA
//! 2011-886, §III). For inputs `xₖ = aₖ + bₖ·ε₁ + cₖ·ε₂ + dₖ·ε₁ε₂`,
//!
//! ```text
//! f(x).re     = f(a)
//! f(x).ε₁ᵢ    = Σₖ ∂ₖf(a) bₖᵢ                  (ε₂ⱼ alike with cₖⱼ)
//! f(x).ε₁ᵢε₂ⱼ = Σₖ ∂ₖf(a) dₖᵢⱼ + Σₖₗ ∂ₖₗf(a) bₖᵢ cₗⱼ
//! ```
//!
//! and a first-order dual needs the gradient only. [`compose`] does this for the fixed-size
//! types the small step kernels evaluate a Lagrangian at ([`super::SmallDual`],
//! [`super::SmallGradient`]: n = 1 … 4 degrees of freedom); for any other scalar type it
//! returns `None` and the caller evaluates the function itself. The values agree with the
//! function's own dual evaluation to round-off (the sums are taken in another order).

use std::any::{Any, TypeId};

use num_dual::HyperDual64;

use super::fixed::{
    Dual2x64, Dual4x64, Dual6x64, Dual8x64, HyperDual2x64, HyperDual3x64, HyperDual4x64,
};
use super::{SmallDual, SmallGradient};
use crate::scalar::Scalar;

/// The most inputs [`compose`] takes (`[q, q̇, t]` of four degrees of freedom).
pub const MAX_INPUTS: usize = 9;

/// Which Taylor data a composition needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// `[f, ∂₀f, …, ∂ₘ₋₁f]`.
    First,
    /// `[f, ∂₀f, …, ∂ₘ₋₁f, ∂ₖₗf for k ≤ l, row by row]`: `1 + m + m(m + 1)/2` values.
    Second,
}

/// `f` at `inputs` (`m ≤ MAX_INPUTS` values) from `taylor(a, order, out)`, which writes
/// [`Order`]'s Taylor data of `f` at the real parts `a` into `out`, when `S` is one of the
/// small kernels' dual types; `None` for every other `S` (nothing is called).
///
/// ```
/// use marsden::numerics::dual::compose::{Order, compose};
///
/// // f64 is no dual type of the small kernels: the caller evaluates f itself.
/// let none = compose(&[1.0_f64, 2.0], |_, _: Order, _: &mut [f64]| unreachable!());
/// assert_eq!(none, None);
/// ```
#[inline]
pub fn compose<S: Scalar>(
    inputs: &[S],
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    if inputs.len() > MAX_INPUTS {
        return None;
    }
    let s = TypeId::of::<S>();
    if s == TypeId::of::<HyperDual64>() {
        second::<1, HyperDual64, S>(inputs, taylor)
    } else if s == TypeId::of::<HyperDual2x64>() {
        second::<2, HyperDual2x64, S>(inputs, taylor)
    } else if s == TypeId::of::<HyperDual3x64>() {
        second::<3, HyperDual3x64, S>(inputs, taylor)
    } else if s == TypeId::of::<HyperDual4x64>() {
        second::<4, HyperDual4x64, S>(inputs, taylor)
    } else if s == TypeId::of::<Dual2x64>() {
        first::<1, Dual2x64, S>(inputs, taylor)
    } else if s == TypeId::of::<Dual4x64>() {
        first::<2, Dual4x64, S>(inputs, taylor)
    } else if s == TypeId::of::<Dual6x64>() {
        first::<3, Dual6x64, S>(inputs, taylor)
    } else if s == TypeId::of::<Dual8x64>() {
        first::<4, Dual8x64, S>(inputs, taylor)
    } else {
        None
    }
}

/// `D` as `S` (the same type).
#[inline(always)]
fn uncast<D: Scalar, S: Scalar>(value: D) -> Option<S> {
    (&value as &dyn Any).downcast_ref::<S>().copied()
}

/// Index of `∂ₖₗf` (`k ≤ l`) in [`Order::Second`]'s data of `m` inputs.
#[inline(always)]
fn hessian_index(m: usize, k: usize, l: usize) -> usize {
    1 + m + k * (2 * m - k + 1) / 2 + (l - k)
}

/// A hyper-dual type built from its parts.
trait HyperParts<const N: usize>: SmallDual<N> {
    fn from_parts(re: f64, e1: [f64; N], e2: [f64; N], e12: [[f64; N]; N]) -> Self;
}

impl HyperParts<1> for HyperDual64 {
    #[inline(always)]
    fn from_parts(re: f64, e1: [f64; 1], e2: [f64; 1], e12: [[f64; 1]; 1]) -> Self {
        HyperDual64::new(re, e1[0], e2[0], e12[0][0])
    }
}

/// A first-order dual type built from its parts.
trait GradientParts<const N: usize>: SmallGradient<N> {
    fn with_parts(re: f64, part: impl Fn(usize) -> f64) -> Self;
}

macro_rules! parts {
    (hyper: [$($h:ty, $n:literal);+], gradient: [$($g:ty, $gn:literal);+]) => {
        $(impl HyperParts<$n> for $h {
            #[inline(always)]
            fn from_parts(re: f64, e1: [f64; $n], e2: [f64; $n], e12: [[f64; $n]; $n]) -> Self {
                <$h>::from_parts(re, e1, e2, e12)
            }
        })+
        $(impl GradientParts<$gn> for $g {
            #[inline(always)]
            fn with_parts(re: f64, part: impl Fn(usize) -> f64) -> Self {
                <$g>::from_parts(re, std::array::from_fn(part))
            }
        })+
    };
}

parts!(hyper: [HyperDual2x64, 2; HyperDual3x64, 3; HyperDual4x64, 4],
       gradient: [Dual2x64, 1; Dual4x64, 2; Dual6x64, 3; Dual8x64, 4]);

/// The second-order composition for a hyper-dual `D` with `N`-dimensional ε parts. Inputs
/// whose ε parts are all zero (the time of a step, a constant) drop out of every sum.
#[inline(always)]
fn second<const N: usize, D: HyperParts<N>, S: Scalar>(
    inputs: &[S],
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    let m = inputs.len();
    let mut a = [0.0; MAX_INPUTS];
    // The live inputs' slots and parts: ε₁ (b), ε₂ (c), ε₁ε₂ (d).
    let (mut live, mut count) = ([0usize; MAX_INPUTS], 0);
    let mut b = [[0.0; N]; MAX_INPUTS];
    let mut c = [[0.0; N]; MAX_INPUTS];
    let mut d = [[[0.0; N]; N]; MAX_INPUTS];
    for (k, input) in inputs.iter().enumerate() {
        let x = (input as &dyn Any).downcast_ref::<D>()?;
        a[k] = x.value();
        let bk: [f64; N] = std::array::from_fn(|i| x.eps1(i));
        let ck: [f64; N] = std::array::from_fn(|j| x.eps2(j));
        let dk: [[f64; N]; N] = std::array::from_fn(|i| std::array::from_fn(|j| x.eps12(i, j)));
        let zero = |v: &[f64]| v.iter().all(|&p| p == 0.0);
        if !(zero(&bk) && zero(&ck) && zero(dk.as_flattened())) {
            (live[count], b[count], c[count], d[count]) = (k, bk, ck, dk);
            count += 1;
        }
    }
    let mut data = [0.0; 1 + MAX_INPUTS + MAX_INPUTS * (MAX_INPUTS + 1) / 2];
    taylor(&a[..m], Order::Second, &mut data);
    let g: [f64; MAX_INPUTS] = std::array::from_fn(|r| data[1 + live[r]]);
    let (mut e1, mut e2, mut e12) = ([0.0; N], [0.0; N], [[0.0; N]; N]);
    for r in 0..count {
        for i in 0..N {
            e1[i] += g[r] * b[r][i];
            e2[i] += g[r] * c[r][i];
            for j in 0..N {
                e12[i][j] += g[r] * d[r][i][j];
            }
        }
    }
    // e12 += Bᵀ H C over the live inputs: first hc = H C (count × N), row by row.
    for r in 0..count {
        let mut hc = [0.0; N];
        for s in 0..count {
            let (k, l) = (live[r].min(live[s]), live[r].max(live[s]));
            let h = data[hessian_index(m, k, l)];
            for j in 0..N {
                hc[j] += h * c[s][j];
            }
        }
        for i in 0..N {
            for j in 0..N {
                e12[i][j] += b[r][i] * hc[j];
            }
        }
    }
    uncast(D::from_parts(data[0], e1, e2, e12))
}

/// The first-order composition for a dual `D` with `2N` parts.
#[inline(always)]
fn first<const N: usize, D: GradientParts<N>, S: Scalar>(
    inputs: &[S],
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    let m = inputs.len();
    let mut x = [D::from(0.0); MAX_INPUTS];
    let mut a = [0.0; MAX_INPUTS];
    for (k, input) in inputs.iter().enumerate() {
        x[k] = *(input as &dyn Any).downcast_ref::<D>()?;
        a[k] = x[k].value();
    }
    let mut data = [0.0; 1 + MAX_INPUTS];
    taylor(&a[..m], Order::First, &mut data);
    let gradient = &data[1..=m];
    let value = D::with_parts(data[0], |p| {
        (0..m).map(|k| gradient[k] * x[k].part(p)).sum()
    });
    uncast(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A function of five inputs with products, quotients and elementary functions, every
    /// input meeting every other.
    fn f<S: Scalar>(x: &[S]) -> S {
        let (a, b, c, d, e) = (x[0], x[1], x[2], x[3], x[4]);
        a * a * b * c.sin()
            + (a * d).exp() / (e * e + 1.0)
            + (b - c).cos() * d.powi(3)
            + (c * e + 2.0).ln() * a
    }

    /// The Taylor data of `f` at `a`, each entry by its own hyper-dual evaluation.
    fn taylor(a: &[f64], order: Order, out: &mut [f64]) {
        let m = a.len();
        let at = |k: usize, l: usize| {
            let x: Vec<HyperDual64> = (0..m)
                .map(|i| HyperDual64::new(a[i], f64::from(i == k), f64::from(i == l), 0.0))
                .collect();
            f(&x)
        };
        out[0] = at(0, 0).re;
        for k in 0..m {
            out[1 + k] = at(k, k).eps1;
        }
        if order == Order::Second {
            for k in 0..m {
                for l in k..m {
                    out[hessian_index(m, k, l)] = at(k, l).eps1eps2;
                }
            }
        }
    }

    const A: [f64; 5] = [0.7, -0.4, 0.25, 1.1, -0.9];

    /// A made-up part, different for every input and index.
    fn part(k: usize, i: usize) -> f64 {
        ((7 * k + 3 * i) % 11) as f64 * 0.1 - 0.45
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-13 * (1.0 + b.abs())
    }

    /// Every part of `f` composed from its Taylor data equals `f` evaluated at the hyper-dual
    /// inputs themselves (every ε₁, ε₂ and ε₁ε₂ part of the inputs nonzero).
    fn second_order_agrees<const N: usize, D: HyperParts<N>>() {
        let x: Vec<D> = (0..A.len())
            .map(|k| {
                let e1 = std::array::from_fn(|i| part(k, i));
                let e2 = std::array::from_fn(|j| part(k, j + 5));
                let e12 = std::array::from_fn(|i| std::array::from_fn(|j| part(k, 3 * i + j + 1)));
                D::from_parts(A[k], e1, e2, e12)
            })
            .collect();
        let direct = f(&x);
        let composed: D = compose(&x, taylor).unwrap();
        assert!(close(composed.value(), direct.value()));
        for i in 0..N {
            assert!(close(composed.eps1(i), direct.eps1(i)), "ε₁ {i}");
            assert!(close(composed.eps2(i), direct.eps2(i)), "ε₂ {i}");
            for j in 0..N {
                let (c, d) = (composed.eps12(i, j), direct.eps12(i, j));
                assert!(close(c, d), "ε₁ε₂ ({i}, {j}): {c} against {d}");
            }
        }
    }

    /// The same for a first-order dual with `2N` parts.
    fn first_order_agrees<const N: usize, D: GradientParts<N>>() {
        let x: Vec<D> = (0..A.len())
            .map(|k| D::with_parts(A[k], |p| part(k, p)))
            .collect();
        let direct = f(&x);
        let composed: D = compose(&x, taylor).unwrap();
        assert!(close(composed.value(), direct.value()));
        for p in 0..2 * N {
            assert!(close(composed.part(p), direct.part(p)), "part {p}");
        }
    }

    #[test]
    fn composed_from_taylor_data_equals_the_dual_evaluation() {
        second_order_agrees::<1, HyperDual64>();
        second_order_agrees::<2, HyperDual2x64>();
        second_order_agrees::<3, HyperDual3x64>();
        second_order_agrees::<4, HyperDual4x64>();
        first_order_agrees::<1, Dual2x64>();
        first_order_agrees::<2, Dual4x64>();
        first_order_agrees::<3, Dual6x64>();
        first_order_agrees::<4, Dual8x64>();
    }

    #[test]
    fn other_types_and_too_many_inputs_are_left_to_the_caller() {
        let never = |_: &[f64], _: Order, _: &mut [f64]| panic!("not to be called");
        assert!(compose(&[1.0_f64; 3], never).is_none());
        let dual = num_dual::Dual64::new(1.0, 1.0);
        assert!(compose(&[dual; 3], never).is_none());
        let hyper = HyperDual64::new(1.0, 1.0, 0.0, 0.0);
        assert!(compose(&[hyper; MAX_INPUTS + 1], never).is_none());
    }
}
