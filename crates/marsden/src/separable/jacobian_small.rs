//! The separable step Jacobian for small systems: sizes known at compile time.
//!
//! The formula is that of the parent module ([`super::jacobian`], [MW01] §1.5 by the implicit
//! function theorem):
//!
//! ```text
//!     A = M/h + h Σ w_i c_i (1 − c_i) H_i,     B = h Σ w_i (1 − c_i) H_i,
//!     C = h Σ w_i c_i H_i,                     K = M/h − h Σ w_i c_i² H_i,
//!     Y = A⁻¹ [−B | I],
//!     ∂q_{k+1}/∂(q_k, p_k) = [I | 0] + Y,      ∂p_{k+1}/∂(q_k, p_k) = K Y − [C | 0],
//! ```
//!
//! with `A`, `B`, `C`, `K` and the LU factors of `A` in stack arrays of size `N ≤ 4` instead of
//! band storage. The factorisation repeats the band LU with partial pivoting of
//! [`crate::numerics::banded`] operation for operation (Golub & Van Loan, *Matrix
//! Computations*, 4th ed., §4.3.5: the same pivots, the same updates restricted to the same
//! band), and every sum is formed in the parent's order, so both give the same bits (test
//! below). `∇²V` still comes through the band storage that [`Lagrangian::potential_hessian`]
//! fills.
//!
//! [MW01]: crate#references

use super::step::{Mass, node};
use crate::mechanics::Lagrangian;
use crate::numerics::banded::Banded;
use crate::numerics::dense::{PIVOT_TOLERANCE, max_norm};

/// What a step Jacobian is taken from: the Lagrangian, the rule's nodes `(c_i, w_i)`, the step
/// `(t₀, h)`, its start `q_k` and converged offset `Δ`, and the half-bandwidth of `∇²V`.
pub(super) struct StepData<'a, L> {
    pub l: &'a L,
    pub nodes: &'a [(f64, f64)],
    pub grid: (f64, f64),
    pub start: (&'a [f64], &'a [f64]),
    pub bandwidth: usize,
}

/// The step Jacobian for `n ≤ 4` into `jac` (row-major `2n × 2n`); `None` for larger systems,
/// `Some(Err(pivot))` if `A` is singular.
pub(super) fn step_jacobian_small<L: Lagrangian>(
    frame: &StepData<'_, L>,
    mass: &Mass,
    hess: &mut Banded,
    jac: &mut [f64],
) -> Option<Result<(), f64>> {
    Some(match frame.start.0.len() {
        1 => sized::<L, 1>(frame, mass, hess, jac),
        2 => sized::<L, 2>(frame, mass, hess, jac),
        3 => sized::<L, 3>(frame, mass, hess, jac),
        4 => sized::<L, 4>(frame, mass, hess, jac),
        _ => return None,
    })
}

/// `A`, `B`, `C`, `K` of the module documentation.
struct Blocks<const N: usize> {
    a: [[f64; N]; N],
    b: [[f64; N]; N],
    c: [[f64; N]; N],
    k: [[f64; N]; N],
}

/// The columns `max(0, i − b) … min(N − 1, i + b)` of row `i` inside a band of half-width `b`.
fn band<const N: usize>(i: usize, b: usize) -> std::ops::Range<usize> {
    i.saturating_sub(b)..(i + b + 1).min(N)
}

fn sized<L: Lagrangian, const N: usize>(
    frame: &StepData<'_, L>,
    mass: &Mass,
    hess: &mut Banded,
    jac: &mut [f64],
) -> Result<(), f64> {
    let b = frame.bandwidth.min(N - 1);
    let mut blocks = assemble::<L, N>(frame, mass, hess, b);
    let pivots = factor(&mut blocks.a, b)?;
    write_jacobian(&blocks, &pivots, b, jac);
    Ok(())
}

/// The blocks at the step's nodes, in the parent's order: `M/h`, then each node's terms.
fn assemble<L: Lagrangian, const N: usize>(
    frame: &StepData<'_, L>,
    mass: &Mass,
    hess: &mut Banded,
    b: usize,
) -> Blocks<N> {
    let (t0, h) = frame.grid;
    let (q0, delta) = frame.start;
    let mut blocks = Blocks {
        a: [[0.0; N]; N],
        b: [[0.0; N]; N],
        c: [[0.0; N]; N],
        k: [[0.0; N]; N],
    };
    for i in 0..N {
        for j in band::<N>(i, b) {
            let m = mass.entry(N, i, j) / h;
            blocks.a[i][j] = m;
            blocks.k[i][j] = m;
        }
    }
    let mut q = [0.0; N];
    for &(c, w) in frame.nodes {
        hess.reshape(N, b);
        node(c, q0, delta, &mut q);
        frame.l.potential_hessian(t0 + c * h, &q, hess);
        let hw = h * w;
        for i in 0..N {
            for j in band::<N>(i, b) {
                let hij = hess.get(i, j);
                blocks.a[i][j] += hw * c * (1.0 - c) * hij;
                blocks.b[i][j] += hw * (1.0 - c) * hij;
                blocks.c[i][j] += hw * c * hij;
                blocks.k[i][j] += -hw * c * c * hij;
            }
        }
    }
    blocks
}

