//! Energy along a trajectory: `E_k = H(q_k, p_k) = ⟨p_k, v_k⟩ − L(q_k, v_k)` with
//! `v_k = FH(q_k, p_k)` (seed: *Legendre transforms*; the energy of the discrete momenta).
//!
//! For a symplectic integrator of order r on a conservative system the energy error stays
//! `O(h^r)` without drift over exponentially long times ([HLW06] Thm. IX.8.1; reference case R8).
//!
//! [HLW06]: crate#references

use std::ops::ControlFlow;

use super::OnlineSlope;
use crate::error::Error;
use crate::mechanics;
use crate::mechanics::Lagrangian;
use crate::run::Trajectory;
use crate::run::{Observer, StepView};

/// Energy errors of a run.
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EnergyReport {
    /// Energy at the first sample.
    pub initial: f64,
    /// `max |E_k − E_0|`.
    pub max_abs_error: f64,
    /// `max |E_k − E_0| / |E_0|` (relative to 1 when `E_0 = 0`).
    pub max_rel_error: f64,
    /// `(E_N − E_0) / |E_0|` at the last sample.
    pub final_rel_error: f64,
    /// Least-squares slope of `E_k − E_0` against time (energy units per unit time).
    pub drift_per_unit_time: f64,
    /// The drift relative to `|E_0|`.
    pub rel_drift_per_unit_time: f64,
    /// Number of samples used.
    pub samples: usize,
    /// Samples whose energy was not finite (skipped, counted here).
    pub failures: usize,
}

/// Accumulates energy errors sample by sample in O(1) memory (shared by the batch report, the
/// [`EnergyMonitor`] and streaming writers that compute energies themselves).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct EnergyAccumulator {
    report: EnergyReport,
    slope: OnlineSlope,
}

impl EnergyAccumulator {
    /// The report so far.
    pub fn report(&self) -> &EnergyReport {
        &self.report
    }

    /// Adds the energy `e` at time `t`; a non-finite value is counted as a failure and skipped.
    pub fn push(&mut self, t: f64, e: f64) {
        if !e.is_finite() {
            self.report.failures += 1;
            return;
        }
        let r = &mut self.report;
        if r.samples == 0 {
            r.initial = e;
        }
        r.samples += 1;
        let err = e - r.initial;
        let scale = if r.initial != 0.0 {
            r.initial.abs()
        } else {
            1.0
        };
        r.max_abs_error = r.max_abs_error.max(err.abs());
        r.max_rel_error = r.max_abs_error / scale;
        r.final_rel_error = err / scale;
        self.slope.push(t, err);
        r.drift_per_unit_time = self.slope.slope();
        r.rel_drift_per_unit_time = r.drift_per_unit_time / scale;
    }
}

impl EnergyReport {
    /// The report of an energy series sampled at `times`.
    pub fn from_series(times: &[f64], energies: &[f64]) -> Self {
        let mut acc = EnergyAccumulator::default();
        times
            .iter()
            .zip(energies)
            .for_each(|(&t, &e)| acc.push(t, e));
        acc.report
    }

    /// Computes the energy series of `trajectory` for `lagrangian` and reports on it.
    pub fn of<L: Lagrangian>(lagrangian: &L, trajectory: &Trajectory) -> Result<Self, Error> {
        let e = energy_series(lagrangian, trajectory)?;
        Ok(Self::from_series(&trajectory.times, &e))
    }
}

/// The energy `H(q_k, p_k)` at every stored sample.
pub fn energy_series<L: Lagrangian>(
    lagrangian: &L,
    trajectory: &Trajectory,
) -> Result<Vec<f64>, Error> {
    let mut v = vec![0.0; trajectory.dof];
    (0..trajectory.len())
        .map(|i| {
            let (t, q, p) = (trajectory.t(i), trajectory.q(i), trajectory.p(i));
            mechanics::energy_from_momentum(lagrangian, t, q, p, &mut v)
        })
        .collect()
}

/// Streaming energy monitor: an [`Observer`] that accumulates the [`EnergyReport`] of every step
/// without storing the trajectory.
#[derive(Debug, Clone)]
pub struct EnergyMonitor<L> {
    lagrangian: L,
    velocity: Vec<f64>,
    acc: EnergyAccumulator,
    error: Option<Error>,
}

impl<L: Lagrangian> EnergyMonitor<L> {
    /// A monitor for `lagrangian`.
    pub fn new(lagrangian: L) -> Self {
        let n = lagrangian.dof();
        Self {
            lagrangian,
            velocity: vec![0.0; n],
            acc: EnergyAccumulator::default(),
            error: None,
        }
    }

    /// The report so far, or the error that stopped the monitor.
    pub fn report(&self) -> Result<&EnergyReport, &Error> {
        match &self.error {
            Some(e) => Err(e),
            None => Ok(&self.acc.report),
        }
    }

    fn record(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        match mechanics::energy_from_momentum(
            &self.lagrangian,
            view.t,
            view.q,
            view.p,
            &mut self.velocity,
        ) {
            Ok(e) => {
                self.acc.push(view.t, e);
                ControlFlow::Continue(())
            }
            Err(e) => {
                self.error = Some(e);
                ControlFlow::Break(())
            }
        }
    }
}

impl<L: Lagrangian> Observer for EnergyMonitor<L> {
    fn start(&mut self, initial: &StepView<'_>) {
        let _ = self.record(initial);
    }
    fn observe(&mut self, view: &StepView<'_>) -> ControlFlow<()> {
        self.record(view)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_energies_are_counted_and_skipped() {
        let mut acc = EnergyAccumulator::default();
        for (t, e) in [(0.0, -2.0), (1.0, -2.1), (2.0, -1.95), (3.0, f64::NAN)] {
            acc.push(t, e);
        }
        let batch = EnergyReport::from_series(&[0.0, 1.0, 2.0], &[-2.0, -2.1, -1.95]);
        let r = acc.report();
        assert_eq!((r.samples, r.failures), (3, 1));
        assert_eq!(r.max_abs_error, batch.max_abs_error);
        assert!((r.max_abs_error - 0.1).abs() < 1e-15 && (r.max_rel_error - 0.05).abs() < 1e-15);
        assert_eq!(r.drift_per_unit_time, batch.drift_per_unit_time);
    }
}
