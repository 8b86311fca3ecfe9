//! Built-in group actions on systems of `k` particles in `ℝ^d` (coordinates `x₁ y₁ (z₁) x₂ …`).
//!
//! | action | group | generator of `e_a` on particle `i` | momentum map `J_H` |
//! |---|---|---|---|
//! | [`Translations`] | `(ℝ^d, +)`, diagonal | `e_a` | total linear momentum `Σᵢ pᵢ` |
//! | [`AxisRotation`] | `SO(2)` about an axis | `ω × qᵢ` (planar: `(−yᵢ, xᵢ)`) | `ω·Σᵢ qᵢ × pᵢ` |
//! | [`Rotations`] | `SO(3)`, diagonal | `ê_a qᵢ = e_a × qᵢ` (hat map) | total angular momentum `Σᵢ qᵢ × pᵢ` |
//!
//! Concept of the notes (MW01): *Examples* (`ℝ³` acting by translation, `SO(3)` acting by rotation). The hat map
//! `ω ↦ ω̂`, `ω̂ x = ω × x`, identifies `ℝ³ ≅ so(3)`; then `Ad_g ω = Rω` and `Ad*_{g⁻¹} μ = Rμ`
//! ([MR99] §9.2). All three actions are linear (affine), so the midpoint, trapezoid and α
//! discrete Lagrangians of an invariant `L` are invariant too ([conventions](crate#conventions)).
//!
//! [MR99]: crate#references

use super::{FiniteAction, GroupAction};
use crate::scalar::Scalar;

/// The hat map `ω ↦ ω̂` with `ω̂ x = ω × x` (row-major 3 × 3).
pub fn hat(w: [f64; 3]) -> [[f64; 3]; 3] {
    [[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]]
}

/// Rodrigues' formula: `exp(ω̂) = I + (sin θ/θ) ω̂ + ((1 − cos θ)/θ²) ω̂²`, `θ = |ω|`.
pub fn rotation_matrix(w: [f64; 3]) -> [[f64; 3]; 3] {
    let theta2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    let theta = theta2.sqrt();
    // Series below θ ~ 1e-4 keeps full precision (next terms are O(θ⁴)).
    let (a, b) = if theta < 1e-4 {
        (1.0 - theta2 / 6.0, 0.5 - theta2 / 24.0)
    } else {
        (theta.sin() / theta, (1.0 - theta.cos()) / theta2)
    };
    let k = hat(w);
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|l| k[i][l] * k[l][j]).sum();
            r[i][j] = f64::from(u8::from(i == j)) + a * k[i][j] + b * k2;
        }
    }
    r
}

fn rotate<S: Scalar>(r: &[[f64; 3]; 3], x: &[S], out: &mut [S]) {
    for i in 0..3 {
        out[i] = x[0] * r[i][0] + x[1] * r[i][1] + x[2] * r[i][2];
    }
}

/// Translations of `k` particles in `ℝ^d`, all by the same vector (the diagonal action of
/// `(ℝ^d, +)`): `Φ_a(q)ᵢ = qᵢ + a`. Momentum map: total linear momentum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Translations {
    /// Number of particles `k`.
    pub particles: usize,
    /// Dimension `d` of the space each particle moves in.
    pub dim: usize,
}

impl Translations {
    /// Translations of `particles` particles in `ℝ^dim`.
    pub fn new(particles: usize, dim: usize) -> Self {
        Self { particles, dim }
    }
}

impl GroupAction for Translations {
    fn name(&self) -> String {
        format!(
            "translations of {} particles in R^{}",
            self.particles, self.dim
        )
    }
    fn dof(&self) -> usize {
        self.particles * self.dim
    }
    fn algebra_dim(&self) -> usize {
        self.dim
    }
    fn generator<S: Scalar>(&self, a: usize, _q: &[S], out: &mut [S]) {
        for (j, o) in out.iter_mut().enumerate().take(self.dof()) {
            *o = S::from(if j % self.dim == a { 1.0 } else { 0.0 });
        }
    }
}

impl FiniteAction for Translations {
    fn act<S: Scalar>(&self, xi: &[f64], q: &[S], out: &mut [S]) {
        for j in 0..self.dof() {
            out[j] = q[j] + xi[j % self.dim];
        }
    }
    fn coadjoint(&self, _xi: &[f64], mu: &[f64], out: &mut [f64]) {
        // Abelian group: Ad* is the identity.
        out.copy_from_slice(mu);
    }
}

/// Rotations of `k` particles about one fixed axis through the origin (an `SO(2)` action):
/// in the plane (`d = 2`), `ξ_Q(qᵢ) = (−yᵢ, xᵢ)`; in space (`d = 3`), `ξ_Q(qᵢ) = ω × qᵢ` with `ω`
/// the unit axis. Momentum map: the angular momentum about the axis, `ω·Σᵢ qᵢ × pᵢ`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisRotation {
    /// Number of particles `k`.
    pub particles: usize,
    /// Dimension `d ∈ {2, 3}` of the space each particle moves in.
    pub dim: usize,
    /// Unit rotation axis (used for `d = 3`; `(0, 0, 1)` in the plane).
    pub axis: [f64; 3],
}

