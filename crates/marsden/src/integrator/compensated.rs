//! Compensated summation of the state update (Kahan summation; [HLW06] §VIII.5).
//!
//! A step adds a small increment to a large state: `q_{k+1} = q_k + Δ_k`. Rounding each sum
//! loses up to half an ulp of `q`, and over 10⁵ steps these losses add up; when the step divides
//! a period they repeat every orbit and add up *linearly* (Kepler, gauss-4: `|ΔL|` grows to
//! 1.6e-11, the energy error tenfold). Compensated summation carries the rounding error of each
//! sum into the next increment:
//!
//! ```text
//! e ← e + δ;   y_new ← y + e;   e ← e + (y − y_new)
//! ```
//!
//! For `q` the increment is the offset `Δ = Q_s − Q₀` the step solves for. For `p` the step
//! returns `p_{k+1} = ∂L_d/∂Q_s + f_s` itself, a quantity of the size of `p` with its own
//! rounding error; the increment has to be computed as such. Summing the step equations (the
//! residual at `Q₀` and the internal-stage equations, all zero at the solution) gives
//!
//! ```text
//! p_{k+1} − p_k = Σ_j ∂L_d/∂Q_j + Σ_j f_j = ∇_{Q₀} L_d(Q₀; Δ₁ … Δ_s) + Σ_j f_j,
//! ```
//!
//! the derivative of the action in offset form along `Q₀` with the offsets fixed (translating
//! all control points at once) — one first-order AD gradient of `L_d` per step, a number of
//! the size of the increment, so its rounding error is that of the increment, not of `p`.
//! Test `kepler_high_order.rs`: over 10⁵ steps gauss-4 keeps `|ΔL|` at 1.4e-15 instead of
//! 1.6e-11, lobatto-3 at 1.9e-14 instead of 1.1e-12.
//!
//! Constrained steps are not compensated: their momenta come out of the multipliers and the
//! momentum projection, not from the sum above.
//!
//! [HLW06]: crate#references

use crate::discrete::legendre::ActionAndForces;
use crate::discrete::{DiscreteAction, DiscreteForce};
use crate::mechanics::State;
use crate::numerics::ad::{self, MultiFunction};

/// The carried rounding errors of `q` and `p`, and the state they belong to.
#[derive(Debug, Clone, Default)]
pub(crate) struct Compensation {
    /// Whether steps are compensated at all.
    pub enabled: bool,
    q_error: Vec<f64>,
    p_error: Vec<f64>,
    /// The state the last compensated update produced: the errors apply to it only.
    last_q: Vec<f64>,
    last_p: Vec<f64>,
    /// `(Q₀, offsets)`, the input of the momentum increment's gradient.
    point: Vec<f64>,
    /// Scratch of [`momentum_increment`], and the increment `δp`.
    scratch: IncrementScratch,
    increment: Vec<f64>,
}

/// The rounding errors compensated summation carries to the next step, and the state they
/// belong to.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct CompensationCarry {
    q_error: Vec<f64>,
    p_error: Vec<f64>,
    last_q: Vec<f64>,
    last_p: Vec<f64>,
}

impl Compensation {
    /// What is carried to the next step, as plain numbers (a checkpoint).
    pub fn carried(&self) -> CompensationCarry {
        CompensationCarry {
            q_error: self.q_error.clone(),
            p_error: self.p_error.clone(),
            last_q: self.last_q.clone(),
            last_p: self.last_p.clone(),
        }
    }

    /// Takes back what [`Compensation::carried`] gave.
    pub fn restore_carried(&mut self, carry: &CompensationCarry) {
        self.q_error.clone_from(&carry.q_error);
        self.p_error.clone_from(&carry.p_error);
        self.last_q.clone_from(&carry.last_q);
        self.last_p.clone_from(&carry.last_p);
    }

    /// Adds `Δ` to `q` and `δp` (from [`momentum_increment`]) to `p` of the step of size `h`
    /// from `state` with compensated summation (`state.t` is left to the caller). The carried
    /// errors are dropped first if `(q, p)` is not the state the last update left (the caller
    /// started elsewhere or changed the state between steps).
    pub fn update<A: DiscreteAction, F: DiscreteForce>(
        &mut self,
        action: &A,
        force: &F,
        state: &mut State,
        h: f64,
        offsets: &[f64],
    ) {
        let (t0, q, p) = (state.t, state.q.as_mut_slice(), state.p.as_mut_slice());
        let n = q.len();
        if self.last_q != q || self.last_p != p {
            self.q_error.clear();
            self.q_error.resize(n, 0.0);
            self.p_error.clear();
            self.p_error.resize(n, 0.0);
        }
        self.point.clear();
        self.point.extend_from_slice(q);
        self.point.extend_from_slice(offsets);
        self.increment.resize(n, 0.0);
        momentum_increment(
            action,
            force,
            t0,
            h,
            &self.point,
            &mut self.scratch,
            &mut self.increment,
        );
        let delta = &offsets[offsets.len() - n..];
        kahan_add(q, &mut self.q_error, delta);
        kahan_add(p, &mut self.p_error, &self.increment);
        self.last_q.clear();
        self.last_q.extend_from_slice(q);
        self.last_p.clear();
        self.last_p.extend_from_slice(p);
    }
}

