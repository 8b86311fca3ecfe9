//! Angles on plots: wrapped to (−π, π], with the line broken where it wraps.
//!
//! An angle integrated over many turns grows without bound (θ down to −60 after ten
//! revolutions), which hides the motion it describes. Coordinates declared as angles are shown
//! modulo 2π; a line crossing ±π would otherwise draw a vertical stroke across the panel, so it
//! is split there.

use std::f64::consts::{PI, TAU};

use super::downsample::Segments;

/// `v` wrapped to (−π, π]; non-finite values stay as they are.
pub(crate) fn wrap(v: f64) -> f64 {
    if !v.is_finite() {
        return v;
    }
    let w = v - TAU * (v / TAU).round();
    if w <= -PI { w + TAU } else { w }
}

/// Every value of `values` wrapped to (−π, π].
pub(crate) fn wrapped(values: &[f64]) -> Vec<f64> {
    values.iter().map(|&v| wrap(v)).collect()
}

/// Splits the polylines of `data` where consecutive points jump by more than π in `x`
/// (`in_x`) or in `y` (`in_y`): the places where a wrapped angle went once round.
pub(crate) fn split_at_wraps(data: Segments, in_x: bool, in_y: bool) -> Segments {
    if !in_x && !in_y {
        return data;
    }
    let jump = |a: (f64, f64), b: (f64, f64)| {
        (in_x && (a.0 - b.0).abs() > PI) || (in_y && (a.1 - b.1).abs() > PI)
    };
    let mut segments = Vec::with_capacity(data.segments.len());
    for seg in data.segments {
        let mut current: Vec<(f64, f64)> = Vec::with_capacity(seg.len());
        for p in seg {
            if current.last().is_some_and(|&last| jump(last, p)) {
                segments.push(std::mem::take(&mut current));
            }
            current.push(p);
        }
        segments.push(current);
    }
    Segments { segments, ..data }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapping_lands_in_the_half_open_interval() {
        for (v, w) in [
            (0.0, 0.0),
            (PI, PI),
            (-PI, PI),
            (3.0 * PI, PI),
            (-60.0, -60.0 + 10.0 * TAU),
            (7.0, 7.0 - TAU),
        ] {
            assert!((wrap(v) - w).abs() < 1e-12, "{v} → {} (want {w})", wrap(v));
            assert!(wrap(v) > -PI && wrap(v) <= PI);
        }
        assert!(wrap(f64::NAN).is_nan());
    }

    #[test]
    fn lines_break_where_the_angle_wraps() {
        let data = Segments {
            segments: vec![vec![(0.0, 3.0), (1.0, -3.0), (2.0, -2.9)]],
            ..Segments::default()
        };
        let split = split_at_wraps(data.clone(), false, true);
        assert_eq!(split.segments.len(), 2);
        assert_eq!(split_at_wraps(data, false, false).segments.len(), 1);
    }
}
