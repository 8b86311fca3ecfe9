//! Quadrature rules on `[0, 1]`: Gauss–Legendre and Gauss–Lobatto nodes and weights.
//!
//! * Gauss–Legendre with `r` points: nodes the roots of the Legendre polynomial `P_r` (mapped
//!   from `[−1, 1]`), weights `w = 2 / ((1 − x²) P_r'(x)²)`; exact for polynomials of degree
//!   `2r − 1`.
//! * Gauss–Lobatto with `r ≥ 2` points: the end points and the roots of `P_{r−1}'`, weights
//!   `w = 2 / (r(r−1) P_{r−1}(x)²)`; exact for degree `2r − 3`.
//!
//! (Abramowitz & Stegun 25.4.29–32; Hairer–Lubich–Wanner, *Geometric Numerical Integration*
//! §II.1.) Nodes are found by Newton's method on the three-term recurrence
//! `(k+1)P_{k+1} = (2k+1) x P_k − k P_{k−1}`, started from the Chebyshev-like guesses
//! `cos(π(i − ¼)/(r + ½))` (Gauss) and `cos(π i/(r − 1))` (Lobatto), and iterated until the update
//! is at round-off; symmetry is imposed by computing one half and mirroring it. This reaches
//! every node and weight to about one ulp. The `gauss-quad` crate was considered
//! and not used: it has no Lobatto rule (it would have to be assembled from its Gauss–Jacobi(1,1)
//! rule, whose Golub–Welsch eigenvalue nodes are accurate only to a few ulp times the matrix
//! norm, with the Lobatto weights still needing the formula above), and the Newton iteration
//! is twenty lines with no dependency.

use crate::error::Error;
use crate::error::InputError;

/// Which family of quadrature nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum QuadratureFamily {
    /// Gauss–Legendre: interior nodes, exact to degree `2r − 1`.
    Gauss,
    /// Gauss–Lobatto: includes both end points, exact to degree `2r − 3`.
    Lobatto,
}

impl QuadratureFamily {
    /// `"gauss"` or `"lobatto"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Gauss => "gauss",
            Self::Lobatto => "lobatto",
        }
    }

    /// Smallest number of points the family has.
    pub fn min_points(self) -> usize {
        match self {
            Self::Gauss => 1,
            Self::Lobatto => 2,
        }
    }

    /// Highest polynomial degree integrated exactly with `points` nodes.
    pub fn exact_degree(self, points: usize) -> usize {
        match self {
            Self::Gauss => 2 * points - 1,
            Self::Lobatto => 2 * points - 3,
        }
    }
}

/// Largest number of quadrature points accepted.
pub const MAX_POINTS: usize = 24;

/// Nodes `c_i ∈ [0, 1]` (increasing) and weights `b_i` (summing to 1) of a quadrature rule
/// `∫₀¹ f ≈ Σ b_i f(c_i)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Quadrature {
    /// The family.
    pub family: QuadratureFamily,
    /// Nodes in `[0, 1]`, increasing.
    pub nodes: Vec<f64>,
    /// Weights, summing to 1.
    pub weights: Vec<f64>,
}

impl Quadrature {
    /// The rule with `points` nodes of `family`.
    ///
    /// # Errors
    /// [`crate::error::InputError::InvalidQuadrature`] if `points` is below the family's minimum
    /// (1 for Gauss, 2 for Lobatto) or above [`MAX_POINTS`].
    pub fn new(family: QuadratureFamily, points: usize) -> Result<Self, Error> {
        if points < family.min_points() || points > MAX_POINTS {
            return Err(Error::Input(InputError::InvalidQuadrature {
                family: family.name(),
                points,
                valid: format!("{} ≤ points ≤ {MAX_POINTS}", family.min_points()),
            }));
        }
        let (x, w) = match family {
            QuadratureFamily::Gauss => gauss_legendre(points),
            QuadratureFamily::Lobatto => gauss_lobatto(points),
        };
        // Map [−1, 1] → [0, 1]; the rule is reflected so nodes increase.
        let nodes = x.iter().rev().map(|x| 0.5 + 0.5 * x).collect();
        let weights = w.iter().rev().map(|w| 0.5 * w).collect();
        Ok(Self {
            family,
            nodes,
            weights,
        })
    }

    /// Gauss–Legendre with `points` nodes.
    pub fn gauss(points: usize) -> Result<Self, Error> {
        Self::new(QuadratureFamily::Gauss, points)
    }

    /// Gauss–Lobatto with `points` nodes.
    pub fn lobatto(points: usize) -> Result<Self, Error> {
        Self::new(QuadratureFamily::Lobatto, points)
    }

    /// Number of nodes.
    pub fn points(&self) -> usize {
        self.nodes.len()
    }

    /// Highest polynomial degree integrated exactly.
    pub fn exact_degree(&self) -> usize {
        self.family.exact_degree(self.points())
    }
}

