//! Axis ranges and tick labels that read well from 1e-15 to 1e15.

/// How values map to the vertical axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scale {
    /// Linear, with plain or scientific tick labels as the range requires.
    Linear,
    /// Base-10 logarithmic; only positive values can be drawn.
    Log,
}

/// The smallest and largest of the values usable on `scale` (finite, and positive for log).
pub(crate) fn extent(values: impl Iterator<Item = f64>, scale: Scale) -> Option<(f64, f64)> {
    values
        .filter(|v| v.is_finite() && (scale == Scale::Linear || *v > 0.0))
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// Widens the extent `lo..hi` by a margin (5 % each side, in log space for log scale) and opens up
/// degenerate ones (a constant series gets a range around its value).
pub(crate) fn padded(lo: f64, hi: f64, scale: Scale) -> (f64, f64) {
    match scale {
        Scale::Linear => {
            if hi > lo {
                let m = 0.05 * (hi - lo);
                if m.is_finite() {
                    return (lo - m, hi + m);
                }
                return (lo, hi);
            }
            let r = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - r, hi + r)
        }
        Scale::Log => {
            let (a, b) = (lo.log10(), hi.log10());
            if b > a {
                let m = 0.05 * (b - a);
                (10f64.powf(a - m), 10f64.powf(b + m))
            } else {
                (lo / 10.0, hi * 10.0)
            }
        }
    }
}

/// Removes trailing zeros (and a bare trailing point) from a decimal mantissa.
fn trim(mantissa: &str) -> &str {
    if mantissa.contains('.') {
        mantissa.trim_end_matches('0').trim_end_matches('.')
    } else {
        mantissa
    }
}

/// Short, unambiguous label for a value `v`, given the axis range `lo..hi`.
///
/// Plain decimals when the range's magnitude is between 1e-3 and 1e5, otherwise scientific
/// (`-2.5e-9`); always enough digits to tell neighbouring ticks apart and never the float
/// noise of tick arithmetic (`0.30000000000000004`).
pub(crate) fn label(v: f64, lo: f64, hi: f64) -> String {
    let step = ((hi - lo) / 8.0).abs();
    let mag = lo.abs().max(hi.abs());
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 || (step > 0.0 && v.abs() < step * 1e-6) {
        return "0".to_owned();
    }
    let digits_below = |s: f64| -> usize {
        if s > 0.0 && s.is_finite() {
            // Clamped to [0, 15] before the (saturating) cast.
            (-s.log10()).ceil().clamp(0.0, 15.0) as usize
        } else {
            0
        }
    };
    if (1e-3..1e5).contains(&mag) {
        let decimals = (digits_below(step) + 1).min(15);
        let s = format!("{v:.decimals$}");
        return trim(&s).to_owned();
    }
    // Scientific: mantissa digits enough to resolve `step` relative to this value.
    let rel = if step > 0.0 { v.abs() / step } else { 1.0 };
    let digits = if rel > 1.0 {
        (rel.log10().ceil() as usize + 1).min(15)
    } else {
        1
    };
    let s = format!("{v:.digits$e}");
    match s.split_once('e') {
        Some((m, e)) => format!("{}e{e}", trim(m)),
        None => s,
    }
}

/// Label for a tick on a log axis: `1e-12`, `2e-12`, `0.01`, `100`.
pub(crate) fn log_label(v: f64) -> String {
    if !(v.is_finite() && v > 0.0) {
        return format!("{v}");
    }
    let s = format!("{v:.2e}");
    let short = match s.split_once('e') {
        Some((m, e)) => format!("{}e{e}", trim(m)),
        None => s,
    };
    if (1e-2..1e4).contains(&v) {
        // Small exponents read better plainly; parse back the rounded value to print it.
        if let Ok(r) = short.parse::<f64>() {
            return format!("{r}");
        }
    }
    short
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_labels_hide_float_noise() {
        assert_eq!(label(0.30000000000000004, 0.0, 1.0), "0.3");
        assert_eq!(label(2.0, 0.0, 10.0), "2");
        assert_eq!(label(1.25, 0.0, 2.0), "1.25");
        assert_eq!(label(0.0, -1.0, 1.0), "0");
        assert_eq!(label(-0.5, -1.0, 1.0), "-0.5");
        assert_eq!(label(1e-17, -1.0, 1.0), "0");
    }

    #[test]
    fn scientific_labels_for_tiny_and_huge_ranges() {
        assert_eq!(label(-2e-9, -2e-9, 2e-9), "-2e-9");
        assert_eq!(label(1.5e-9, -2e-9, 2e-9), "1.5e-9");
        assert_eq!(label(5e-16, -1e-15, 1e-15), "5e-16");
        assert_eq!(label(3e7, 0.0, 1e8), "3e7");
        // Neighbouring ticks stay distinguishable on a narrow range far from zero.
        assert_ne!(
            label(1.0001e-3 * 1e-3, 1e-6, 1.0002e-6),
            label(1.00015e-6, 1e-6, 1.0002e-6)
        );
    }

    #[test]
    fn log_labels() {
        assert_eq!(log_label(1e-12), "1e-12");
        assert_eq!(log_label(2.0000000000000003e-12), "2e-12");
        assert_eq!(log_label(0.1), "0.1");
        assert_eq!(log_label(100.0), "100");
    }

    #[test]
    fn ranges() {
        assert_eq!(
            extent([1.0, f64::NAN, -2.0].into_iter(), Scale::Linear),
            Some((-2.0, 1.0))
        );
        assert_eq!(
            extent([0.0, -1.0, 1e-3].into_iter(), Scale::Log),
            Some((1e-3, 1e-3))
        );
        assert_eq!(extent([f64::NAN].into_iter(), Scale::Linear), None);
        assert_eq!(padded(0.0, 0.0, Scale::Linear), (-1.0, 1.0));
        assert_eq!(padded(2.0, 2.0, Scale::Linear), (1.8, 2.2));
        let (a, b) = padded(1e-3, 1e-3, Scale::Log);
        assert!((a - 1e-4).abs() < 1e-18 && (b - 1e-2).abs() < 1e-15);
    }
}
