//! Band matrices and their LU factorisation with partial pivoting: the linear algebra of the
//! Newton step for large systems whose potential is a sum of local terms.
//!
//! A square matrix with half-bandwidth `b` has `a_ij = 0` for `|i − j| > b`. Gaussian
//! elimination with partial pivoting keeps `L` within `b` subdiagonals and lets `U` grow to
//! `2b` superdiagonals (Golub & Van Loan, *Matrix Computations*, 4th ed., §4.3.5, the scheme of
//! LAPACK's `dgbtrf`), so factoring costs `O(n b²)` and solving `O(n b)` — linear in `n` for a
//! chain (`b = 1`).
//!
//! Why not faer's sparse LU? For a banded matrix the band *is* the sparsity
//! pattern: no symbolic analysis, no index arrays, no indirect addressing, and the storage is
//! reused from step to step without allocation. A general sparse LU pays for all three and
//! would only win for patterns that are not bands (2-D meshes), which no catalog system has.

use crate::numerics::dense::SingularMatrix;

/// Relative pivot threshold below which the matrix is treated as singular (as [`crate::numerics::dense`]).
const PIVOT_TOLERANCE: f64 = 1e-13;

/// A square `n × n` matrix with half-bandwidth `b`, stored by rows: row `i` holds columns
/// `i − b … i + b` (entries outside `0 … n−1` are unused zeros).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Banded {
    n: usize,
    b: usize,
    data: Vec<f64>,
}

impl Banded {
    /// The zero `n × n` matrix with half-bandwidth `b` (clamped to `n − 1`).
    pub fn new(n: usize, b: usize) -> Self {
        let b = b.min(n.saturating_sub(1));
        Self {
            n,
            b,
            data: vec![0.0; n * (2 * b + 1)],
        }
    }

    /// Re-shapes to `n × n` with half-bandwidth `b` (reusing the storage) and zeroes it.
    #[inline]
    pub fn reshape(&mut self, n: usize, b: usize) {
        self.n = n;
        self.b = b.min(n.saturating_sub(1));
        self.data.clear();
        self.data.resize(n * (2 * self.b + 1), 0.0);
    }

    /// Dimension `n`.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Half-bandwidth `b`.
    pub fn bandwidth(&self) -> usize {
        self.b
    }

    /// Sets every entry to zero.
    pub fn fill_zero(&mut self) {
        self.data.fill(0.0);
    }

    /// The columns of row `i` inside the band: `max(0, i − b) … min(n − 1, i + b)`.
    pub fn columns(&self, i: usize) -> std::ops::Range<usize> {
        i.saturating_sub(self.b)..(i + self.b + 1).min(self.n)
    }

    #[inline]
    fn index(&self, i: usize, j: usize) -> usize {
        i * (2 * self.b + 1) + (j + self.b - i)
    }

    /// Entry `(i, j)` (zero outside the band).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i.abs_diff(j) > self.b || i >= self.n || j >= self.n {
            0.0
        } else {
            self.data[self.index(i, j)]
        }
    }

    /// Sets entry `(i, j)`, which must lie inside the band (ignored otherwise).
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, value: f64) {
        if i.abs_diff(j) <= self.b && i < self.n && j < self.n {
            let k = self.index(i, j);
            self.data[k] = value;
        }
    }

    /// Adds to entry `(i, j)`, which must lie inside the band (ignored otherwise).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        if i.abs_diff(j) <= self.b && i < self.n && j < self.n {
            let k = self.index(i, j);
            self.data[k] += value;
        }
    }

    /// Largest entry magnitude (NaN if any entry is NaN).
    pub fn max_abs(&self) -> f64 {
        crate::numerics::dense::max_norm(&self.data)
    }
}

/// LU factors `P A = L U` of a [`Banded`] matrix, by rows of width `3b + 1` (row `i` holds
/// columns `i − b … i + 2b`: the band plus the fill of pivoting).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BandLu {
    n: usize,
    b: usize,
    lu: Vec<f64>,
    /// Row exchanged with row `k` at elimination step `k`.
    pivots: Vec<usize>,
}

impl BandLu {
    /// An empty factorisation; call [`BandLu::factor`] before solving.
    pub fn new() -> Self {
        Self::default()
    }

    /// Dimension of the factored matrix.
    pub fn dim(&self) -> usize {
        self.n
    }

    #[inline]
    fn at(&self, i: usize, c: usize) -> usize {
        i * (3 * self.b + 1) + (c + self.b - i)
    }

