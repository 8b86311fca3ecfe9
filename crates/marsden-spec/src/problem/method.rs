//! `[integrator] method`: which rule turns `L` into `L_d`.
//!
//! The names are the core's ([`marsden::discrete::rules::Method`]): `midpoint`, `trapezoid`,
//! `alpha-<a>`, `symmetrized-<a>`, `gauss-<s>`, `lobatto-<s>`, `galerkin-<s>-<family>-<r>` and
//! compositions `<scheme>(<base>)`. This module adds the file-level error with a suggestion.

use marsden::error::InputError;
use std::fmt;

use marsden::discrete::rules::{METHOD_GRAMMAR, Method as CoreMethod, WithRule};

use marsden_expr::closest;

/// A variational integrator's rule, by the name a problem file uses.
#[derive(Debug, Clone, PartialEq)]
pub struct Method(pub CoreMethod);

/// The names accepted, for error messages and `--help`.
pub const METHOD_NAMES: &str = METHOD_GRAMMAR;

/// Typical names, for "did you mean" suggestions.
const KNOWN: [&str; 10] = [
    "midpoint",
    "trapezoid",
    "alpha-0.5",
    "symmetrized-0.5",
    "gauss-2",
    "gauss-3",
    "lobatto-3",
    "lobatto-4",
    "kahan-li-6(trapezoid)",
    "suzuki-umeno-8(trapezoid)",
];

impl Method {
    /// The midpoint rule (the default).
    pub fn midpoint() -> Self {
        Self(CoreMethod::Single(
            marsden::discrete::rules::BaseMethod::Midpoint,
        ))
    }

    /// Parses a method name; the error says what is wrong and may suggest a name.
    pub fn parse(name: &str) -> Result<Method, MethodError> {
        CoreMethod::parse(name).map(Method).map_err(|e| {
            let message = match e {
                marsden::Error::Input(InputError::UnknownMethod { reason, .. }) => {
                    format!("unknown method `{name}`: {reason}")
                }
                other => format!("method `{name}`: {other}"),
            };
            MethodError {
                message,
                suggestion: closest(name, KNOWN).map(str::to_owned),
            }
        })
    }

    /// The classical order of the integrator.
    pub fn order(&self) -> u32 {
        self.0.order()
    }

    /// Calls `visitor` with the concrete rule.
    pub fn dispatch<V: WithRule>(&self, visitor: V) -> V::Output {
        self.0.dispatch(visitor)
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0.name())
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
        for name in [
            "midpoint",
            "trapezoid",
            "alpha-0.25",
            "symmetrized-0",
            "gauss-2",
            "lobatto-3",
            "kahan-li-6(trapezoid)",
        ] {
            let m = Method::parse(name).unwrap();
            assert_eq!(m.to_string(), name);
        }
        assert_eq!(Method::parse("alpha-0.25").unwrap().order(), 1);
        assert_eq!(Method::parse("gauss-3").unwrap().order(), 6);
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
        let e = Method::parse("gauss-0").unwrap_err();
        assert!(e.message.contains("valid"), "{}", e.message);
        let e = Method::parse("galerkin-3-gauss-2").unwrap_err();
        assert!(e.message.contains("too few"), "{}", e.message);
    }
}
