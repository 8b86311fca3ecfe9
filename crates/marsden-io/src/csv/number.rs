//! Round-trip printing and parsing of `f64` for CSV.

use std::fmt::Write as _;

/// Appends `x` to `out` with the fewest digits that parse back to the same bits.
///
/// Plain decimal notation (Rust's `{}`) for zero and `1e-5 <= |x| < 1e16`; exponent notation
/// (Rust's `{:e}`, also shortest round-trip) otherwise, so tiny and huge values stay short.
/// Non-finite values print as `NaN`, `inf`, `-inf`.
pub fn format_f64(x: f64, out: &mut String) {
    let a = x.abs();
    // Writing to a `String` cannot fail, so the `fmt::Result` carries no information.
    let _ = if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&a) {
        write!(out, "{x}")
    } else {
        write!(out, "{x:e}")
    };
}

/// Parses a number written by [`format_f64`] (or any form Rust's `f64::from_str` accepts,
/// after trimming ASCII whitespace).
pub fn parse_f64(field: &str) -> Option<f64> {
    field.trim_ascii().parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fmt(x: f64) -> String {
        let mut s = String::new();
        format_f64(x, &mut s);
        s
    }

    #[test]
    fn chosen_notation() {
        assert_eq!(fmt(0.0), "0");
        assert_eq!(fmt(-0.0), "-0");
        assert_eq!(fmt(0.1), "0.1");
        assert_eq!(fmt(1.0), "1");
        assert_eq!(fmt(-123.25), "-123.25");
        assert_eq!(fmt(1e-5), "0.00001");
        assert_eq!(fmt(9.5e-6), "9.5e-6");
        assert_eq!(fmt(1e16), "1e16");
        assert_eq!(fmt(1e-300), "1e-300");
        assert_eq!(fmt(f64::MIN_POSITIVE / 4.0), "5.562684646268003e-309");
        assert_eq!(fmt(f64::NAN), "NaN");
        assert_eq!(fmt(f64::INFINITY), "inf");
        assert_eq!(fmt(f64::NEG_INFINITY), "-inf");
    }

    #[test]
    fn edge_values_round_trip_bitwise() {
        let cases = [
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::from_bits(1),
            -f64::from_bits(1),
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            0.1 + 0.2,
            1.0 / 3.0,
            9_007_199_254_740_993.0,
            1e15 + 0.3,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for x in cases {
            let back = parse_f64(&fmt(x)).unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:e} printed as {}", fmt(x));
        }
        assert!(parse_f64("NaN").unwrap().is_nan());
        assert_eq!(parse_f64(" 2.5 "), Some(2.5));
        assert_eq!(parse_f64("x"), None);
    }
}