impl AxisRotation {
    /// Rotations in the plane of `particles` planar particles (the Kepler problem: `k = 1`).
    pub fn planar(particles: usize) -> Self {
        Self {
            particles,
            dim: 2,
            axis: [0.0, 0.0, 1.0],
        }
    }

    /// Rotations of `particles` particles in `ℝ³` about the vertical axis `z` (e.g. the
    /// spherical pendulum hanging from the origin).
    pub fn about_z(particles: usize) -> Self {
        Self {
            particles,
            dim: 3,
            axis: [0.0, 0.0, 1.0],
        }
    }

    /// Rotations of `particles` particles in `ℝ³` about `axis` (normalised here; a zero axis
    /// gives non-finite generators, reported by [`super::validate`]).
    pub fn about(particles: usize, axis: [f64; 3]) -> Self {
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        Self {
            particles,
            dim: 3,
            axis: axis.map(|x| x / norm),
        }
    }
}

impl GroupAction for AxisRotation {
    fn name(&self) -> String {
        if self.dim == 2 {
            format!("planar rotations SO(2) of {} particles", self.particles)
        } else {
            format!(
                "rotations SO(2) of {} particles about the axis {:?}",
                self.particles, self.axis
            )
        }
    }
    fn dof(&self) -> usize {
        self.particles * self.dim
    }
    fn algebra_dim(&self) -> usize {
        1
    }
    fn generator<S: Scalar>(&self, _a: usize, q: &[S], out: &mut [S]) {
        let w = self.axis;
        for i in 0..self.particles {
            if self.dim == 2 {
                out[2 * i] = -q[2 * i + 1];
                out[2 * i + 1] = q[2 * i];
            } else {
                let x = &q[3 * i..3 * i + 3];
                out[3 * i] = x[2] * w[1] - x[1] * w[2];
                out[3 * i + 1] = x[0] * w[2] - x[2] * w[0];
                out[3 * i + 2] = x[1] * w[0] - x[0] * w[1];
            }
        }
    }
}

impl FiniteAction for AxisRotation {
    fn act<S: Scalar>(&self, xi: &[f64], q: &[S], out: &mut [S]) {
        if self.dim == 2 {
            let (s, c) = xi[0].sin_cos();
            for i in 0..self.particles {
                let (x, y) = (q[2 * i], q[2 * i + 1]);
                out[2 * i] = x * c - y * s;
                out[2 * i + 1] = x * s + y * c;
            }
        } else {
            let r = rotation_matrix(self.axis.map(|a| a * xi[0]));
            for i in 0..self.particles {
                rotate(&r, &q[3 * i..3 * i + 3], &mut out[3 * i..3 * i + 3]);
            }
        }
    }
    fn coadjoint(&self, _xi: &[f64], mu: &[f64], out: &mut [f64]) {
        out.copy_from_slice(mu);
    }
}

/// The diagonal action of `SO(3)` on `k` particles in `ℝ³`, `Φ_R(q)ᵢ = R qᵢ`, with basis
/// generators from the hat map: `(e_a)_Q(q)ᵢ = ê_a qᵢ = e_a × qᵢ`. Momentum map: the total
/// angular momentum `Σᵢ qᵢ × pᵢ`; equivariant with `Ad*_{g⁻¹} μ = R μ`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rotations {
    /// Number of particles `k`.
    pub particles: usize,
}

impl Rotations {
    /// `SO(3)` acting on `particles` particles in `ℝ³`.
    pub fn new(particles: usize) -> Self {
        Self { particles }
    }
}

impl GroupAction for Rotations {
    fn name(&self) -> String {
        format!("rotations SO(3) of {} particles", self.particles)
    }
    fn dof(&self) -> usize {
        3 * self.particles
    }
    fn algebra_dim(&self) -> usize {
        3
    }
    fn generator<S: Scalar>(&self, a: usize, q: &[S], out: &mut [S]) {
        let zero = S::from(0.0);
        for i in 0..self.particles {
            let (x, y, z) = (q[3 * i], q[3 * i + 1], q[3 * i + 2]);
            let e = match a {
                0 => [zero, -z, y],
                1 => [z, zero, -x],
                _ => [-y, x, zero],
            };
            out[3 * i..3 * i + 3].copy_from_slice(&e);
        }
    }
}

impl FiniteAction for Rotations {
    fn act<S: Scalar>(&self, xi: &[f64], q: &[S], out: &mut [S]) {
        let r = rotation_matrix([xi[0], xi[1], xi[2]]);
        for i in 0..self.particles {
            rotate(&r, &q[3 * i..3 * i + 3], &mut out[3 * i..3 * i + 3]);
        }
    }
    fn coadjoint(&self, xi: &[f64], mu: &[f64], out: &mut [f64]) {
        let r = rotation_matrix([xi[0], xi[1], xi[2]]);
        rotate(&r, mu, out);
    }
}