/// `(P_k(x), P_k'(x))` by the three-term recurrence (`|x| < 1` for the derivative).
fn legendre(k: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if k == 0 {
        return (1.0, 0.0);
    }
    for j in 1..k {
        let j = j as f64;
        let p2 = ((2.0 * j + 1.0) * x * p1 - j * p0) / (j + 1.0);
        p0 = p1;
        p1 = p2;
    }
    let dp = k as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, dp)
}

/// Newton's method from `x` on `f`, returning `(f, f')` at the converged point; stops when the
/// update is at round-off (at most 100 iterations, far more than the 3–6 needed).
fn newton_root(mut x: f64, f: impl Fn(f64) -> (f64, f64)) -> f64 {
    for _ in 0..100 {
        let (value, slope) = f(x);
        let dx = value / slope;
        x -= dx;
        if dx.abs() <= 2.0 * f64::EPSILON * x.abs().max(1e-3) {
            break;
        }
    }
    x
}

/// Nodes (decreasing, in `[−1, 1]`) and weights of Gauss–Legendre with `r` points.
fn gauss_legendre(r: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; r];
    let mut w = vec![0.0; r];
    for i in 0..r.div_ceil(2) {
        let guess = (std::f64::consts::PI * (i as f64 + 0.75) / (r as f64 + 0.5)).cos();
        let xi = if 2 * i + 1 == r {
            0.0
        } else {
            newton_root(guess, |x| legendre(r, x))
        };
        let (_, dp) = legendre(r, xi);
        let wi = 2.0 / ((1.0 - xi * xi) * dp * dp);
        (x[i], x[r - 1 - i]) = (xi, -xi);
        (w[i], w[r - 1 - i]) = (wi, wi);
    }
    (x, w)
}

/// Nodes (decreasing, in `[−1, 1]`) and weights of Gauss–Lobatto with `r ≥ 2` points.
fn gauss_lobatto(r: usize) -> (Vec<f64>, Vec<f64>) {
    let n = r - 1; // interior nodes are the roots of P_n'
    let nn = (n * (n + 1)) as f64;
    let mut x = vec![0.0; r];
    let mut w = vec![0.0; r];
    (x[0], x[n]) = (1.0, -1.0);
    (w[0], w[n]) = (2.0 / nn, 2.0 / nn);
    for i in 1..r.div_ceil(2) {
        let guess = (std::f64::consts::PI * i as f64 / n as f64).cos();
        // P_n'' from Legendre's equation: (1 − x²) P'' = 2x P' − n(n+1) P.
        let derivative = |x: f64| {
            let (p, dp) = legendre(n, x);
            (dp, (2.0 * x * dp - nn * p) / (1.0 - x * x))
        };
        let xi = if 2 * i == n {
            0.0
        } else {
            newton_root(guess, derivative)
        };
        let (p, _) = legendre(n, xi);
        let wi = 2.0 / (nn * p * p);
        (x[i], x[n - i]) = (xi, -xi);
        (w[i], w[n - i]) = (wi, wi);
    }
    (x, w)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫₀¹ t^k dt = 1/(k+1)`.
    fn moment(q: &Quadrature, k: i32) -> f64 {
        q.nodes
            .iter()
            .zip(&q.weights)
            .map(|(c, b)| b * c.powi(k))
            .sum()
    }

    #[test]
    fn rules_integrate_polynomials_up_to_their_degree() {
        for family in [QuadratureFamily::Gauss, QuadratureFamily::Lobatto] {
            for r in family.min_points()..=12 {
                let q = Quadrature::new(family, r).unwrap();
                for k in 0..=q.exact_degree() as i32 {
                    let err = moment(&q, k) - 1.0 / (k as f64 + 1.0);
                    assert!(err.abs() < 4e-16, "{family:?} r={r} k={k}: {err:e}");
                }
                let k = q.exact_degree() as i32 + 1;
                if r <= 5 {
                    assert!((moment(&q, k) - 1.0 / (k as f64 + 1.0)).abs() > 1e-10);
                }
                assert!(q.nodes.windows(2).all(|w| w[0] < w[1]));
            }
        }
    }

    #[test]
    fn known_nodes() {
        let g2 = Quadrature::gauss(2).unwrap();
        let c = 3.0_f64.sqrt() / 6.0;
        assert!((g2.nodes[0] - (0.5 - c)).abs() < 1e-16);
        let l3 = Quadrature::lobatto(3).unwrap();
        assert_eq!(l3.nodes, vec![0.0, 0.5, 1.0]);
        assert!((l3.weights[1] - 2.0 / 3.0).abs() < 2e-16);
        let l4 = Quadrature::lobatto(4).unwrap();
        assert!((l4.nodes[1] - (0.5 - 0.5 / 5.0_f64.sqrt())).abs() < 1e-16);
        assert!(Quadrature::lobatto(1).is_err());
        assert!(Quadrature::gauss(0).is_err());
    }
}
