//! Automatic differentiation: the only module that seeds dual numbers.
//!
//! Physics is written once as a [`MultiFunction`] generic over [`Scalar`]; this module evaluates
//! it at num-dual's statically sized dual numbers to obtain exact first and mixed second
//! derivatives (forward mode). Sizes are dispatched once per call to a chunk width
//! `C ∈ {1, 2, 4}`; wider ranges are covered in blocks of 4 (chunked as ForwardDiff.jl does), so
//! nothing here allocates on the heap for systems whose `(inputs, outputs)` fit the inline
//! buffers, and large systems still work.
//!
//! Why no wider chunk: the mixed part of a hyper-dual number has `C²` entries, so covering an
//! `n × n` block costs about `n²` multiply–adds per operation whatever `C` is; a wider chunk only
//! saves repeating the value and first-order parts (`1 + 2C` per chunk pair) and the scalar
//! work of `f` itself. An 8-wide chunk (its operations unrolled over 64 entries, compiled once
//! per system and rule) was a sixth of the `marsden` binary and ran slower than blocks of four
//! where it was used (BENCHMARKS.md, "Chunks of four").
//!
//! * [`jacobian`]: values and `∂out/∂x[cols]` with first-order duals `DualSVec64<C>`.
//! * [`partial_hessian`]: additionally `∂out₀/∂x[rows]` and the mixed block
//!   `∂²out₀/∂x[rows]∂x[cols]` of the first output, with hyper-dual numbers
//!   `HyperDualSVec64<C, C>` (eps₁ seeds the rows, eps₂ the columns; a variable in both ranges is
//!   seeded in both, which still yields the exact second derivative).
//! * [`nested_gradient`]: a gradient evaluated at scalars that are themselves dual numbers
//!   (nested `Dual<S>`), so that generic code can differentiate inside itself.

use std::ops::Range;

use crate::numerics::scratch::Buffer;
use crate::scalar::Scalar;
use nalgebra::{Const, U1};
use num_dual::{Derivative, Dual, DualSVec64, HyperDual64, HyperDualSVec64};

/// A vector-valued function written once over the scalar type.
pub trait MultiFunction {
    /// The largest number of inputs the type can have, when the type fixes it: only the chunk
    /// widths that many inputs can need are compiled (a wrong value costs speed, never
    /// correctness: a smaller width covers the ranges in blocks). Default: `None`.
    const MAX_INPUTS: Option<usize> = None;

    /// Number of inputs.
    fn inputs(&self) -> usize;
    /// Number of outputs.
    fn outputs(&self) -> usize;
    /// Writes `f(x)` into `out` (length [`MultiFunction::outputs`]).
    fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]);
}

/// Inline capacity of the dual-number buffers (inputs or outputs beyond it spill to the heap).
const INLINE: usize = 24;

/// Result of [`partial_hessian`]; buffers are reused across calls.
#[derive(Debug, Clone, Default)]
pub struct HessianParts {
    /// `f(x)`, one per output.
    pub values: Vec<f64>,
    /// `∂f₀/∂x[rows]` (first output only).
    pub grad_rows: Vec<f64>,
    /// `∂fᵢ/∂x[cols]`, row-major: output `i`, column `j` at `i * ncols + j`.
    pub jac_cols: Vec<f64>,
    /// `∂²f₀/∂x[rows]∂x[cols]`, row-major `nrows × ncols`.
    pub hess: Vec<f64>,
    /// Number of function evaluations performed (one per chunk pair).
    pub evaluations: usize,
}

impl HessianParts {
    fn resize(&mut self, outputs: usize, nrows: usize, ncols: usize) {
        self.values.resize(outputs, 0.0);
        self.grad_rows.resize(nrows, 0.0);
        self.jac_cols.resize(outputs * ncols, 0.0);
        self.hess.resize(nrows * ncols, 0.0);
        self.evaluations = 0;
    }
}

