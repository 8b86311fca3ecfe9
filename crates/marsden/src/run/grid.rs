//! The time grid of a run and how much of it is stored.
//!
//! Times are computed as `t_k = t₀ + k h`, never accumulated.

use crate::error::Error;
use crate::error::InputError;

/// A time grid `t_k = t₀ + k h`, `k = 0 … steps`, uniform but perhaps for its last step.
///
/// A grid that must end at a time `t_end` which is not a whole number of steps after `t₀`
/// ([`TimeGrid::ending_at`]) takes `steps − 1` steps of `h` and one shorter last step
/// `h_N = t_end − t_{N−1}` ∈ (0, h), so that `t_N = t_end` exactly. The last step is a
/// variational step of its own size (the discrete Lagrangian `L_d(q_{N−1}, q_N, h_N)`), so the
/// whole map is still a composition of symplectic maps (Marsden & West 2001, §1.3: every
/// `F_{L_d}` preserves the discrete symplectic form, whatever its `h`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct TimeGrid {
    /// Initial time.
    pub t0: f64,
    /// Time step (positive).
    pub h: f64,
    /// Number of steps.
    pub steps: usize,
    /// The final time when the last step is shorter than `h` (`None`: a uniform grid).
    pub end: Option<f64>,
}

impl TimeGrid {
    /// `steps` steps of size `h` from `t0`.
    pub fn new(t0: f64, h: f64, steps: usize) -> Result<Self, Error> {
        if !(h > 0.0 && h.is_finite()) {
            return Err(Error::Input(InputError::InvalidStep { h }));
        }
        Error::check_finite("t0", &[t0])?;
        Ok(Self {
            t0,
            h,
            steps,
            end: None,
        })
    }

    /// Steps of size `h` from `t0` to exactly `t_end`: a whole number of steps when `t_end` is
    /// one (within a relative 1e-9, so `t_end = 10, h = 0.1` gives 100 uniform steps), otherwise
    /// `⌈(t_end − t₀)/h⌉` steps of which the last is the shorter `t_end − t_{N−1}`.
    ///
    /// # Errors
    /// `h` not positive and finite, `t0` or `t_end` not finite, `t_end` not after `t0`.
    pub fn ending_at(t0: f64, t_end: f64, h: f64) -> Result<Self, Error> {
        let uniform = Self::until(t0, t_end, h)?;
        match uniform.whole_steps(t_end) {
            true => Ok(uniform),
            false => Ok(Self {
                end: Some(t_end),
                ..uniform
            }),
        }
    }

    /// [`TimeGrid::ending_at`] with `time(steps) = t_end` to the bit also when `t_end` is a
    /// whole number of steps away: where `t₀ + N h` rounds to another number than `t_end`, the
    /// last step is `t_end − t_{N−1}`, which is `h` to round-off (a stepping interface asked
    /// to integrate to a time ends there, as a user reads the time back).
    ///
    /// # Errors
    /// As [`TimeGrid::ending_at`].
    pub fn ending_exactly_at(t0: f64, t_end: f64, h: f64) -> Result<Self, Error> {
        let grid = Self::ending_at(t0, t_end, h)?;
        match grid.t_end() == t_end {
            true => Ok(grid),
            false => Ok(Self {
                end: Some(t_end),
                ..grid
            }),
        }
    }

    /// Checks a grid built field by field: `h` positive and finite, `t0` finite, and a shorter
    /// last step, if any, in `(0, h]` (to a relative 1e-9 above `h`: round-off).
    ///
    /// # Errors
    /// The field at fault.
    pub fn validate(&self) -> Result<(), Error> {
        Self::new(self.t0, self.h, self.steps)?;
        let fits = |last: f64| last > 0.0 && last <= self.h * (1.0 + 1e-9);
        match (self.end, self.last_step()) {
            (Some(_), last) if !last.is_some_and(fits) => {
                Err(Error::Input(InputError::InvalidTimeSpan {
                    reason: format!(
                        "the final time {} must lie within the last of {} steps h = {} after \
                         t0 = {}",
                        self.end.unwrap_or(f64::NAN),
                        self.steps,
                        self.h,
                        self.t0
                    ),
                }))
            }
            _ => Ok(()),
        }
    }

    /// Whether `t_end` is a whole number of steps after `t₀` (to a relative 1e-9).
    fn whole_steps(&self, t_end: f64) -> bool {
        let n = (t_end - self.t0) / self.h;
        (n - n.round()).abs() <= 1e-9 * n.max(1.0)
    }

    /// The size of the last step when it is shorter than `h`.
    #[inline]
    pub fn last_step(&self) -> Option<f64> {
        let end = self.end?;
        let before = self.steps.checked_sub(1)?;
        Some(end - (self.t0 + before as f64 * self.h))
    }

    /// The size of step `k` (from `t_k` to `t_{k+1}`): `h`, or the shorter last step.
    #[inline]
    pub fn step_size(&self, k: usize) -> f64 {
        match self.last_step() {
            Some(last) if k + 1 == self.steps => last,
            _ => self.h,
        }
    }

    /// How many of the `steps` steps from grid point `k` have the uniform size `h` (all but a
    /// shorter last step among them).
    #[inline]
    pub fn uniform_steps(&self, k: usize, steps: usize) -> usize {
        match self.end.is_some() && k + steps == self.steps && steps > 0 {
            true => steps - 1,
            false => steps,
        }
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
        let steps = if grid.whole_steps(t_end) {
            n.round()
        } else {
            n.ceil()
        };
        Ok(Self {
            steps: steps as usize,
            ..grid
        })
    }

    /// Time of grid point `k`: `t₀ + k h`, and the final time itself at the end of a shorter
    /// last step.
    #[inline]
    pub fn time(&self, k: usize) -> f64 {
        match self.end {
            Some(end) if k == self.steps => end,
            _ => self.t0 + k as f64 * self.h,
        }
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
