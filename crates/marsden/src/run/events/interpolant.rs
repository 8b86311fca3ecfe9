//! The discrete trajectory between two of its states: the cubic Hermite interpolant of a step.
//!
//! A two-point rule gives `(q_k, p_k)` and `(q_{k+1}, p_{k+1})`; with the velocities
//! `v = FL⁻¹(q, p)` at both ends, the cubic Hermite interpolant in `θ = (t − t_k)/h ∈ [0, 1]`,
//!
//! ```text
//! q(θ) = q_k + (3θ² − 2θ³) Δ + h (θ − 2θ² + θ³) v_k + h (θ³ − θ²) v_{k+1},   Δ = q_{k+1} − q_k,
//! ```
//!
//! matches positions and velocities at both ends; its velocity is its own derivative,
//!
//! ```text
//! v(θ) = 6(θ − θ²) Δ/h + (1 − 4θ + 3θ²) v_k + (3θ² − 2θ) v_{k+1},
//! ```
//!
//! so `(q, v)` is a curve in the tangent bundle, and the momenta along it are its Legendre
//! transform `p(θ) = FL(q(θ), v(θ))`, equal to `p_k`, `p_{k+1}` at the ends. For data of a
//! smooth solution the interpolant's error inside the step is `O(h⁴)` in `q` (at most
//! `h⁴ max|q⁽⁴⁾|/384`, the remainder of Hermite interpolation) and `O(h³)` in `v` and `p`: for a
//! method of order `r ≤ 3` (`r ≤ 2` for events that read `v` or `p`) it is below the `O(h^r)`
//! error of the states themselves, so an event located on it is as accurate as the run.
//!
//! Why `p = FL(q, v)` rather than a Hermite interpolant of `p` with `ṗ = ∂L/∂q + f − Dφᵀλ`:
//! the detector sees the states of the run, not its forces or multipliers, and `FL` of the
//! interpolated tangent vector needs neither, costs one Legendre transform (`M v` for a
//! separable Lagrangian), and has the same `O(h³)` error as `v`; a linear interpolant of `p`
//! would have `O(h²)`, the trajectory's own error for the midpoint rule.

/// Two consecutive states of a run with their velocities.
#[derive(Debug, Clone, Copy)]
pub(super) struct HermiteStep<'a> {
    /// `t_k`.
    pub t0: f64,
    /// `t_{k+1} − t_k`.
    pub h: f64,
    /// `q_k`.
    pub q0: &'a [f64],
    /// `v_k`.
    pub v0: &'a [f64],
    /// `q_{k+1}`.
    pub q1: &'a [f64],
    /// `v_{k+1}`.
    pub v1: &'a [f64],
}

impl HermiteStep<'_> {
    /// `q(t)` and `v(t)` of the interpolant, written into `q` and `v`.
    pub(super) fn at(&self, t: f64, q: &mut [f64], v: &mut [f64]) {
        let h = self.h;
        let s = (t - self.t0) / h;
        let s2 = s * s;
        let s3 = s2 * s;
        // Hermite basis (θ = s): the weights of Δ, h v_k, h v_{k+1} and their derivatives.
        let (w_delta, w_v0, w_v1) = (3.0 * s2 - 2.0 * s3, s - 2.0 * s2 + s3, s3 - s2);
        let (dw_delta, dw_v0, dw_v1) =
            (6.0 * (s - s2), 1.0 - 4.0 * s + 3.0 * s2, 3.0 * s2 - 2.0 * s);
        for i in 0..q.len() {
            let delta = self.q1[i] - self.q0[i];
            q[i] = self.q0[i] + w_delta * delta + h * (w_v0 * self.v0[i] + w_v1 * self.v1[i]);
            v[i] = dw_delta * delta / h + dw_v0 * self.v0[i] + dw_v1 * self.v1[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cubic `q(t) = 1 + 2t − t² + 0.5t³` is reproduced exactly (to round-off) from its
    /// values and derivatives at the ends, with its derivative; a quartic's error is `O(h⁴)`.
    #[test]
    fn cubic_reproduced_quartic_to_fourth_order() {
        let cubic = |t: f64| 1.0 + 2.0 * t - t * t + 0.5 * t * t * t;
        let dcubic = |t: f64| 2.0 - 2.0 * t + 1.5 * t * t;
        let (t0, h) = (0.3, 0.7);
        let ends = ([cubic(t0)], [dcubic(t0)], [cubic(t0 + h)], [dcubic(t0 + h)]);
        let step = HermiteStep {
            t0,
            h,
            q0: &ends.0,
            v0: &ends.1,
            q1: &ends.2,
            v1: &ends.3,
        };
        let (mut q, mut v) = ([0.0], [0.0]);
        for j in 0..=10 {
            let t = t0 + h * j as f64 / 10.0;
            step.at(t, &mut q, &mut v);
            assert!((q[0] - cubic(t)).abs() < 1e-14, "q({t})");
            assert!((v[0] - dcubic(t)).abs() < 1e-14, "v({t})");
        }
        // t⁴: the error at mid-step is h⁴/16 exactly (the basis leaves t²(t − h)² · 1 out).
        let errors: Vec<f64> = [0.1f64, 0.05]
            .iter()
            .map(|&h| {
                let ends = ([0.0], [0.0], [h.powi(4)], [4.0 * h.powi(3)]);
                let step = HermiteStep {
                    t0: 0.0,
                    h,
                    q0: &ends.0,
                    v0: &ends.1,
                    q1: &ends.2,
                    v1: &ends.3,
                };
                step.at(0.5 * h, &mut q, &mut v);
                (q[0] - (0.5 * h).powi(4)).abs()
            })
            .collect();
        assert!((errors[0] - 0.1f64.powi(4) / 16.0).abs() < 1e-17);
        assert!((errors[0] / errors[1] - 16.0).abs() < 1e-9);
    }
}