/// Which chunk widths are compiled for `F`: each is a constant of the monomorphised driver,
/// so the code of the others is never generated.
struct Widths<F>(std::marker::PhantomData<F>);

impl<F: MultiFunction> Widths<F> {
    const TWO: bool = may_reach::<F>(2);
    const FOUR: bool = may_reach::<F>(3);
}

/// Whether a range of `len` inputs can occur for `F`.
const fn may_reach<F: MultiFunction>(len: usize) -> bool {
    match F::MAX_INPUTS {
        Some(max) => len <= max,
        None => true,
    }
}

/// Values and Jacobian `∂f/∂x[cols]` (row-major `outputs × cols.len()`) of `f` at `x`.
///
/// Returns the number of function evaluations performed.
pub fn jacobian<F: MultiFunction>(
    f: &F,
    x: &[f64],
    cols: Range<usize>,
    values: &mut [f64],
    jac: &mut [f64],
) -> usize {
    match cols.len() {
        0 => {
            eval_f64(f, x, values);
            1
        }
        1 => jacobian_chunked::<1, F>(f, x, cols, values, jac),
        2 if Widths::<F>::TWO => jacobian_chunked::<2, F>(f, x, cols, values, jac),
        3.. if Widths::<F>::FOUR => jacobian_chunked::<4, F>(f, x, cols, values, jac),
        // Beyond `F::MAX_INPUTS`: one column at a time.
        _ => jacobian_chunked::<1, F>(f, x, cols, values, jac),
    }
}

/// Values, first derivatives and the mixed second-derivative block of `f` at `x`
/// (see [`HessianParts`]).
pub fn partial_hessian<F: MultiFunction>(
    f: &F,
    x: &[f64],
    rows: Range<usize>,
    cols: Range<usize>,
    out: &mut HessianParts,
) {
    out.resize(f.outputs(), rows.len(), cols.len());
    match rows.len().max(cols.len()) {
        0 => {
            eval_f64(f, x, &mut out.values);
            out.evaluations = 1;
        }
        1 => hessian_scalar(f, x, rows, cols, out),
        2 if Widths::<F>::TWO => hessian_chunked::<2, F>(f, x, rows, cols, out),
        3.. if Widths::<F>::FOUR => hessian_chunked::<4, F>(f, x, rows, cols, out),
        // Beyond `F::MAX_INPUTS`: one row and column at a time.
        _ => hessian_chunked::<1, F>(f, x, rows, cols, out),
    }
}

/// Plain evaluation at `f64`.
pub fn eval_f64<F: MultiFunction>(f: &F, x: &[f64], values: &mut [f64]) {
    f.eval(x, values);
}

/// Gradient `∂f₀/∂x[cols]` at a point whose coordinates are themselves scalars of type `S`
/// (nested forward mode: one evaluation at `Dual<S>` per column), written into `out`.
///
/// This differentiates *inside* generic code: a function written over `S` can use the
/// derivative of another function and still be differentiated by the caller (e.g. the
/// Legendre transform `∂L/∂v` inside a Hamiltonian built from a Lagrangian). Costs
/// `cols.len()` evaluations; meant for small systems and derived quantities, not hot loops.
pub fn nested_gradient<S: Scalar, F: MultiFunction>(
    f: &F,
    x: &[S],
    cols: Range<usize>,
    out: &mut [S],
) {
    let m = f.outputs();
    let mut xs: Vec<Dual<S>> = x.iter().map(|&v| Dual::from_re(v)).collect();
    let mut res: Vec<Dual<S>> = (0..m).map(|_| Dual::from_re(S::from(0.0))).collect();
    for (k, c) in cols.enumerate() {
        xs[c].eps = S::from(1.0);
        f.eval(&xs, &mut res);
        out[k] = res[0].eps;
        xs[c].eps = S::from(0.0);
    }
}

