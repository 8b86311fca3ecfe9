//! Small dense linear algebra for the Newton step: LU with partial pivoting, in place.
//!
//! The Newton systems of a variational step are small (`n·s + d` unknowns) and solved millions of
//! times, so they are factored in caller-owned buffers with no allocation. Textbook Doolittle
//! elimination with row pivoting (Golub & Van Loan, *Matrix Computations*, Alg. 3.4.1).
//! Large or sparse systems belong to faer, not here.

/// An LU factorisation `P A = L U` stored in place (row-major, unit lower triangle implicit).
#[derive(Debug, Clone, Default)]
pub struct Lu {
    n: usize,
    lu: Vec<f64>,
    perm: Vec<usize>,
}

/// The factorisation met a pivot that is zero relative to the matrix scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingularMatrix {
    /// Column at which elimination stopped.
    pub column: usize,
    /// The pivot found there.
    pub pivot: f64,
}

/// Relative pivot threshold below which a matrix is treated as singular.
pub(crate) const PIVOT_TOLERANCE: f64 = 1e-13;

impl Lu {
    /// An empty factorisation; call [`Lu::factor`] before solving.
    pub fn new() -> Self {
        Self::default()
    }

    /// Dimension of the factored matrix.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Factors the `n × n` row-major matrix `a` (copied; `a` is left untouched).
    pub fn factor(&mut self, a: &[f64], n: usize) -> Result<(), SingularMatrix> {
        debug_assert_eq!(a.len(), n * n);
        self.n = n;
        self.lu.clear();
        self.lu.extend_from_slice(a);
        self.perm.clear();
        self.perm.extend(0..n);
        let scale = a.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        if !scale.is_finite() {
            return Err(SingularMatrix {
                column: 0,
                pivot: scale,
            });
        }
        for k in 0..n {
            self.eliminate_column(k, scale)?;
        }
        Ok(())
    }

    fn eliminate_column(&mut self, k: usize, scale: f64) -> Result<(), SingularMatrix> {
        let n = self.n;
        let (p, pivot) =
            (k..n)
                .map(|i| (i, self.lu[i * n + k]))
                .fold((k, 0.0_f64), |best, (i, v)| {
                    if v.abs() > best.1.abs() { (i, v) } else { best }
                });
        if pivot.abs().is_nan() || pivot.abs() <= PIVOT_TOLERANCE * scale {
            return Err(SingularMatrix { column: k, pivot });
        }
        if p != k {
            for j in 0..n {
                self.lu.swap(k * n + j, p * n + j);
            }
            self.perm.swap(k, p);
        }
        for i in k + 1..n {
            let factor = self.lu[i * n + k] / pivot;
            self.lu[i * n + k] = factor;
            if factor != 0.0 {
                for j in k + 1..n {
                    self.lu[i * n + j] -= factor * self.lu[k * n + j];
                }
            }
        }
        Ok(())
    }

    /// Solves `A x = b` in place (`b` becomes `x`), using `scratch` of length `n`.
    pub fn solve(&self, b: &mut [f64], scratch: &mut Vec<f64>) {
        let n = self.n;
        scratch.clear();
        scratch.extend(self.perm.iter().map(|&i| b[i]));
        for i in 0..n {
            let row = &self.lu[i * n..i * n + i];
            let s: f64 = row.iter().zip(&scratch[..i]).map(|(l, y)| l * y).sum();
            scratch[i] -= s;
        }
        for i in (0..n).rev() {
            let row = &self.lu[i * n + i + 1..(i + 1) * n];
            let s: f64 = row.iter().zip(&scratch[i + 1..]).map(|(u, x)| u * x).sum();
            scratch[i] = (scratch[i] - s) / self.lu[i * n + i];
        }
        b.copy_from_slice(scratch);
    }

    /// The smallest pivot magnitude of the factorisation (a cheap conditioning hint).
    pub fn min_pivot(&self) -> f64 {
        (0..self.n)
            .map(|i| self.lu[i * self.n + i].abs())
            .fold(f64::INFINITY, f64::min)
    }
}

/// Solves `A x = b` in place by Gaussian elimination with partial pivoting, destroying `a`
/// (row-major n × n); `b` becomes `x`. For a Jacobian used once this avoids the copy and the
/// permutation bookkeeping of [`Lu`].
#[inline]
pub fn solve_in_place(a: &mut [f64], b: &mut [f64], n: usize) -> Result<(), SingularMatrix> {
    // The sizes of the small kernels and projections as compile-time constants: the same
    // operations, unrolled.
    match n {
        2 => eliminate(a, b, 2),
        3 => eliminate(a, b, 3),
        4 => eliminate(a, b, 4),
        _ => eliminate(a, b, n),
    }
}

/// [`solve_in_place`] for a size known at compile time (the small kernels): the same
/// operations in the same order, so the same bits, with the loops unrolled by the compiler.
#[inline(always)]
pub fn solve_fixed<const N: usize>(
    a: &mut [[f64; N]; N],
    b: &mut [f64; N],
) -> Result<(), SingularMatrix> {
    eliminate(a.as_flattened_mut(), b, N)
}