/// `y ← y + δ` element-wise, carrying the rounding error in `error`.
fn kahan_add(y: &mut [f64], error: &mut [f64], delta: &[f64]) {
    for ((y, e), d) in y.iter_mut().zip(error.iter_mut()).zip(delta) {
        let old = *y;
        *e += d;
        *y = old + *e;
        *e += old - *y;
    }
}

/// Values and Jacobian of [`ActionAndForces`] for [`momentum_increment`].
#[derive(Debug, Clone, Default)]
pub(crate) struct IncrementScratch {
    values: Vec<f64>,
    jacobian: Vec<f64>,
}

/// `δp = ∇_{Q₀} L_d(Q₀; offsets) + Σ_j f_j`, the momentum increment of a solved step, at
/// `point = (Q₀, offsets)` (module doc): one first-order AD pass over `(L_d, f₀ … f_s)` with
/// the `n` columns of `Q₀` seeded; row 0 of the Jacobian is the gradient, the force values are
/// summed over the control points.
pub(crate) fn momentum_increment<A: DiscreteAction, F: DiscreteForce>(
    action: &A,
    force: &F,
    t0: f64,
    h: f64,
    point: &[f64],
    scratch: &mut IncrementScratch,
    increment: &mut [f64],
) {
    let n = increment.len();
    let f = ActionAndForces::new(action, force, t0, h);
    scratch.values.resize(f.outputs(), 0.0);
    scratch.jacobian.resize(f.outputs() * n, 0.0);
    ad::jacobian(&f, point, 0..n, &mut scratch.values, &mut scratch.jacobian);
    increment.copy_from_slice(&scratch.jacobian[..n]);
    for point_force in scratch.values[1..].chunks_exact(n) {
        increment
            .iter_mut()
            .zip(point_force)
            .for_each(|(d, f)| *d += f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discrete::rules::Midpoint;
    use crate::discrete::rules::Rule;
    use crate::mechanics::NoForce;
    use crate::systems::Kepler;

    /// The increment equals `p_{k+1} − p_k` of a midpoint step of Kepler's problem solved to
    /// round-off: they differ by the step's residual and the rounding of the difference, a few
    /// ulps of `p`.
    #[test]
    fn increment_matches_the_solved_step() {
        let tight = crate::numerics::newton::NewtonOptions {
            residual_tolerance: 1e-15,
            ..crate::numerics::newton::NewtonOptions::default()
        };
        let mut integrator =
            crate::integrator::Integrator::new(Midpoint.discretize(Kepler::default()))
                .with_options(tight)
                .unwrap();
        let mut state = crate::mechanics::State {
            t: 0.0,
            q: vec![0.4, 0.0],
            p: vec![0.0, 2.0],
        };
        let before = state.clone();
        integrator.step(&mut state, 0.01).unwrap();
        let offsets: Vec<f64> = state.q.iter().zip(&before.q).map(|(a, b)| a - b).collect();
        let point: Vec<f64> = before.q.iter().chain(&offsets).copied().collect();
        let mut increment = [0.0; 2];
        momentum_increment(
            integrator.action(),
            &NoForce,
            0.0,
            0.01,
            &point,
            &mut IncrementScratch::default(),
            &mut increment,
        );
        for i in 0..2 {
            let difference = state.p[i] - before.p[i];
            assert!(
                (increment[i] - difference).abs() <= 8.0 * f64::EPSILON * before.p[1].abs(),
                "{increment:?} against {difference}"
            );
        }
    }

    /// Compensated sums of many small increments keep the exact total; plain sums do not.
    #[test]
    fn kahan_sum_keeps_the_small_increments() {
        let (mut plain, mut compensated, mut error) = ([1.0], [1.0], [0.0]);
        for _ in 0..1_000_000 {
            plain[0] += 1e-16;
            kahan_add(&mut compensated, &mut error, &[1e-16]);
        }
        assert_eq!(plain[0], 1.0);
        assert!(
            (compensated[0] - (1.0 + 1e-10)).abs() < 1e-15,
            "{}",
            compensated[0]
        );
    }
}