/// `P A = L U` in place, as [`crate::numerics::banded::BandLu::factor`] does it for the band of
/// half-width `b`: the row exchanged at each step, or the offending pivot.
fn factor<const N: usize>(a: &mut [[f64; N]; N], b: usize) -> Result<[usize; N], f64> {
    let scale = max_norm(a.as_flattened());
    if !scale.is_finite() {
        return Err(scale);
    }
    let mut pivots = [0; N];
    for k in 0..N {
        let (last_row, last_col) = ((k + b).min(N - 1), (k + 2 * b).min(N - 1));
        let p =
            (k + 1..=last_row).fold(k, |p, i| if a[i][k].abs() > a[p][k].abs() { i } else { p });
        let pivot = a[p][k];
        if pivot.is_nan() || pivot.abs() <= PIVOT_TOLERANCE * scale {
            return Err(pivot);
        }
        pivots[k] = p;
        if p != k {
            let (upper, lower) = a.split_at_mut(p);
            upper[k][k..=last_col].swap_with_slice(&mut lower[0][k..=last_col]);
        }
        let (done, below) = a.split_at_mut(k + 1);
        let pivot_row = &done[k][k + 1..=last_col];
        for row in &mut below[..last_row - k] {
            let f = row[k] / pivot;
            row[k] = f;
            if f != 0.0 {
                for (x, y) in row[k + 1..=last_col].iter_mut().zip(pivot_row) {
                    *x -= f * y;
                }
            }
        }
    }
    Ok(pivots)
}

/// Solves `A x = r` in place with the factors of [`factor`], as
/// [`crate::numerics::banded::BandLu::solve`] does.
fn solve<const N: usize>(lu: &[[f64; N]; N], pivots: &[usize; N], b: usize, r: &mut [f64; N]) {
    for k in 0..N {
        r.swap(k, pivots[k]);
        let rk = r[k];
        for i in k + 1..=(k + b).min(N - 1) {
            r[i] -= lu[i][k] * rk;
        }
    }
    for i in (0..N).rev() {
        let mut s = r[i];
        for c in i + 1..=(i + 2 * b).min(N - 1) {
            s -= lu[i][c] * r[c];
        }
        r[i] = s / lu[i][i];
    }
}