/// Gaussian elimination with partial pivoting (the body of [`solve_in_place`]).
#[inline(always)]
fn eliminate(a: &mut [f64], b: &mut [f64], n: usize) -> Result<(), SingularMatrix> {
    if n == 1 {
        return if a[0].abs() > 0.0 && a[0].is_finite() {
            b[0] /= a[0];
            Ok(())
        } else {
            Err(SingularMatrix {
                column: 0,
                pivot: a[0],
            })
        };
    }
    let scale = max_norm(a);
    for k in 0..n {
        let p = (k..n).fold(k, |best, i| {
            if a[i * n + k].abs() > a[best * n + k].abs() {
                i
            } else {
                best
            }
        });
        let pivot = a[p * n + k];
        if pivot.abs().is_nan() || pivot.abs() <= PIVOT_TOLERANCE * scale {
            return Err(SingularMatrix { column: k, pivot });
        }
        if p != k {
            for j in k..n {
                a.swap(k * n + j, p * n + j);
            }
            b.swap(k, p);
        }
        for i in k + 1..n {
            let factor = a[i * n + k] / pivot;
            if factor != 0.0 {
                for j in k + 1..n {
                    a[i * n + j] -= factor * a[k * n + j];
                }
                b[i] -= factor * b[k];
            }
        }
    }
    for i in (0..n).rev() {
        let s: f64 = (i + 1..n).map(|j| a[i * n + j] * b[j]).sum();
        b[i] = (b[i] - s) / a[i * n + i];
    }
    Ok(())
}

/// `max(a, b)`, or NaN if either is NaN: the fold of a maximum that must not skip a NaN
/// (`f64::max` returns the other argument, so a NaN defect or residual would look like 0).
#[inline]
pub fn max_or_nan(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Max-norm of a vector; NaN if any entry is NaN (`f64::max` alone would skip it, and a NaN
/// residual would then look converged).
#[inline]
pub fn max_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| {
        if m.is_nan() || v.is_nan() {
            f64::NAN
        } else {
            m.max(v.abs())
        }
    })
}

/// Index of entry `(i, j)`, `i ≤ j`, of a symmetric `n × n` matrix stored as its upper
/// triangle row by row (`(0, 0), (0, 1), …, (0, n − 1), (1, 1), …`: `n(n + 1)/2` values).
#[inline(always)]
pub(crate) const fn packed_index(n: usize, i: usize, j: usize) -> usize {
    i * (2 * n - i + 1) / 2 + (j - i)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_pivoting_system() {
        // The (0,0) entry is zero, so row pivoting is required.
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let x = [1.0, -2.0, 0.5];
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|j| a[i * 3 + j] * x[j]).sum())
            .collect();
        let mut lu = Lu::new();
        lu.factor(&a, 3).unwrap();
        lu.solve(&mut b, &mut Vec::new());
        for (bi, xi) in b.iter().zip(x) {
            assert!((bi - xi).abs() < 1e-15);
        }
    }

    #[test]
    fn in_place_solve_matches_lu() {
        let a = [0.0, 2.0, 1.0, 1.0, 1.0, 0.0, 3.0, 0.0, 1.0];
        let mut b = [1.0, 2.0, 3.0];
        let mut expected = b;
        let mut lu = Lu::new();
        lu.factor(&a, 3).unwrap();
        lu.solve(&mut expected, &mut Vec::new());
        solve_in_place(&mut a.clone(), &mut b, 3).unwrap();
        for (x, y) in b.iter().zip(expected) {
            assert!((x - y).abs() < 1e-15);
        }
        assert!(solve_in_place(&mut [0.0], &mut [1.0], 1).is_err());
    }

    /// The unrolled sizes (fixed arrays, and the run-time sizes 2–4 dispatched to constants)
    /// give the bits of the elimination with a size known only at run time (`black_box` keeps
    /// the compiler from folding it into a constant), pivoting included.
    #[test]
    fn fixed_size_solves_are_bit_identical_to_the_generic_one() {
        fn check<const N: usize>() {
            // Non-symmetric, with the largest entry of the first column below the diagonal.
            let a: [[f64; N]; N] = std::array::from_fn(|i| {
                std::array::from_fn(|j| {
                    ((i * 7 + j * 3) % 5) as f64 * 0.37 + 1.0 / (1.0 + (i + 2 * j) as f64)
                })
            });
            let b: [f64; N] = std::array::from_fn(|i| (i as f64 + 0.3).sin());
            let mut generic_a = a.as_flattened().to_vec();
            let mut generic_b = b;
            eliminate(&mut generic_a, &mut generic_b, std::hint::black_box(N)).unwrap();
            let (mut fixed_a, mut fixed_b) = (a, b);
            solve_fixed(&mut fixed_a, &mut fixed_b).unwrap();
            let (mut dispatched_a, mut dispatched_b) = (a.as_flattened().to_vec(), b);
            solve_in_place(&mut dispatched_a, &mut dispatched_b, N).unwrap();
            assert_eq!(
                fixed_b.map(f64::to_bits),
                generic_b.map(f64::to_bits),
                "N = {N}"
            );
            assert_eq!(
                dispatched_b.map(f64::to_bits),
                generic_b.map(f64::to_bits),
                "N = {N}"
            );
        }
        check::<2>();
        check::<3>();
        check::<4>();
        check::<5>();
        let mut singular = [[1.0, 2.0], [2.0, 4.0]];
        assert_eq!(
            solve_fixed(&mut singular, &mut [1.0, 1.0])
                .unwrap_err()
                .column,
            1
        );
    }

    #[test]
    fn reports_singular_matrix() {
        let a = [1.0, 2.0, 2.0, 4.0];
        let err = Lu::new().factor(&a, 2).unwrap_err();
        assert_eq!(err.column, 1);
    }

    /// The packed upper triangle's indices run 0, 1, 2, … in row order, for every size.
    #[test]
    fn packed_index_counts_the_upper_triangle_row_by_row() {
        for n in 1..=9 {
            let mut next = 0;
            for i in 0..n {
                for j in i..n {
                    assert_eq!(packed_index(n, i, j), next, "n = {n}, ({i}, {j})");
                    next += 1;
                }
            }
            assert_eq!(next, n * (n + 1) / 2);
        }
    }
}
