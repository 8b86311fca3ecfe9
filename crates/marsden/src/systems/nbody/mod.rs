//! Gravitational N-body problem in three dimensions with Plummer softening:
//!
//! ```text
//! L = Σᵢ ½ mᵢ |vᵢ|² + Σ_{i<j} G mᵢ mⱼ / √(|qᵢ − qⱼ|² + ε²).
//! ```
//!
//! Coordinates are `(x₁, y₁, z₁, x₂, …)`. `L` below is the general (AD) form and the reference;
//! the structure-aware paths use the hand-written gradient of [`gravity`] (direct summation,
//! structure of arrays, vectorised), which tests compare with AD. Initial data can be read from
//! the benchmark file format ([`file`](mod@file)).

pub mod file;
pub mod gravity;

pub use file::{NBodyData, NBodyFileError, load, parse as parse_file};

use crate::error::Error;
use crate::error::InputError;
use crate::mechanics::{Lagrangian, MassMatrix, Structure};
use crate::scalar::Scalar;

/// N point masses under mutual gravitation.
#[derive(Debug, Clone, PartialEq)]
pub struct NBody {
    /// Masses (one per body).
    pub masses: Vec<f64>,
    /// Gravitational constant (default 1).
    pub g: f64,
    /// Softening length ε (default 0).
    pub softening: f64,
}

impl NBody {
    /// Bodies of the given masses with `G = 1`, no softening.
    pub fn new(masses: Vec<f64>) -> Self {
        Self {
            masses,
            g: 1.0,
            softening: 0.0,
        }
    }

    /// Bodies of the given masses with gravitational constant `g` and Plummer softening length
    /// `softening`, checked: at least one body, every mass positive and finite, `g` finite
    /// and positive, `softening` finite and non-negative (else
    /// [`crate::error::InputError::InvalidOption`] naming `masses`, `G` or `softening`).
    ///
    /// ```
    /// use marsden::systems::NBody;
    ///
    /// let system = NBody::with_parameters(vec![1.0, 1e-3], 1.0, 0.01)?;
    /// assert_eq!(system.bodies(), 2);
    /// assert!(NBody::with_parameters(vec![1.0, -1.0], 1.0, 0.0).is_err());
    /// # Ok::<(), marsden::Error>(())
    /// ```
    pub fn with_parameters(masses: Vec<f64>, g: f64, softening: f64) -> Result<Self, Error> {
        let invalid = |name, value, reason| {
            Error::Input(InputError::InvalidOption {
                name,
                value,
                reason,
            })
        };
        if masses.is_empty() {
            return Err(invalid("masses", 0.0, "at least one body is needed"));
        }
        if let Some(&m) = masses.iter().find(|m| !(m.is_finite() && **m > 0.0)) {
            return Err(invalid(
                "masses",
                m,
                "every mass must be positive and finite",
            ));
        }
        if !(g.is_finite() && g > 0.0) {
            return Err(invalid("G", g, "must be positive and finite"));
        }
        if !(softening.is_finite() && softening >= 0.0) {
            return Err(invalid("softening", softening, "must be finite and ≥ 0"));
        }
        Ok(Self {
            masses,
            g,
            softening,
        })
    }

    /// Number of bodies.
    pub fn bodies(&self) -> usize {
        self.masses.len()
    }

    /// Energy `Σ |pᵢ|²/2mᵢ − Σ_{i<j} G mᵢ mⱼ / rᵢⱼ`.
    pub fn energy(&self, q: &[f64], p: &[f64]) -> f64 {
        let mut e = 0.0;
        for (i, m) in self.masses.iter().enumerate() {
            let pi = &p[3 * i..3 * i + 3];
            e += 0.5 * pi.iter().map(|x| x * x).sum::<f64>() / m;
        }
        e - self.interaction(q)
    }

    /// Total linear momentum `Σ pᵢ`.
    pub fn linear_momentum(p: &[f64]) -> [f64; 3] {
        let mut total = [0.0; 3];
        for body in p.chunks_exact(3) {
            (0..3).for_each(|a| total[a] += body[a]);
        }
        total
    }

    /// Total angular momentum `Σ qᵢ × pᵢ`.
    pub fn angular_momentum(q: &[f64], p: &[f64]) -> [f64; 3] {
        let mut l = [0.0; 3];
        for (qi, pi) in q.chunks_exact(3).zip(p.chunks_exact(3)) {
            l[0] += qi[1] * pi[2] - qi[2] * pi[1];
            l[1] += qi[2] * pi[0] - qi[0] * pi[2];
            l[2] += qi[0] * pi[1] - qi[1] * pi[0];
        }
        l
    }

    fn interaction<S: Scalar>(&self, q: &[S]) -> S {
        let eps2 = self.softening * self.softening;
        let mut u = S::from(0.0);
        for i in 0..self.bodies() {
            for j in i + 1..self.bodies() {
                let mut r2 = S::from(eps2);
                for a in 0..3 {
                    let d = q[3 * i + a] - q[3 * j + a];
                    r2 += d * d;
                }
                u += r2.sqrt().recip() * (self.g * self.masses[i] * self.masses[j]);
            }
        }
        u
    }
}

impl Lagrangian for NBody {
    fn dof(&self) -> usize {
        3 * self.bodies()
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let mut kinetic = S::from(0.0);
        for (i, m) in self.masses.iter().enumerate() {
            for a in 0..3 {
                kinetic += v[3 * i + a] * v[3 * i + a] * (0.5 * m);
            }
        }
        kinetic + self.interaction(q)
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(self.masses.iter().flat_map(|&m| [m, m, m]).collect()),
        }
    }
    /// Direct summation ([`gravity::gradient`]), `O(N²)` with one pass over all pairs.
    #[inline]
    fn potential_gradient(&self, _t: f64, q: &[f64], grad: &mut [f64], scratch: &mut Vec<f64>) {
        gravity::gradient(self, q, grad, scratch);
    }
}