/// The mixed directional second derivative `uᵀ ∇²f₀(x) w` of the first output, in one
/// evaluation at scalar hyper-dual numbers `x + ε₁u + ε₂w`: a probe of a Hessian of any size at
/// the cost of about four evaluations of `f`.
pub fn directional_second<F: MultiFunction>(f: &F, x: &[f64], u: &[f64], w: &[f64]) -> f64 {
    let zero = HyperDual64::from(0.0);
    let seed = |i: usize| HyperDual64::new(x[i], u[i], w[i], 0.0);
    let mut xs = Buffer::<_, INLINE>::empty();
    let xs = xs.from_fn(x.len(), zero, seed);
    let mut res = Buffer::<_, INLINE>::empty();
    let res = res.filled(f.outputs(), zero);
    f.eval(xs, res);
    res[0].eps1eps2
}

fn jacobian_chunked<const C: usize, F: MultiFunction>(
    f: &F,
    x: &[f64],
    cols: Range<usize>,
    values: &mut [f64],
    jac: &mut [f64],
) -> usize {
    let (nc, m) = (cols.len(), f.outputs());
    let zero = DualSVec64::<C>::from_re(0.0);
    let init = |i: usize| DualSVec64::<C>::from_re(x[i]);
    let mut xs = Buffer::<_, INLINE>::empty();
    let xs = xs.from_fn(x.len(), zero, init);
    let mut out = Buffer::<_, INLINE>::empty();
    let out = out.filled(m, zero);
    let mut evaluations = 0;
    for jb in (0..nc).step_by(C) {
        let width = C.min(nc - jb);
        for a in 0..width {
            xs[cols.start + jb + a].eps = Derivative::derivative_generic(Const::<C>, U1, a);
        }
        f.eval(xs, out);
        evaluations += 1;
        for (i, o) in out.iter().enumerate() {
            values[i] = o.re;
            let row = &mut jac[i * nc + jb..i * nc + jb + width];
            match &o.eps.0 {
                Some(e) => row.copy_from_slice(&e.as_slice()[..width]),
                None => row.fill(0.0),
            }
        }
        for a in 0..width {
            xs[cols.start + jb + a].eps = Derivative::none();
        }
    }
    evaluations
}

fn hessian_chunked<const C: usize, F: MultiFunction>(
    f: &F,
    x: &[f64],
    rows: Range<usize>,
    cols: Range<usize>,
    out: &mut HessianParts,
) {
    let (nr, nc, m) = (rows.len(), cols.len(), f.outputs());
    let zero = hd_re::<C>(0.0);
    let mut xs = Buffer::<_, INLINE>::empty();
    let xs = xs.from_fn(x.len(), zero, |i| hd_re::<C>(x[i]));
    let mut res = Buffer::<_, INLINE>::empty();
    let res = res.filled(m, zero);
    // At least one chunk each way, so values are written even if a range is empty.
    for ib in (0..nr.max(1)).step_by(C) {
        for jb in (0..nc.max(1)).step_by(C) {
            let (wr, wc) = (C.min(nr.saturating_sub(ib)), C.min(nc.saturating_sub(jb)));
            for a in 0..wr {
                xs[rows.start + ib + a] = xs[rows.start + ib + a].derivative1(a);
            }
            for b in 0..wc {
                xs[cols.start + jb + b] = xs[cols.start + jb + b].derivative2(b);
            }
            f.eval(xs, res);
            out.evaluations += 1;
            collect_block(res, ib, wr, jb, wc, nc, out);
            for v in xs.iter_mut() {
                *v = hd_re::<C>(v.re);
            }
        }
    }
}

