//! The path inequalities of one step as a function of its local unknowns
//! `w = (q_k, u_k, Q_1 … Q_{s−1}, q_{k+1})` (the same block as [`super::step::StepFunction`]):
//!
//! ```text
//!     g(t_k + τ_i h, q(τ_i), q̇(τ_i), u_{k,i}) ≤ 0,     i = 1 … σ,
//! ```
//!
//! with `q(τ_i)` and `q̇(τ_i)` read off the step's control points ([`PathPoints`]): the secant
//! at the midpoint for one control value per step, the rule's polynomial at its nodes for
//! stage values. A state constraint `g(q) ≤ 0` on a smooth arc is then met to `O(h²)` between
//! the points (the interpolation error), like the simple bounds on the nodes.

use marsden::Scalar;
use marsden::numerics::ad::MultiFunction;

use crate::model::PathConstraint;
use crate::stages::PathPoints;

/// Step `k`'s path inequalities: outputs `σ n_g` values, point by point.
pub struct PathFunction<'a, G> {
    /// The inequalities `g`.
    pub path: &'a G,
    /// Where they are imposed.
    pub points: &'a PathPoints,
    /// Start of the step.
    pub t0: f64,
    /// Step size.
    pub h: f64,
    /// Degrees of freedom `n`.
    pub n: usize,
    /// Number of controls `m`.
    pub m: usize,
}

impl<G> PathFunction<'_, G> {
    fn control_points(&self) -> usize {
        self.points.position.len() / self.points.times.len()
    }
}

impl<G: PathConstraint> MultiFunction for PathFunction<'_, G> {
    fn inputs(&self) -> usize {
        let sigma = self.points.times.len();
        self.control_points() * self.n + sigma * self.m
    }
    fn outputs(&self) -> usize {
        self.points.times.len() * self.path.count()
    }
    fn eval<S: Scalar>(&self, w: &[S], out: &mut [S]) {
        let (n, m, ng) = (self.n, self.m, self.path.count());
        let points = self.control_points();
        let sigma = self.points.times.len();
        let (q0, rest) = w.split_at(n);
        let (u, later) = rest.split_at(sigma * m);
        // Control point j: q_k for j = 0, then the inner points and q_{k+1}.
        let point = |j: usize, a: usize| {
            if j == 0 {
                q0[a]
            } else {
                later[(j - 1) * n + a]
            }
        };
        let zero = S::from(0.0);
        let (mut q, mut v) = (vec![zero; n], vec![zero; n]);
        for (i, &tau) in self.points.times.iter().enumerate() {
            let weights = i * points..(i + 1) * points;
            let position = &self.points.position[weights.clone()];
            let rate = &self.points.rate[weights];
            for a in 0..n {
                q[a] = (0..points).fold(zero, |s, j| s + point(j, a) * position[j]);
                v[a] = (0..points).fold(zero, |s, j| s + point(j, a) * rate[j]) * (1.0 / self.h);
            }
            let t = S::from(self.t0 + tau * self.h);
            let ui = &u[i * m..(i + 1) * m];
            self.path
                .eval(t, &q, &v, ui, &mut out[i * ng..(i + 1) * ng]);
        }
    }
}
