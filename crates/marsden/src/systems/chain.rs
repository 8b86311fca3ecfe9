//! A chain of `n` particles joined by nonlinear springs, ends fixed: the Fermi–Pasta–Ulam–Tsingou
//! α-β chain,
//!
//! ```text
//! L = Σᵢ ½ m q̇ᵢ² − Σ_{j=0}^{n} φ(q_j − q_{j−1}),   q_{−1} = q_n = 0,
//! φ(r) = ½ k r² + (α/3) r³ + (β/4) r⁴
//! ```
//!
//! (Fermi, Pasta, Ulam, Tsingou, Los Alamos report LA-1940, 1955; Gallavotti (ed.), *The
//! Fermi–Pasta–Ulam Problem*, Springer 2008). The potential is a sum of nearest-neighbour
//! terms, so `∇²V` is tridiagonal: the chain declares [`Lagrangian::potential_bandwidth`]
//! `= 1` and writes `∇V` and `∇²V` by hand (each bond's `φ′`, `φ″` once), and the midpoint
//! step's Newton system `M/h + (h/4)∇²V` is assembled and solved in `O(n)`
//! ([`crate::separable::alpha`], [`crate::numerics::banded`]). The AD form of `L` below remains the reference
//! (tests compare the hand-written derivatives with it).

use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::numerics::banded::Banded;
use crate::scalar::Scalar;

/// An FPU-type chain of `n` equal masses with fixed ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Chain {
    /// Number of moving particles.
    pub n: usize,
    /// Particle mass (default 1).
    pub m: f64,
    /// Linear spring constant `k` (default 1).
    pub k: f64,
    /// Cubic coefficient `α` of the bond potential (default 0).
    pub alpha: f64,
    /// Quartic coefficient `β` of the bond potential (default 1: the FPU-β chain).
    pub beta: f64,
}

impl Chain {
    /// `n` unit masses with `k = 1`, `α = 0`, `β = 1`.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            m: 1.0,
            k: 1.0,
            alpha: 0.0,
            beta: 1.0,
        }
    }

    /// `φ(r)`, over any scalar.
    #[inline]
    fn bond<S: Scalar>(&self, r: S) -> S {
        let r2 = r * r;
        r2 * (0.5 * self.k) + r2 * r * (self.alpha / 3.0) + r2 * r2 * (0.25 * self.beta)
    }

    /// `φ′(r)` and `φ″(r)`.
    #[inline(always)]
    fn bond_derivatives(&self, r: f64) -> (f64, f64) {
        let d1 = r * (self.k + r * (self.alpha + r * self.beta));
        let d2 = self.k + r * (2.0 * self.alpha + r * (3.0 * self.beta));
        (d1, d2)
    }

    /// The stretch of bond `j = 0 … n` (between particles `j − 1` and `j`, walls at both ends).
    #[inline(always)]
    fn stretch(q: &[f64], j: usize) -> f64 {
        let right = q.get(j).copied().unwrap_or(0.0);
        let left = if j == 0 { 0.0 } else { q[j - 1] };
        right - left
    }

    /// Energy `Σ pᵢ²/2m + V(q)`.
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        let kinetic: f64 = p.iter().map(|x| x * x).sum::<f64>() * (0.5 / self.m);
        kinetic
            + (0..=q.len())
                .map(|j| self.bond(Self::stretch(q, j)))
                .sum::<f64>()
    }
}

impl Lagrangian for Chain {
    fn dof(&self) -> usize {
        self.n
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let zero = S::from(0.0);
        let mut kinetic = zero;
        for vi in v {
            kinetic += *vi * *vi;
        }
        let mut potential = zero;
        for j in 0..=q.len() {
            let right = q.get(j).copied().unwrap_or(zero);
            let left = if j == 0 { zero } else { q[j - 1] };
            potential += self.bond(right - left);
        }
        kinetic * (0.5 * self.m) - potential
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![self.m; self.n]),
        }
    }
    /// `∂V/∂qᵢ = φ′(q_i − q_{i−1}) − φ′(q_{i+1} − q_i)`: each bond's force once (into `scratch`),
    /// then differences.
    #[inline]
    fn potential_gradient(&self, _t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        let n = q.len();
        scratch.resize(n + 1, 0.0);
        for (j, f) in scratch.iter_mut().enumerate() {
            *f = self.bond_derivatives(Self::stretch(q, j)).0;
        }
        for (i, g) in grad.iter_mut().enumerate() {
            *g = scratch[i] - scratch[i + 1];
        }
    }
    fn potential_bandwidth(&self) -> Option<usize> {
        Some(1)
    }
    /// Tridiagonal: `∂²V/∂qᵢ² = φ″(rᵢ) + φ″(r_{i+1})`, `∂²V/∂qᵢ∂q_{i+1} = −φ″(r_{i+1})`.
    #[inline]
    fn potential_hessian(&self, _t: f64, q: &[f64], hess: &mut Banded) {
        let n = q.len();
        let mut left = self.bond_derivatives(Self::stretch(q, 0)).1;
        for i in 0..n {
            let right = self.bond_derivatives(Self::stretch(q, i + 1)).1;
            hess.set(i, i, left + right);
            if i + 1 < n {
                hess.set(i, i + 1, -right);
                hess.set(i + 1, i, -right);
            }
            left = right;
        }
    }
}