/// The 1 × 1 case with num-dual's scalar hyper-dual numbers (no optional derivative parts):
/// the pendulum-sized hot path.
fn hessian_scalar<F: MultiFunction>(
    f: &F,
    x: &[f64],
    rows: Range<usize>,
    cols: Range<usize>,
    out: &mut HessianParts,
) {
    let zero = HyperDual64::from(0.0);
    let seed = |i: usize| {
        let mut v = HyperDual64::from(x[i]);
        v.eps1 = if rows.contains(&i) { 1.0 } else { 0.0 };
        v.eps2 = if cols.contains(&i) { 1.0 } else { 0.0 };
        v
    };
    let mut xs = Buffer::<_, 4>::empty();
    let xs = xs.from_fn(x.len(), zero, seed);
    let mut res = Buffer::<_, 4>::empty();
    let res = res.filled(f.outputs(), zero);
    f.eval(xs, res);
    out.evaluations += 1;
    for (i, o) in res.iter().enumerate() {
        out.values[i] = o.re;
        if cols.len() == 1 {
            out.jac_cols[i] = o.eps2;
        }
    }
    if rows.len() == 1 {
        out.grad_rows[0] = res[0].eps1;
        if cols.len() == 1 {
            out.hess[0] = res[0].eps1eps2;
        }
    }
}

#[inline]
fn hd_re<const C: usize>(v: f64) -> HyperDualSVec64<C, C> {
    HyperDualSVec64::<C, C>::from_re(v)
}

