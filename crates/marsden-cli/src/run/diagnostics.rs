//! What a run preserved, accumulated sample by sample in bounded memory: energy error and
//! drift, momentum-map drift, constraint residual.
//!
//! The energy statistics follow `marsden::diagnostics::EnergyReport` (same definitions; the
//! core keeps its accumulator private, so the streaming form lives here for now).

use marsden::diagnostics::OnlineSlope;

/// Energy errors over the stored samples: `E_k = H(q_k, p_k)`.
#[derive(Debug, Clone, Default)]
pub struct EnergyStats {
    /// `E_0`.
    pub initial: f64,
    /// `max |E_k − E_0|`.
    pub max_abs_error: f64,
    /// `max |E_k − E_0| / |E_0|` (relative to 1 when `E_0 = 0`).
    pub max_rel_error: f64,
    /// `(E_N − E_0) / |E_0|` at the last sample.
    pub final_rel_error: f64,
    /// Samples used.
    pub samples: usize,
    /// Samples where the energy could not be evaluated (written as NaN).
    pub failures: usize,
    slope: OnlineSlope,
}

impl EnergyStats {
    /// Adds the energy `e` at time `t` (NaN counts as a failure and is skipped).
    pub fn push(&mut self, t: f64, e: f64) {
        if !e.is_finite() {
            self.failures += 1;
            return;
        }
        if self.samples == 0 {
            self.initial = e;
        }
        self.samples += 1;
        let err = e - self.initial;
        let scale = self.scale();
        self.max_abs_error = self.max_abs_error.max(err.abs());
        self.max_rel_error = self.max_abs_error / scale;
        self.final_rel_error = err / scale;
        self.slope.push(t, err);
    }

    /// Least-squares slope of `E_k − E_0` against time.
    pub fn drift_per_unit_time(&self) -> f64 {
        self.slope.slope()
    }

    fn scale(&self) -> f64 {
        if self.initial != 0.0 {
            self.initial.abs()
        } else {
            1.0
        }
    }
}

/// Drift of one momentum map: `max |J_k − J_0|`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MapStats {
    /// `J_0`.
    pub initial: f64,
    /// `max |J_k − J_0|`.
    pub max_abs_drift: f64,
    /// Samples used.
    pub samples: usize,
}

impl MapStats {
    /// Adds a value.
    pub fn push(&mut self, j: f64) {
        if self.samples == 0 {
            self.initial = j;
        }
        self.samples += 1;
        let drift = (j - self.initial).abs();
        // NaN propagates, so a broken run does not report a perfect drift.
        if drift > self.max_abs_drift || drift.is_nan() {
            self.max_abs_drift = drift;
        }
    }
}

/// Everything monitored along a run.
#[derive(Debug, Clone, Default)]
pub struct Diagnostics {
    /// Energy errors.
    pub energy: EnergyStats,
    /// One per symmetry, in the file's order.
    pub maps: Vec<MapStats>,
    /// `max_k max_i |φ_i(q_k)|` (`None` without constraints).
    pub max_residual: Option<f64>,
}

impl Diagnostics {
    /// Empty statistics for `maps` momentum maps, with or without constraints.
    pub fn new(maps: usize, constrained: bool) -> Self {
        Self {
            energy: EnergyStats::default(),
            maps: vec![MapStats::default(); maps],
            max_residual: constrained.then_some(0.0),
        }
    }

    /// Adds a constraint residual.
    pub fn push_residual(&mut self, r: f64) {
        if let Some(max) = &mut self.max_residual
            && (r > *max || r.is_nan())
        {
            *max = r;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn energy_errors_match_the_core_definitions() {
        let mut e = EnergyStats::default();
        for (t, v) in [(0.0, -2.0), (1.0, -2.1), (2.0, -1.95), (3.0, f64::NAN)] {
            e.push(t, v);
        }
        let core =
            marsden::diagnostics::EnergyReport::from_series(&[0.0, 1.0, 2.0], &[-2.0, -2.1, -1.95]);
        assert_eq!(e.initial, core.initial);
        assert_eq!(e.max_abs_error, core.max_abs_error);
        assert_eq!(e.max_rel_error, core.max_rel_error);
        assert_eq!(e.final_rel_error, core.final_rel_error);
        assert_eq!(e.drift_per_unit_time(), core.drift_per_unit_time);
        assert_eq!((e.samples, e.failures), (3, 1));
    }

    #[test]
    fn drifts_and_residuals() {
        let mut d = Diagnostics::new(1, true);
        for j in [1.0, 1.0 + 1e-12, 1.0 - 3e-12] {
            d.maps[0].push(j);
        }
        d.push_residual(1e-15);
        d.push_residual(5e-16);
        assert!((d.maps[0].max_abs_drift - 3e-12).abs() < 1e-15);
        assert_eq!(d.max_residual, Some(1e-15));
        assert_eq!(Diagnostics::new(0, false).max_residual, None);
    }
}
