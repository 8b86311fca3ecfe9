//! A rigid body made of point masses held at fixed mutual distances (holonomic constraints):
//!
//! ```text
//! L = Σᵢ ½ mᵢ |vᵢ|²,      φ_c(q) = ½(|qᵢ − qⱼ|² − d_c²) = 0  for every link c = (i, j, d_c).
//! ```
//!
//! With no external field the system is invariant under translations and rotations of all
//! particles (and so are the constraints, `Dφ·ξ_Q = 0`), so total linear and angular momentum are
//! conserved — also by the SHAKE discretisation, whose constraint impulse `h Dφ(q_k)ᵀλ_k` has
//! no component along `ξ_Q(q_k)` (see `diagnostics::noether`). Coordinates `x₁ y₁ z₁ x₂ …`.
//! Four non-coplanar points with all six links form a rigid (and not over-constrained) body.

use crate::mechanics::{Constraint, Lagrangian};
use crate::scalar::Scalar;

/// Point masses with distance constraints (a free rigid body when the links make it rigid).
#[derive(Debug, Clone, PartialEq)]
pub struct PointRigidBody {
    /// Masses (one per particle).
    pub masses: Vec<f64>,
    /// Links `(i, j, d)`: particles `i` and `j` stay at distance `d`.
    pub links: Vec<(usize, usize, f64)>,
}

impl PointRigidBody {
    /// Particles of the given masses at `positions` (length `3k`), linked pairwise (every pair,
    /// at its current distance).
    pub fn linked(masses: Vec<f64>, positions: &[f64]) -> Self {
        let k = masses.len();
        let mut links = Vec::with_capacity(k * (k.saturating_sub(1)) / 2);
        for i in 0..k {
            for j in i + 1..k {
                let d2: f64 = (0..3)
                    .map(|a| (positions[3 * i + a] - positions[3 * j + a]).powi(2))
                    .sum();
                links.push((i, j, d2.sqrt()));
            }
        }
        Self { masses, links }
    }

    /// An irregular tetrahedron of masses 1, 2, 3, 4 (all six links) and its positions.
    pub fn tetrahedron() -> (Self, Vec<f64>) {
        let q = vec![
            1.0, 0.0, 0.0, //
            0.0, 1.5, 0.0, //
            0.0, 0.0, 0.8, //
            -0.5, -0.4, -0.3,
        ];
        (Self::linked(vec![1.0, 2.0, 3.0, 4.0], &q), q)
    }

    /// Number of particles.
    pub fn bodies(&self) -> usize {
        self.masses.len()
    }

    /// Rigid motion velocities `vᵢ = V + ω × (qᵢ − c)`, with `c` the centre of mass (these satisfy
    /// the velocity constraints `Dφ(q)·v = 0`).
    pub fn rigid_velocities(&self, q: &[f64], velocity: [f64; 3], omega: [f64; 3]) -> Vec<f64> {
        let total: f64 = self.masses.iter().sum();
        let mut c = [0.0; 3];
        for (i, m) in self.masses.iter().enumerate() {
            (0..3).for_each(|a| c[a] += m * q[3 * i + a] / total);
        }
        let mut v = vec![0.0; q.len()];
        for i in 0..self.bodies() {
            let r = [q[3 * i] - c[0], q[3 * i + 1] - c[1], q[3 * i + 2] - c[2]];
            v[3 * i] = velocity[0] + omega[1] * r[2] - omega[2] * r[1];
            v[3 * i + 1] = velocity[1] + omega[2] * r[0] - omega[0] * r[2];
            v[3 * i + 2] = velocity[2] + omega[0] * r[1] - omega[1] * r[0];
        }
        v
    }

    /// Kinetic energy `Σ |pᵢ|²/2mᵢ`.
    pub fn energy(&self, p: &[f64]) -> f64 {
        self.masses
            .iter()
            .zip(p.chunks_exact(3))
            .map(|(m, pi)| pi.iter().map(|x| x * x).sum::<f64>() / (2.0 * m))
            .sum()
    }
}

impl Lagrangian for PointRigidBody {
    fn dof(&self) -> usize {
        3 * self.bodies()
    }
    fn lagrangian<S: Scalar>(&self, _t: S, _q: &[S], v: &[S]) -> S {
        let mut kinetic = S::from(0.0);
        for (i, m) in self.masses.iter().enumerate() {
            for a in 0..3 {
                kinetic += v[3 * i + a] * v[3 * i + a] * (0.5 * m);
            }
        }
        kinetic
    }
}

impl Constraint for PointRigidBody {
    fn count(&self) -> usize {
        self.links.len()
    }
    fn constraint<S: Scalar>(&self, q: &[S], out: &mut [S]) {
        for (c, &(i, j, d)) in self.links.iter().enumerate() {
            let mut r2 = S::from(-d * d);
            for a in 0..3 {
                let x = q[3 * i + a] - q[3 * j + a];
                r2 += x * x;
            }
            out[c] = r2 * 0.5;
        }
    }
}