/// Copies one chunk pair's derivatives (the `wr` rows from `ib` by the `wc` columns from `jb`
/// of the `nc` columns) into the output buffers.
fn collect_block<const C: usize>(
    res: &[HyperDualSVec64<C, C>],
    ib: usize,
    wr: usize,
    jb: usize,
    wc: usize,
    nc: usize,
    out: &mut HessianParts,
) {
    let first = &res[0];
    if jb == 0 {
        let g = &mut out.grad_rows[ib..ib + wr];
        match &first.eps1.0 {
            Some(e) => g.copy_from_slice(&e.as_slice()[..wr]),
            None => g.fill(0.0),
        }
    }
    if ib == 0 {
        for (i, o) in res.iter().enumerate() {
            out.values[i] = o.re;
            let row = &mut out.jac_cols[i * nc + jb..i * nc + jb + wc];
            match &o.eps2.0 {
                Some(e) => row.copy_from_slice(&e.as_slice()[..wc]),
                None => row.fill(0.0),
            }
        }
    }
    for a in 0..wr {
        let row = &mut out.hess[(ib + a) * nc + jb..(ib + a) * nc + jb + wc];
        match &first.eps1eps2.0 {
            // nalgebra stores column-major: entry (a, b) is at a + b * C.
            Some(h) => {
                for (b, r) in row.iter_mut().enumerate() {
                    *r = h[(a, b)];
                }
            }
            None => row.fill(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f(x) = [x0² x1 + sin(x2) x3, x0 x3]  (4 inputs, 2 outputs).
    struct Probe;
    impl MultiFunction for Probe {
        fn inputs(&self) -> usize {
            4
        }
        fn outputs(&self) -> usize {
            2
        }
        fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
            out[0] = x[0] * x[0] * x[1] + x[2].sin() * x[3];
            out[1] = x[0] * x[3];
        }
    }

    fn exact_hessian(x: &[f64]) -> [[f64; 4]; 4] {
        let (s, c) = x[2].sin_cos();
        [
            [2.0 * x[1], 2.0 * x[0], 0.0, 0.0],
            [2.0 * x[0], 0.0, 0.0, 0.0],
            [0.0, 0.0, -s * x[3], c],
            [0.0, 0.0, c, 0.0],
        ]
    }

    #[test]
    fn partial_hessian_matches_closed_form_for_overlapping_ranges() {
        let x = [0.7, -1.3, 0.4, 2.1];
        let mut parts = HessianParts::default();
        // Rows 0..3 and columns 1..4 overlap in 1..3, like a Galerkin step's internal stages.
        partial_hessian(&Probe, &x, 0..3, 1..4, &mut parts);
        let h = exact_hessian(&x);
        for (a, row) in h.iter().take(3).enumerate() {
            for b in 0..3 {
                assert!((parts.hess[a * 3 + b] - row[b + 1]).abs() < 1e-15);
            }
        }
        let grad = [
            2.0 * x[0] * x[1],
            x[0] * x[0],
            x[2].cos() * x[3],
            x[2].sin(),
        ];
        for a in 0..3 {
            assert!((parts.grad_rows[a] - grad[a]).abs() < 1e-15);
            assert!((parts.jac_cols[a] - grad[a + 1]).abs() < 1e-15);
        }
        // Second output: x0 x3, derivative w.r.t. columns (x1, x2, x3) = (0, 0, x0).
        assert_eq!(&parts.jac_cols[3..6], &[0.0, 0.0, x[0]]);
        assert_eq!(parts.evaluations, 1);
    }

    #[test]
    fn nested_gradient_differentiates_inside_generic_code() {
        /// f(x) = x0² x1 + sin x0.
        struct F;
        impl MultiFunction for F {
            fn inputs(&self) -> usize {
                2
            }
            fn outputs(&self) -> usize {
                1
            }
            fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
                out[0] = x[0] * x[0] * x[1] + x[0].sin();
            }
        }
        let (a, b) = (0.7_f64, -1.3_f64);
        let x = [Dual::new(a, 1.0), Dual::new(b, 0.0)];
        let mut g = [Dual::new(0.0, 0.0); 2];
        nested_gradient(&F, &x, 0..2, &mut g);
        // ∂f/∂x0 = 2 x0 x1 + cos x0 and its x0-derivative 2 x1 − sin x0.
        assert!((g[0].re - (2.0 * a * b + a.cos())).abs() < 1e-15);
        assert!((g[0].eps - (2.0 * b - a.sin())).abs() < 1e-15);
        // ∂f/∂x1 = x0² and its x0-derivative 2 x0.
        assert!((g[1].re - a * a).abs() < 1e-15 && (g[1].eps - 2.0 * a).abs() < 1e-15);
    }

    /// An `n`-input quadratic form: `n ≥ 3` takes the chunked (4-wide) path, in `⌈n/4⌉²` chunk
    /// pairs, the last chunk partial unless 4 divides `n`.
    struct Quadratic(usize);
    impl MultiFunction for Quadratic {
        fn inputs(&self) -> usize {
            self.0
        }
        fn outputs(&self) -> usize {
            1
        }
        fn eval<S: Scalar>(&self, x: &[S], out: &mut [S]) {
            let mut acc = S::from(0.0);
            for i in 0..self.0 {
                for j in 0..self.0 {
                    acc += x[i] * x[j] * ((i + 2 * j) as f64).sin();
                }
            }
            out[0] = acc;
        }
    }

    #[test]
    fn chunked_hessian_equals_symmetrised_coefficients() {
        // 7: a partial last chunk (4 + 3); 20: five full chunks.
        for n in [7, 20] {
            let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).cos()).collect();
            let mut parts = HessianParts::default();
            partial_hessian(&Quadratic(n), &x, 0..n, 0..n, &mut parts);
            let chunks = n.div_ceil(4);
            assert_eq!(parts.evaluations, chunks * chunks, "n = {n}");
            for i in 0..n {
                for j in 0..n {
                    let a = ((i + 2 * j) as f64).sin() + ((j + 2 * i) as f64).sin();
                    assert!(
                        (parts.hess[i * n + j] - a).abs() < 1e-13,
                        "n = {n}, ({i},{j})"
                    );
                }
            }
            let mut values = [0.0];
            let mut jac = vec![0.0; n];
            let evaluations = jacobian(&Quadratic(n), &x, 0..n, &mut values, &mut jac);
            assert_eq!(evaluations, chunks, "n = {n}");
            assert_eq!(values[0], parts.values[0]);
            for (g, r) in jac.iter().zip(&parts.grad_rows) {
                assert!((g - r).abs() < 1e-13, "n = {n}");
            }
        }
    }
}
