//! What a run preserved, accumulated sample by sample in bounded memory: energy error and
//! drift, momentum-map drift, constraint residual.
//!
//! The energy statistics are the core's (`marsden::analysis::diagnostics::EnergyAccumulator`).

use marsden::analysis::diagnostics::EnergyAccumulator;

/// Drift of one momentum map: `max |J_k − J_0|`.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
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
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
pub struct Diagnostics {
    /// Energy errors.
    pub energy: EnergyAccumulator,
    /// One per symmetry, in the file's order.
    pub maps: Vec<MapStats>,
    /// `max_k max_i |φ_i(q_k)|` (`None` without constraints).
    pub max_residual: Option<f64>,
    /// `max_k max_i |Dφ_i(q_k)·v_k|`, the hidden (velocity) constraint (`None` without
    /// constraints).
    pub max_velocity_residual: Option<f64>,
}

impl Diagnostics {
    /// Empty statistics for `maps` momentum maps, with or without constraints.
    pub fn new(maps: usize, constrained: bool) -> Self {
        Self {
            energy: EnergyAccumulator::default(),
            maps: vec![MapStats::default(); maps],
            max_residual: constrained.then_some(0.0),
            max_velocity_residual: constrained.then_some(0.0),
        }
    }

    /// Adds a constraint residual.
    pub fn push_residual(&mut self, r: f64) {
        raise(&mut self.max_residual, r);
    }

    /// Adds a velocity-constraint residual.
    pub fn push_velocity_residual(&mut self, r: f64) {
        raise(&mut self.max_velocity_residual, r);
    }
}

/// `max ← max(max, r)`, NaN sticking (a broken run does not report a perfect residual).
fn raise(max: &mut Option<f64>, r: f64) {
    if let Some(max) = max
        && (r > *max || r.is_nan())
    {
        *max = r;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
