//! The predictor: a starting guess for the unknowns of the next step from the last ones.

use super::equations::StepShape;
use crate::numerics::short;

/// Starting guess for the unknowns of the next step.
///
/// The unknowns are offsets `Δ_j ≈ c_j h v`, smooth in time: each is extrapolated from the same
/// unknown in the last three steps (quadratic: `3z₁ − 3z₂ + z₃`, error `O(h⁴)` in positions),
/// falling back to linear, constant, and for a fresh start `Δ_j = c_j h v_k` with the velocity
/// hint (or 0). Multipliers start from their last values. The history is a flat ring of three
/// solutions (no allocation per step).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) struct Predictor {
    /// Three solutions back to back.
    ring: Vec<f64>,
    /// Slots of the newest, previous and oldest solution.
    order: [usize; 3],
    /// Number of valid solutions in the ring (0 … 3).
    len: usize,
    h: f64,
    velocity: Option<Vec<f64>>,
}

impl Predictor {
    /// `z` ← the guess for a step of size `h` (inlined into the generic step, which is compiled
    /// in the crate that names the system: a call across crates costs more than the work here).
    #[inline]
    pub(super) fn predict(&mut self, z: &mut Vec<f64>, h: f64, sh: StepShape) {
        let m = sh.unknowns();
        if z.len() != m {
            z.resize(m, 0.0);
        }
        if h != self.h || self.ring.len() != 3 * m {
            self.reset_ring(m);
        }
        if self.len == 0 {
            return self.fresh(z, h, sh);
        }
        let [a, b, c] = self.order.map(|slot| &self.ring[slot * m..(slot + 1) * m]);
        // The offsets are extrapolated, the multipliers (after them) start from their last values.
        let sn = sh.s * sh.n;
        let (offsets, multipliers) = z.split_at_mut(sn);
        match self.len {
            1 => short::copy(offsets, &a[..sn]),
            2 => short::combine3(offsets, a, b, c, |a, b, _| 2.0 * a - b),
            _ => short::combine3(offsets, a, b, c, |a, b, c| 3.0 * (a - b) + c),
        }
        if !multipliers.is_empty() {
            multipliers.copy_from_slice(&a[sn..]);
        }
    }

    #[cold]
    fn reset_ring(&mut self, m: usize) {
        self.ring.resize(3 * m, 0.0);
        self.order = [0, 1, 2];
        self.len = 0;
    }

    #[inline(never)]
    fn fresh(&self, z: &mut [f64], h: f64, sh: StepShape) {
        let n = sh.n;
        for j in 1..=sh.s {
            let c = j as f64 / sh.s as f64;
            for a in 0..n {
                let v = self.velocity.as_ref().map_or(0.0, |v| v[a]);
                z[(j - 1) * n + a] = c * h * v;
            }
        }
        z[sh.s * n..].fill(0.0);
    }

    /// The velocity for a fresh start (`Δ_j = c_j h v`).
    pub(super) fn set_velocity(&mut self, v: &[f64]) {
        self.velocity = Some(v.to_vec());
    }

    /// Keeps the solution `z` of a step of size `h` (inlined as [`Predictor::predict`] is).
    #[inline]
    pub(super) fn record(&mut self, z: &[f64], h: f64) {
        let m = z.len();
        if self.ring.len() != 3 * m {
            self.reset_ring(m);
        }
        let [newest, previous, oldest] = self.order;
        self.order = [oldest, newest, previous];
        short::copy(&mut self.ring[oldest * m..(oldest + 1) * m], z);
        self.len = (self.len + 1).min(3);
        self.h = h;
        self.velocity = None;
    }
}
