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
//! types the small step kernels evaluate a Lagrangian at (`super::SmallDual`,
//! `super::SmallGradient`: n = 1 … 4 degrees of freedom), at the `2n + 1` inputs
//! `[q, q̇, t]` of a kernel of that size; for any other scalar type or number of inputs it
//! returns `None` and the caller evaluates the function itself. The values agree with the
//! function's own dual evaluation to round-off (the sums are taken in another order).

use std::any::{Any, TypeId};

use num_dual::HyperDual64;

use super::fixed::{
    Dual2x64, Dual4x64, Dual6x64, Dual8x64, HyperDual2x64, HyperDual3x64, HyperDual4x64,
};
use super::{SmallDual, SmallGradient};
use crate::numerics::dense::packed_index;
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

/// `f` at the inputs `[q, q̇, t]` from `taylor(a, order, out)`, which writes [`Order`]'s
/// Taylor data of `f` at their real parts `a` into `out`, when `S` is one of the small
/// kernels' dual types for `n` degrees of freedom and `q`, `q̇` have length `n`; `None`
/// otherwise (nothing is called). The inputs are read where they are, not copied into one
/// array first.
///
/// ```
/// use marsden::numerics::dual::compose::{Order, compose};
///
/// // f64 is no dual type of the small kernels: the caller evaluates f itself.
/// let none = compose(&[1.0_f64], &[2.0], 0.0, |_, _: Order, _: &mut [f64]| unreachable!());
/// assert_eq!(none, None);
/// ```
#[inline]
pub fn compose<S: Scalar>(
    q: &[S],
    v: &[S],
    t: S,
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    let x = Inputs { q, v, t };
    let s = TypeId::of::<S>();
    if s == TypeId::of::<HyperDual64>() {
        second::<1, 3, 10, HyperDual64, S>(x, taylor)
    } else if s == TypeId::of::<HyperDual2x64>() {
        second::<2, 5, 21, HyperDual2x64, S>(x, taylor)
    } else if s == TypeId::of::<HyperDual3x64>() {
        second::<3, 7, 36, HyperDual3x64, S>(x, taylor)
    } else if s == TypeId::of::<HyperDual4x64>() {
        second::<4, 9, 55, HyperDual4x64, S>(x, taylor)
    } else if s == TypeId::of::<Dual2x64>() {
        first::<1, 3, Dual2x64, S>(x, taylor)
    } else if s == TypeId::of::<Dual4x64>() {
        first::<2, 5, Dual4x64, S>(x, taylor)
    } else if s == TypeId::of::<Dual6x64>() {
        first::<3, 7, Dual6x64, S>(x, taylor)
    } else if s == TypeId::of::<Dual8x64>() {
        first::<4, 9, Dual8x64, S>(x, taylor)
    } else {
        None
    }
}

/// The inputs `[q, q̇, t]` where the caller holds them.
#[derive(Clone, Copy)]
struct Inputs<'a, S> {
    q: &'a [S],
    v: &'a [S],
    t: S,
}

impl<S: Scalar> Inputs<'_, S> {
    /// Input `k` of `[q, q̇, t]` as `D` when `q` and `q̇` have length `N` and `S` is `D`.
    #[inline(always)]
    fn get<const N: usize, D: Scalar>(&self, k: usize) -> Option<&D> {
        let x = if k < N {
            self.q.get(k)?
        } else if k < 2 * N {
            self.v.get(k - N)?
        } else {
            &self.t
        };
        (x as &dyn Any).downcast_ref::<D>()
    }

    /// Whether `q` and `q̇` have length `N`.
    #[inline(always)]
    fn fits<const N: usize>(&self) -> bool {
        self.q.len() == N && self.v.len() == N
    }
}

