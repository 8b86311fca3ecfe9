//! `[integrator] method`: which rule turns `L` into `L_d`.

use std::fmt;

use crate::expr::suggest::closest;

/// A variational integrator's rule, by the name a problem file uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// `midpoint`: [`marsden::Midpoint`], order 2.
    Midpoint,
    /// `trapezoid`: [`marsden::Trapezoid`] (Störmer–Verlet for mechanical systems), order 2.
    Trapezoid,
    /// `alpha-<a>`: [`marsden::GeneralizedMidpoint`], order 1 (2 for a = 0.5).
    Alpha(f64),
    /// `symmetrized-<a>`: [`marsden::SymmetrizedMidpoint`], order 2.
    Symmetrized(f64),
}

/// The names accepted, for error messages and `--help`.
pub const METHOD_NAMES: &str =
    "midpoint, trapezoid, alpha-<a> and symmetrized-<a> with 0 <= a <= 1 (e.g. alpha-0.25)";

/// Families announced in the design that are not available yet.
const LATER: [&str; 2] = ["gauss", "lobatto"];

impl Method {
    /// Parses a method name; the error says what is wrong and may suggest a name.
    pub fn parse(name: &str) -> Result<Method, MethodError> {
        match name {
            "midpoint" => return Ok(Method::Midpoint),
            "trapezoid" => return Ok(Method::Trapezoid),
            _ => {}
        }
        if let Some((family, arg)) = name.split_once('-') {
            match family {
                "alpha" => return parse_alpha(arg, name).map(Method::Alpha),
                "symmetrized" => return parse_alpha(arg, name).map(Method::Symmetrized),
                f if LATER.contains(&f) => {
                    return Err(MethodError {
                        message: format!(
                            "method `{name}`: Galerkin methods ({f}-<s>) are not available yet"
                        ),
                        suggestion: None,
                    });
                }
                _ => {}
            }
        }
        let known = ["midpoint", "trapezoid", "alpha-0.5", "symmetrized-0.5"];
        Err(MethodError {
            message: format!("unknown method `{name}`"),
            suggestion: closest(name, known).map(str::to_owned),
        })
    }

    /// The classical order of the integrator.
    pub fn order(self) -> u32 {
        match self {
            Method::Alpha(a) if a != 0.5 => 1,
            _ => 2,
        }
    }
}

fn parse_alpha(arg: &str, name: &str) -> Result<f64, MethodError> {
    match arg.parse::<f64>() {
        Ok(a) if (0.0..=1.0).contains(&a) => Ok(a),
        _ => Err(MethodError {
            message: format!("method `{name}`: the parameter must be a number in [0, 1]"),
            suggestion: None,
        }),
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Method::Midpoint => f.write_str("midpoint"),
            Method::Trapezoid => f.write_str("trapezoid"),
            Method::Alpha(a) => write!(f, "alpha-{a}"),
            Method::Symmetrized(a) => write!(f, "symmetrized-{a}"),
        }
    }
}

/// Why a method name was rejected.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MethodError {
    /// What is wrong.
    pub message: String,
    /// A close valid name.
    pub suggestion: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for m in [
            Method::Midpoint,
            Method::Trapezoid,
            Method::Alpha(0.25),
            Method::Symmetrized(0.0),
        ] {
            assert_eq!(Method::parse(&m.to_string()), Ok(m));
        }
        assert_eq!(Method::Alpha(0.25).order(), 1);
        assert_eq!(Method::Alpha(0.5).order(), 2);
    }

    #[test]
    fn rejections_explain() {
        let e = Method::parse("midpiont").unwrap_err();
        assert_eq!(e.suggestion.as_deref(), Some("midpoint"));
        assert!(
            Method::parse("alpha-2")
                .unwrap_err()
                .message
                .contains("[0, 1]")
        );
        assert!(
            Method::parse("gauss-2")
                .unwrap_err()
                .message
                .contains("not available yet")
        );
    }
}
