//! [`ControlTable`]: controls `u_0 … u_{N−1}` read from a table, piecewise constant per step
//! (`u_k` on `[t_k, t_{k+1})`), the time-dependent input of a `marsden run` whose forces use
//! `[system] controls` — so that the controls `marsden optimize` found can be fed back to the
//! integrator ([OJM11] §3: the optimal trajectory is a solution of the forced discrete
//! Euler–Lagrange equations with those controls).
//!
//! The forces are evaluated at a rule's quadrature times, so `u(t)` must tell the step from
//! the time: it does for rules whose quadrature nodes lie inside the step (midpoint,
//! `alpha-<a>` and `symmetrized-<a>` with `0 < a < 1`), not at a step's ends, where two
//! steps meet (trapezoid); the problem file check refuses those.
//!
//! [OJM11]: marsden#references

use marsden::Scalar;
use marsden::numerics::scratch::with_slice;

/// Controls per step on a uniform grid `t_k = t0 + k h`.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlTable {
    /// The grid's first time.
    pub t0: f64,
    /// The step.
    pub h: f64,
    /// `u_k`, one row per step, one value per declared control.
    pub rows: Vec<Vec<f64>>,
}

impl ControlTable {
    /// The number of controls.
    pub fn controls(&self) -> usize {
        self.rows.first().map_or(0, Vec::len)
    }

    /// `u(t) = u_k` for `t ∈ [t_k, t_{k+1})`, the first row before `t0`, the last after the
    /// table's end.
    pub fn at(&self, t: f64) -> &[f64] {
        let s = ((t - self.t0) / self.h).floor();
        let k = if s > 0.0 { s as usize } else { 0 };
        self.rows
            .get(k.min(self.rows.len().saturating_sub(1)))
            .map_or(&[], Vec::as_slice)
    }
}

/// Calls `body` with `[x₀ … x_{n−1}, y₀ … y_{n−1}, t, u(t)…]`: the inputs of a force whose
/// expressions read the controls after `[q, q̇, t]` (or `[q, p, t]`).
#[inline(always)]
pub fn with_controls<S: Scalar, R>(
    x: &[S],
    y: &[S],
    t: S,
    table: &ControlTable,
    body: impl FnOnce(&[S]) -> R,
) -> R {
    let n = x.len();
    let u = table.at(t.re());
    with_slice(2 * n + 1 + u.len(), t, |slots| {
        slots[..n].copy_from_slice(x);
        slots[n..2 * n].copy_from_slice(y);
        for (s, &ui) in slots[2 * n + 1..].iter_mut().zip(u) {
            *s = S::from(ui);
        }
        body(slots)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `u_k` on `[t_k, t_{k+1})`: the midpoint of step k reads row k, as do its ends' insides.
    #[test]
    fn reads_the_row_of_the_step() {
        let table = ControlTable {
            t0: 1.0,
            h: 0.5,
            rows: vec![vec![10.0], vec![20.0], vec![30.0]],
        };
        assert_eq!(table.at(1.25), [10.0]);
        assert_eq!(table.at(1.75), [20.0]);
        assert_eq!(table.at(2.25), [30.0]);
        assert_eq!(table.at(0.0), [10.0]);
        assert_eq!(table.at(9.0), [30.0]);
        let got = with_controls(&[1.0, 2.0][..], &[3.0, 4.0][..], 1.8, &table, |x| {
            x.to_vec()
        });
        assert_eq!(got, [1.0, 2.0, 3.0, 4.0, 1.8, 20.0]);
    }
}
