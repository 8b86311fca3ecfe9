//! Hamiltonians of the catalog systems ([`crate::systems`]), the Legendre transforms of their
//! Lagrangians written out in closed form.
//!
//! | system | `H(q, p)` | separable |
//! |---|---|---|
//! | [`HarmonicOscillator`] | `p²/2m + kq²/2` | yes |
//! | [`FreeFall`] | `p²/2m + mgq` | yes |
//! | [`Pendulum`] | `p²/(2ml²) − mgl cos q` | yes |
//! | [`Kepler`] | `½|p|² − μ/|q|` | yes |
//! | [`HenonHeiles`] | `½|p|² + ½(x² + y²) + λ(x²y − y³/3)` | yes |
//! | [`NBody`] | `Σ|pᵢ|²/2mᵢ − Σ_{i<j} G mᵢmⱼ/rᵢⱼ` | yes |
//! | [`DoublePendulum`] | `½pᵀM(θ)⁻¹p + V(θ)` | no (mass matrix depends on `θ₁ − θ₂`) |
//!
//! For the double pendulum `M = [[a, c], [c, b]]` with `a = (m₁+m₂)l₁²`, `b = m₂l₂²`,
//! `c = m₂l₁l₂ cos(θ₁−θ₂)`, so `½pᵀM⁻¹p = (b p₁² + a p₂² − 2c p₁p₂) / (2(ab − c²))` and
//! `ab − c² = m₂l₁²l₂²(m₁ + m₂ sin²(θ₁−θ₂))`.

use super::{Hamiltonian, Separable};
use crate::mechanics::Lagrangian;
use crate::scalar::Scalar;
use crate::systems::{
    DoublePendulum, FreeFall, HarmonicOscillator, HenonHeiles, Kepler, NBody, Pendulum,
};

fn half_square<S: Scalar>(p: &[S]) -> S {
    p.iter().fold(S::from(0.0), |acc, &x| acc + x * x) * 0.5
}

impl Separable for HarmonicOscillator {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        p[0] * p[0] * (0.5 / self.m)
    }
    fn potential<S: Scalar>(&self, _t: S, q: &[S]) -> S {
        q[0] * q[0] * (0.5 * self.k)
    }
}

impl Separable for FreeFall {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        p[0] * p[0] * (0.5 / self.m)
    }
    fn potential<S: Scalar>(&self, _t: S, q: &[S]) -> S {
        q[0] * (self.m * self.g)
    }
}

impl Separable for Pendulum {
    fn dof(&self) -> usize {
        1
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        p[0] * p[0] * (0.5 / (self.m * self.l * self.l))
    }
    fn potential<S: Scalar>(&self, _t: S, q: &[S]) -> S {
        -q[0].cos() * (self.m * self.g * self.l)
    }
}

impl Separable for Kepler {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        half_square(p)
    }
    fn potential<S: Scalar>(&self, _t: S, q: &[S]) -> S {
        -(q[0] * q[0] + q[1] * q[1]).sqrt().recip() * self.mu
    }
}

impl Separable for HenonHeiles {
    fn dof(&self) -> usize {
        2
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        half_square(p)
    }
    fn potential<S: Scalar>(&self, _t: S, q: &[S]) -> S {
        let (x, y) = (q[0], q[1]);
        (x * x + y * y) * 0.5 + (x * x * y - y * y * y * (1.0 / 3.0)) * self.lambda
    }
}

impl Separable for NBody {
    fn dof(&self) -> usize {
        3 * self.bodies()
    }
    fn kinetic<S: Scalar>(&self, p: &[S]) -> S {
        self.masses
            .iter()
            .enumerate()
            .fold(S::from(0.0), |acc, (i, m)| {
                acc + half_square(&p[3 * i..3 * i + 3]) / *m
            })
    }
    fn potential<S: Scalar>(&self, t: S, q: &[S]) -> S {
        // L = T(v) − V(q) with T(0) = 0, so V(q) = −L(t, q, 0).
        let rest: Vec<S> = vec![S::from(0.0); q.len()];
        -self.lagrangian(t, q, &rest)
    }
}

impl Hamiltonian for DoublePendulum {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<S: Scalar>(&self, _t: S, q: &[S], p: &[S]) -> S {
        let (m1, m2, l1, l2, g) = (self.m1, self.m2, self.l1, self.l2, self.g);
        let (a, b) = ((m1 + m2) * l1 * l1, m2 * l2 * l2);
        let (s, c) = ((q[0] - q[1]).sin(), (q[0] - q[1]).cos() * (m2 * l1 * l2));
        let det = (s * s * m2 + m1) * (m2 * l1 * l1 * l2 * l2);
        let kinetic = (p[0] * p[0] * b + p[1] * p[1] * a - c * p[0] * p[1] * 2.0) / (det * 2.0);
        let potential = q[0].cos() * (-(m1 + m2) * g * l1) - q[1].cos() * (m2 * g * l2);
        kinetic + potential
    }
}