    /// Factors `a` (copied; storage is reused between calls).
    pub fn factor(&mut self, a: &Banded) -> Result<(), SingularMatrix> {
        let (n, b) = (a.n, a.b);
        self.n = n;
        self.b = b;
        let w = 3 * b + 1;
        self.lu.clear();
        self.lu.resize(n * w, 0.0);
        for i in 0..n {
            let row = &a.data[i * (2 * b + 1)..(i + 1) * (2 * b + 1)];
            self.lu[i * w..i * w + 2 * b + 1].copy_from_slice(row);
        }
        self.pivots.clear();
        self.pivots.resize(n, 0);
        let scale = a.max_abs();
        if !scale.is_finite() {
            return Err(SingularMatrix {
                column: 0,
                pivot: scale,
            });
        }
        for k in 0..n {
            self.eliminate(k, scale)?;
        }
        Ok(())
    }

    /// Step `k` of the elimination: pivot search in column `k`, row exchange, update.
    fn eliminate(&mut self, k: usize, scale: f64) -> Result<(), SingularMatrix> {
        let (n, b) = (self.n, self.b);
        let last_row = (k + b).min(n - 1);
        let last_col = (k + 2 * b).min(n - 1);
        let mut p = k;
        for i in k + 1..=last_row {
            if self.lu[self.at(i, k)].abs() > self.lu[self.at(p, k)].abs() {
                p = i;
            }
        }
        let pivot = self.lu[self.at(p, k)];
        if pivot.is_nan() || pivot.abs() <= PIVOT_TOLERANCE * scale {
            return Err(SingularMatrix { column: k, pivot });
        }
        self.pivots[k] = p;
        if p != k {
            for c in k..=last_col {
                let (x, y) = (self.at(k, c), self.at(p, c));
                self.lu.swap(x, y);
            }
        }
        for i in k + 1..=last_row {
            let ik = self.at(i, k);
            let factor = self.lu[ik] / pivot;
            self.lu[ik] = factor;
            if factor != 0.0 {
                let (row_i, row_k) = (self.at(i, k + 1), self.at(k, k + 1));
                let len = last_col - k;
                for c in 0..len {
                    self.lu[row_i + c] -= factor * self.lu[row_k + c];
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = r` in place (`r` becomes `x`).
    pub fn solve(&self, r: &mut [f64]) {
        let (n, b) = (self.n, self.b);
        for k in 0..n {
            let p = self.pivots[k];
            if p != k {
                r.swap(k, p);
            }
            let rk = r[k];
            let last = (k + b).min(n.saturating_sub(1));
            for (i, ri) in r.iter_mut().enumerate().take(last + 1).skip(k + 1) {
                *ri -= self.lu[self.at(i, k)] * rk;
            }
        }
        for i in (0..n).rev() {
            let last = (i + 2 * b).min(n - 1);
            let start = self.at(i, i);
            let mut s = r[i];
            for (offset, c) in (i + 1..=last).enumerate() {
                s -= self.lu[start + 1 + offset] * r[c];
            }
            r[i] = s / self.lu[start];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::dense::Lu;

    /// A pentadiagonal matrix whose first diagonal entry is zero (pivoting is required).
    fn sample(n: usize) -> Banded {
        let mut a = Banded::new(n, 2);
        for i in 0..n {
            for j in a.columns(i) {
                let v = ((i * 7 + j * 3) % 11) as f64 - 5.0;
                a.set(i, j, if i == j { v + 0.5 } else { v });
            }
        }
        a.set(0, 0, 0.0);
        a
    }

    #[test]
    fn band_lu_matches_dense_lu() {
        let n = 9;
        let a = sample(n);
        let dense: Vec<f64> = (0..n * n).map(|k| a.get(k / n, k % n)).collect();
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut expected = rhs.clone();
        let mut lu = Lu::new();
        lu.factor(&dense, n).unwrap();
        lu.solve(&mut expected, &mut Vec::new());
        let mut band = BandLu::new();
        band.factor(&a).unwrap();
        let mut x = rhs;
        band.solve(&mut x);
        for (a, b) in x.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-12 * b.abs().max(1.0), "{a} vs {b}");
        }
    }

    #[test]
    fn singular_band_is_reported() {
        let mut a = Banded::new(3, 1);
        a.set(0, 0, 1.0);
        a.set(0, 1, 1.0);
        a.set(1, 0, 1.0);
        a.set(1, 1, 1.0);
        a.set(2, 2, 1.0);
        assert_eq!(BandLu::new().factor(&a).unwrap_err().column, 1);
    }
}
