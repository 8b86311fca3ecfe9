//! The time grid of a run, checked so that nothing untrue is reported on success: the steps
//! are counted exactly, the final time is finite, and the floating-point times resolve the step.
//!
//! Times are `t_k = t₀ + k h` (see [`marsden::TimeGrid`]); a `t_end` that is not a whole
//! number of steps after `t₀` (to a relative 1e-9) ends with one shorter step, so the run
//! stops where it was asked to ([`marsden::TimeGrid::ending_at`]). A grid is refused when
//!
//! - `t_end` is less than one step after `t₀`;
//! - it has more than [`MAX_STEPS`] steps;
//! - `t₀ + N h` overflows;
//! - the spacing of doubles near `max(|t₀|, |t_N|)` exceeds [`RESOLUTION`]·h, so the computed
//!   steps `t_{k+1} − t_k` would differ from `h` by more than that fraction (with `t₀ = 10¹⁷`
//!   and `h = 0.05`, `t₀ + h == t₀`: time would never advance).

use marsden::TimeGrid;

/// Most steps a run may take (10¹²: weeks of computing at a microsecond a step).
pub const MAX_STEPS: usize = 1_000_000_000_000;

/// Largest relative error of a computed step `t_{k+1} − t_k` accepted against `h`.
pub const RESOLUTION: f64 = 1e-6;

/// The number of steps from `t0` to exactly `t_end`: `(t_end − t₀)/h` when it is a whole
/// number (to a relative 1e-9), else one more than its whole part (the last step shorter).
///
/// # Errors
/// A message (without position) if `t_end` is not after `t0`, is less than a step away, or is
/// more than [`MAX_STEPS`] steps away.
pub fn steps_until(t0: f64, t_end: f64, h: f64) -> Result<usize, String> {
    if t_end <= t0 {
        return Err(format!("t_end = {t_end} must be after t0 = {t0}"));
    }
    let n = (t_end - t0) / h;
    if !n.is_finite() || n > MAX_STEPS as f64 {
        return Err(format!(
            "t_end = {t_end} is {n:.3e} steps of h = {h} after t0 = {t0}, more than the \
             limit of {MAX_STEPS:.0e} steps"
        ));
    }
    let whole = match (n - n.round()).abs() <= 1e-9 * n.max(1.0) {
        true => n.round(),
        false => n.ceil(),
    };
    if n < 1.0 - 1e-9 {
        return Err(format!(
            "t_end = {t_end} is less than one step h = {h} after t0 = {t0}"
        ));
    }
    // `whole` is a whole number in 1 ..= MAX_STEPS, so the conversion is exact.
    Ok(whole as usize)
}

/// Checks that `steps` is within [`MAX_STEPS`].
///
/// # Errors
/// A message naming the limit.
pub fn check_steps(steps: usize) -> Result<usize, String> {
    if steps > MAX_STEPS {
        Err(format!(
            "{steps} steps is more than the limit of {MAX_STEPS:.0e} steps"
        ))
    } else {
        Ok(steps)
    }
}

/// Checks that the final time is finite and that the times resolve the step.
///
/// # Errors
/// A message with the numbers at fault.
pub fn check_grid(grid: &TimeGrid) -> Result<(), String> {
    let end = grid.t_end();
    if !end.is_finite() {
        return Err(format!(
            "the final time t0 + steps·h = {} + {}·{} is not a finite number",
            grid.t0, grid.steps, grid.h
        ));
    }
    let largest = grid.t0.abs().max(end.abs());
    let spacing = largest * f64::EPSILON;
    if spacing > RESOLUTION * grid.h {
        return Err(format!(
            "the time step h = {} is below the resolution of t near {largest:e} (doubles \
             there are {spacing:.1e} apart): the computed steps t(k+1) − t(k) would be off \
             by more than a fraction {RESOLUTION:e} of h",
            grid.h
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whole_steps_are_counted_and_the_rest_refused() {
        assert_eq!(steps_until(0.0, 10.0, 0.1), Ok(100));
        assert_eq!(steps_until(0.0, 20.0, 0.01), Ok(2000));
        assert_eq!(steps_until(0.0, 0.07, 0.05), Ok(2));
        assert_eq!(steps_until(0.0, 0.0999999, 0.05), Ok(2));
        assert!(steps_until(0.0, 1e-12, 0.05).is_err());
        assert!(steps_until(0.0, 1e300, 0.05).is_err());
        assert!(steps_until(1.0, 1.0, 0.05).is_err());
    }

    #[test]
    fn overflow_and_resolution_are_refused() {
        let grid = |t0, h, steps| TimeGrid {
            t0,
            h,
            steps,
            end: None,
        };
        assert!(check_grid(&grid(0.0, 1e308, 2)).is_err());
        assert!(check_grid(&grid(1e17, 0.05, 10)).is_err());
        assert!(check_grid(&grid(0.0, 0.05, 10)).is_ok());
        assert!(check_grid(&grid(1000.0, 1e-3, 10)).is_ok());
    }
}