/// Column `j` of `Y = A⁻¹[−B | I]`, then column `j` of `[[I | 0] + Y; K Y − [C | 0]]` into
/// `jac` (row-major `2N × 2N`), for every `j`.
fn write_jacobian<const N: usize>(
    blocks: &Blocks<N>,
    pivots: &[usize; N],
    b: usize,
    jac: &mut [f64],
) {
    let m = 2 * N;
    for j in 0..m {
        let mut col = [0.0; N];
        if j < N {
            for (i, x) in col.iter_mut().enumerate() {
                *x = -blocks.b[i][j];
            }
        } else {
            col[j - N] = 1.0;
        }
        solve(&blocks.a, pivots, b, &mut col);
        for a in 0..N {
            jac[a * m + j] = f64::from(u8::from(a == j)) + col[a];
            let through: f64 = band::<N>(a, b).map(|k| blocks.k[a][k] * col[k]).sum();
            let direct = if j < N { blocks.c[a][j] } else { 0.0 };
            jac[(N + a) * m + j] = through - direct;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::jacobian::{JacobianWorkspace, banded, step_data};
    use super::*;
    use crate::Scalar;
    use crate::mechanics::{MassMatrix, Structure};
    use crate::systems::{Chain, Kepler, Pendulum};

    /// `L = ½ vᵀ M v − V(t, q)` on three degrees of freedom with a dense `M` and a strongly
    /// coupled, indefinite, time-dependent `V`, so that a long step makes `A` pivot.
    struct Coupled;

    impl Lagrangian for Coupled {
        fn dof(&self) -> usize {
            3
        }
        fn lagrangian<S: Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
            let kinetic = v[0] * v[0] + v[0] * v[1] * 0.5 + v[1] * v[1] * 0.5 + v[2] * v[2];
            let potential = q[0].cos() * (t * 0.1).cos() + q[0] * q[1] * 6.0 - q[1] * q[2] * 2.0
                + q[2] * q[2] * q[2];
            kinetic - potential
        }
        fn structure(&self) -> Structure {
            Structure::Separable {
                mass: MassMatrix::Dense(vec![2.0, 0.5, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 2.0]),
            }
        }
    }

    /// `L = ½ v² + ½ κ q²`: the midpoint step's `A = 1/h − hκ/4` is exactly zero at `h = ½`,
    /// `κ = 16`.
    struct Unstable;

    impl Lagrangian for Unstable {
        fn dof(&self) -> usize {
            1
        }
        fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
            v[0] * v[0] * 0.5 + q[0] * q[0] * 8.0
        }
        fn structure(&self) -> Structure {
            Structure::Separable {
                mass: MassMatrix::Diagonal(vec![1.0]),
            }
        }
    }

    const MIDPOINT: &[(f64, f64)] = &[(0.5, 1.0)];
    const TRAPEZOID: &[(f64, f64)] = &[(0.0, 0.5), (1.0, 0.5)];
    const ALPHA: &[(f64, f64)] = &[(0.3, 1.0)];
    const SYMMETRIZED: &[(f64, f64)] = &[(0.2, 0.5), (0.8, 0.5)];

    /// The stack-array Jacobian and the band one of the same step, as bits (or the pivot).
    fn both<L: Lagrangian>(
        l: &L,
        nodes: &[(f64, f64)],
        grid: (f64, f64),
        start: (&[f64], &[f64]),
    ) -> [Result<Vec<u64>, u64>; 2] {
        let n = start.0.len();
        let mut ws = JacobianWorkspace::default();
        let data = step_data(l, nodes, grid, start, &mut ws).expect("separable");
        let mut small = vec![f64::NAN; 4 * n * n];
        let mut band = vec![f64::NAN; 4 * n * n];
        let mass = ws.mass.clone().flatten().expect("separable");
        let got = step_jacobian_small(&data, &mass, &mut ws.hess, &mut small).expect("n ≤ 4");
        let reference = banded(&data, &mut band, &mut ws);
        let bits = |r: Result<(), f64>, jac: Vec<f64>| match r {
            Ok(()) => Ok(jac.into_iter().map(f64::to_bits).collect()),
            Err(pivot) => Err(pivot.to_bits()),
        };
        [bits(got, small), bits(reference, band)]
    }

    /// Every rule's nodes at a few steps of `l`: the same bits.
    fn check<L: Lagrangian>(name: &str, l: &L, q0: &[f64], h: f64) {
        let n = q0.len();
        for (r, nodes) in [MIDPOINT, TRAPEZOID, ALPHA, SYMMETRIZED].iter().enumerate() {
            for s in 0..5 {
                let delta: Vec<f64> = (0..n)
                    .map(|i| h * (0.3 + 0.7 * (1.9 * (i + 3 * s) as f64).sin()))
                    .collect();
                let [small, band] = both(l, nodes, (0.1 * s as f64, h), (q0, &delta));
                assert!(small.is_ok(), "{name}, rule {r}, step {s}: {small:?}");
                assert_eq!(small, band, "{name}, rule {r}, step {s}");
            }
        }
    }

    #[test]
    fn small_step_jacobian_is_the_band_one_bit_for_bit() {
        check("pendulum", &Pendulum::default(), &[1.2], 0.1);
        check("kepler", &Kepler::default(), &[0.4, 0.0], 0.01);
        let chain = |n| Chain {
            alpha: 0.25,
            ..Chain::new(n)
        };
        check("chain of 3 (band 1)", &chain(3), &[0.1, -0.2, 0.3], 0.05);
        check(
            "chain of 4 (band 1)",
            &chain(4),
            &[0.1, -0.2, 0.3, 0.05],
            0.05,
        );
        check("dense mass, long step", &Coupled, &[0.4, -0.3, 0.2], 4.0);
    }

    /// The dense-mass case exchanges rows, so the pivoting is compared, not only the diagonal
    /// path.
    #[test]
    fn long_coupled_step_pivots() {
        let mut ws = JacobianWorkspace::default();
        let (q0, delta) = ([0.4, -0.3, 0.2], [0.5, 0.1, -0.2]);
        let data = step_data(&Coupled, MIDPOINT, (0.0, 4.0), (&q0, &delta), &mut ws);
        let data = data.expect("separable");
        let mass = ws.mass.clone().flatten().expect("separable");
        let blocks = assemble::<Coupled, 3>(&data, &mass, &mut ws.hess, 2);
        let mut a = blocks.a;
        let pivots = factor(&mut a, 2).expect("regular");
        assert_ne!(pivots, [0, 1, 2]);
    }

    /// A singular `A` is reported with the same pivot by both.
    #[test]
    fn singular_step_matrix_gives_the_same_pivot() {
        let [small, band] = both(&Unstable, MIDPOINT, (0.0, 0.5), (&[0.3], &[0.1]));
        assert_eq!(small, Err(0.0_f64.to_bits()));
        assert_eq!(small, band);
    }
}
