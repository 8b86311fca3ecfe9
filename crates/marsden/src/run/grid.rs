//! The time grid of a run and how much of it is stored.
//!
//! Times are computed as `t_k = t₀ + k h`, never accumulated.

use crate::error::Error;
use crate::error::InputError;

/// A uniform time grid `t_k = t₀ + k h`, `k = 0 … steps`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TimeGrid {
    /// Initial time.
    pub t0: f64,
    /// Time step (positive).
    pub h: f64,
    /// Number of steps.
    pub steps: usize,
}

impl TimeGrid {
    /// `steps` steps of size `h` from `t0`.
    pub fn new(t0: f64, h: f64, steps: usize) -> Result<Self, Error> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        Error::check_finite("t0", &[t0])?;
        Ok(Self { t0, h, steps })
    }

    /// Steps of size `h` from `t0` until `t_end`: the last grid time is the first one at or after
    /// `t_end` (within a relative 1e-9, so `t_end = 10, h = 0.1` gives exactly 100 steps).
    pub fn until(t0: f64, t_end: f64, h: f64) -> Result<Self, Error> {
        let grid = Self::new(t0, h, 0)?;
        Error::check_finite("t_end", &[t_end])?;
        if t_end <= t0 {
            return Err(Error::Input(InputError::InvalidTimeSpan {
                reason: format!("t_end = {t_end} must be after t0 = {t0}"),
            }));
        }
        let n = (t_end - t0) / h;
        let steps = if (n - n.round()).abs() <= 1e-9 * n.max(1.0) {
            n.round()
        } else {
            n.ceil()
        };
        Ok(Self {
            steps: steps as usize,
            ..grid
        })
    }

    /// Time of grid point `k`.
    pub fn time(&self, k: usize) -> f64 {
        self.t0 + k as f64 * self.h
    }

    /// Final time.
    pub fn t_end(&self) -> f64 {
        self.time(self.steps)
    }
}

/// Options of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RunOptions {
    /// Store every `stride`-th state (default 1: every state). The first and last states are
    /// always stored; `usize::MAX` stores only those.
    pub stride: usize,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self { stride: 1 }
    }
}
