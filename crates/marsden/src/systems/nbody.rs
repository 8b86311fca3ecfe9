//! Gravitational N-body problem in three dimensions with Plummer softening:
//!
//! ```text
//! L = Σᵢ ½ mᵢ |vᵢ|² + Σ_{i<j} G mᵢ mⱼ / √(|qᵢ − qⱼ|² + ε²).
//! ```
//!
//! Coordinates are `(x₁, y₁, z₁, x₂, …)`. This is the general (AD) form; large N belongs to the
//! explicit fast path.

use crate::{Lagrangian, MassMatrix, Scalar, Structure};

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
}