/// `D` as `S` (the same type).
#[inline(always)]
fn uncast<D: Scalar, S: Scalar>(value: D) -> Option<S> {
    (&value as &dyn Any).downcast_ref::<S>().copied()
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

/// The second-order composition for a hyper-dual `D` with `N`-dimensional ε parts, at the
/// `M = 2N + 1` inputs `[q, q̇, t]` of a kernel of that size (`None` for other lengths),
/// whose Taylor data has `T = 1 + M + M(M + 1)/2` values. Inputs whose ε parts are all zero
/// (the time of a step, a constant) drop out of every sum.
#[inline(always)]
fn second<const N: usize, const M: usize, const T: usize, D: HyperParts<N>, S: Scalar>(
    inputs: Inputs<'_, S>,
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    const { assert!(M == 2 * N + 1 && M <= MAX_INPUTS && T == 1 + M + M * (M + 1) / 2) };
    if !inputs.fits::<N>() {
        return None;
    }
    let mut parts = Parts::<N, M> {
        a: [0.0; M],
        b: [[0.0; N]; M],
        c: [[0.0; N]; M],
        d: [[[0.0; N]; N]; M],
        live: [false; M],
    };
    for k in 0..M {
        let x = inputs.get::<N, D>(k)?;
        parts.a[k] = x.value();
        parts.b[k] = std::array::from_fn(|i| x.eps1(i));
        parts.c[k] = std::array::from_fn(|j| x.eps2(j));
        parts.d[k] = std::array::from_fn(|i| std::array::from_fn(|j| x.eps12(i, j)));
        let zero = |v: &[f64]| v.iter().all(|&p| p == 0.0);
        let (b, c, d) = (&parts.b[k], &parts.c[k], &parts.d[k]);
        parts.live[k] = !(zero(b) && zero(c) && zero(d.as_flattened()));
    }
    let mut data = [0.0; T];
    taylor(&parts.a, Order::Second, &mut data);
    // The kernels' case: only the time is a plain number. Every bound of the sums is then a
    // constant (the loops unroll, the packed Hessian's indices are known when compiled).
    let (e1, e2, e12) = if parts.live[..M - 1].iter().all(|&l| l) && !parts.live[M - 1] {
        parts.sums(&data, |k| k < M - 1)
    } else {
        parts.sums(&data, |k| parts.live[k])
    };
    uncast(D::from_parts(data[0], e1, e2, e12))
}

/// The inputs of [`second`]: values `a`, parts ε₁ (`b`), ε₂ (`c`), ε₁ε₂ (`d`), and whether
/// any part is nonzero.
struct Parts<const N: usize, const M: usize> {
    a: [f64; M],
    b: [[f64; N]; M],
    c: [[f64; N]; M],
    d: [[[f64; N]; N]; M],
    live: [bool; M],
}

impl<const N: usize, const M: usize> Parts<N, M> {
    /// The ε₁, ε₂ and ε₁ε₂ parts of the result from the Taylor data, summed over the inputs
    /// `k` with `live(k)` in ascending order.
    #[inline(always)]
    fn sums(
        &self,
        data: &[f64],
        live: impl Fn(usize) -> bool,
    ) -> ([f64; N], [f64; N], [[f64; N]; N]) {
        let (b, c, d) = (&self.b, &self.c, &self.d);
        let (mut e1, mut e2, mut e12) = ([0.0; N], [0.0; N], [[0.0; N]; N]);
        for k in (0..M).filter(|&k| live(k)) {
            let g = data[1 + k];
            for i in 0..N {
                e1[i] += g * b[k][i];
                e2[i] += g * c[k][i];
                for j in 0..N {
                    e12[i][j] += g * d[k][i][j];
                }
            }
        }
        // e12 += Bᵀ H C: the rows hc_k = Σₗ ∂ₖₗf c_l (l ascending) first.
        for k in (0..M).filter(|&k| live(k)) {
            let mut hc = [0.0; N];
            for l in (0..M).filter(|&l| live(l)) {
                let h = data[hessian_index(M, k.min(l), k.max(l))];
                for j in 0..N {
                    hc[j] += h * c[l][j];
                }
            }
            for i in 0..N {
                for j in 0..N {
                    e12[i][j] += b[k][i] * hc[j];
                }
            }
        }
        (e1, e2, e12)
    }
}

/// Index of `∂ₖₗf` (`k ≤ l`) in [`Order::Second`]'s data of `m` inputs: after the value and
/// the gradient, the Hessian's packed upper triangle.
#[inline(always)]
const fn hessian_index(m: usize, k: usize, l: usize) -> usize {
    1 + m + packed_index(m, k, l)
}

/// The first-order composition for a dual `D` with `2N` parts, at the `M = 2N + 1` inputs
/// `[q, q̇, t]` of a kernel of that size (`None` for other lengths).
#[inline(always)]
fn first<const N: usize, const M: usize, D: GradientParts<N>, S: Scalar>(
    inputs: Inputs<'_, S>,
    taylor: impl FnOnce(&[f64], Order, &mut [f64]),
) -> Option<S> {
    const { assert!(M == 2 * N + 1 && M <= MAX_INPUTS) };
    if !inputs.fits::<N>() {
        return None;
    }
    let mut x = [D::from(0.0); M];
    let mut a = [0.0; M];
    for k in 0..M {
        x[k] = *inputs.get::<N, D>(k)?;
        a[k] = x[k].value();
    }
    let mut data = [0.0; 1 + MAX_INPUTS];
    taylor(&a, Order::First, &mut data[..=M]);
    let gradient = &data[1..=M];
    let value = D::with_parts(data[0], |p| {
        (0..M).map(|k| gradient[k] * x[k].part(p)).sum()
    });
    uncast(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A function of any number of inputs with products, quotients and elementary functions,
    /// every input meeting its two neighbours (cyclically).
    fn f<S: Scalar>(x: &[S]) -> S {
        let m = x.len();
        (0..m).fold(S::from(0.0), |sum, k| {
            let (a, b, c) = (x[k], x[(k + 1) % m], x[(k + 2) % m]);
            sum + a * a * b * c.sin() + (a * b).exp() / (c * c + 1.0) + (b - c).cos() * a.powi(3)
        })
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

    const A: [f64; MAX_INPUTS] = [0.7, -0.4, 0.25, 1.1, -0.9, 0.3, -0.6, 0.85, 0.15];

    /// A made-up part, different for every input and index.
    fn part(k: usize, i: usize) -> f64 {
        ((7 * k + 3 * i) % 11) as f64 * 0.1 - 0.45
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-13 * (1.0 + b.abs())
    }

    /// Every part of `f` composed from its Taylor data equals `f` evaluated at the hyper-dual
    /// inputs themselves: every ε₁, ε₂ and ε₁ε₂ part of the inputs nonzero, and again with
    /// input `dead` a plain number (as the time of a step is), which the composition skips.
    fn second_order_agrees<const N: usize, D: HyperParts<N>>() {
        for dead in [None, Some(2 * N), Some(0)] {
            second_order_agrees_with::<N, D>(dead);
        }
    }

    fn second_order_agrees_with<const N: usize, D: HyperParts<N>>(dead: Option<usize>) {
        let x: Vec<D> = (0..2 * N + 1)
            .map(|k| {
                let live = if dead == Some(k) { 0.0 } else { 1.0 };
                let e1 = std::array::from_fn(|i| live * part(k, i));
                let e2 = std::array::from_fn(|j| live * part(k, j + 5));
                let e12 =
                    std::array::from_fn(|i| std::array::from_fn(|j| live * part(k, 3 * i + j + 1)));
                D::from_parts(A[k], e1, e2, e12)
            })
            .collect();
        let direct = f(&x);
        let composed: D = compose(&x[..N], &x[N..2 * N], x[2 * N], taylor).unwrap();
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
        let x: Vec<D> = (0..2 * N + 1)
            .map(|k| D::with_parts(A[k], |p| part(k, p)))
            .collect();
        let direct = f(&x);
        let composed: D = compose(&x[..N], &x[N..2 * N], x[2 * N], taylor).unwrap();
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
    fn other_types_and_other_input_counts_are_left_to_the_caller() {
        let never = |_: &[f64], _: Order, _: &mut [f64]| panic!("not to be called");
        assert!(compose(&[1.0_f64], &[1.0], 0.0, never).is_none());
        let dual = num_dual::Dual64::new(1.0, 1.0);
        assert!(compose(&[dual], &[dual], dual, never).is_none());
        let hyper = HyperDual64::new(1.0, 1.0, 0.0, 0.0);
        assert!(compose(&[hyper; 2], &[hyper; 2], hyper, never).is_none());
        assert!(compose(&[hyper], &[], hyper, never).is_none());
        let gradient = Dual4x64::from_parts(1.0, [1.0, 0.0, 0.0, 0.0]);
        assert!(compose(&[gradient], &[gradient], gradient, never).is_none());
    }
}
