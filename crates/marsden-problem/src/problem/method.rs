//! `[integrator] method`: which rule turns `L` into `L_d`.
//!
//! The names are the core's ([`marsden::discrete::rules::Method`]): `midpoint`, `trapezoid`,
//! `alpha-<a>`, `symmetrized-<a>`, `gauss-<s>`, `lobatto-<s>`, `galerkin-<s>-<family>-<r>` and
//! compositions `<scheme>(<base>)`; and `exact`, the exact discrete Lagrangian
//! `L_d^E(q₀, q₁) = ∫₀ʰ L dt` along the Euler–Lagrange solution from `q₀` to `q₁`, computed by
//! shooting ([`marsden::discrete::exact`], [MW01] §1.6): its discrete Hamiltonian map is the
//! exact flow, so it serves as a reference for small unforced, unconstrained problems. This
//! module adds the file-level error with a suggestion.
//!
//! [MW01]: marsden#references

use marsden::error::InputError;
use std::fmt;

use marsden::discrete::rules::{METHOD_GRAMMAR, Method as CoreMethod};

use marsden_expr::closest;

/// A variational integrator's rule, by the name a problem file uses.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// A quadrature rule of the core.
    Rule(CoreMethod),
    /// `exact`: `L_d^E` by shooting.
    Exact,
}

/// The name of [`Method::Exact`].
pub const EXACT: &str = "exact";

/// The names accepted, for error messages and `--help`.
pub const METHOD_NAMES: &str = METHOD_GRAMMAR;

/// The names accepted besides the core's rules, for error messages.
pub const EXACT_NOTE: &str = "or `exact` (the exact discrete Lagrangian by shooting)";

/// Typical names, for "did you mean" suggestions.
const KNOWN: [&str; 11] = [
    "midpoint",
    "exact",
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
        Self::Rule(CoreMethod::Single(
            marsden::discrete::rules::BaseMethod::Midpoint,
        ))
    }

    /// Parses a method name; the error says what is wrong and may suggest a name.
    pub fn parse(name: &str) -> Result<Method, MethodError> {
        if name == EXACT {
            return Ok(Method::Exact);
        }
        CoreMethod::parse(name).map(Method::Rule).map_err(|e| {
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

    /// The classical order of the integrator (`None` for `exact`: no truncation error).
    pub fn order(&self) -> Option<u32> {
        match self {
            Method::Rule(m) => Some(m.order()),
            Method::Exact => None,
        }
    }

    /// The core's rule (`None` for `exact`).
    pub fn rule(&self) -> Option<&CoreMethod> {
        match self {
            Method::Rule(m) => Some(m),
            Method::Exact => None,
        }
    }

    /// Why the method cannot be used with holonomic constraints, if it cannot.
    pub fn constraint_refusal(&self) -> Option<String> {
        match self {
            Method::Rule(m) => m.constraint_refusal(),
            Method::Exact => Some(
                "`exact` shoots the unconstrained Euler–Lagrange equations: the core has no \
                 exact discrete Lagrangian on a constraint manifold"
                    .to_owned(),
            ),
        }
    }
}

/// Why a method cannot be used with holonomic constraints, in the words of the name the user
/// wrote ([`Method::constraint_refusal_as_written`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConstraintRefusal {
    /// `the method `<written>` cannot be used with constraints`.
    pub headline: String,
    /// Why, from the rule; it says which rule the written name is when the rule's own name
    /// differs (`galerkin-3-gauss-3` is `gauss-3`).
    pub note: String,
}

impl Method {
    /// [`Method::constraint_refusal`] naming the method as `written` (in a file or on the
    /// command line): several names parse to one rule (`galerkin-3-gauss-3` is `gauss-3`), and
    /// the user must recognise the name in the message.
    pub fn constraint_refusal_as_written(&self, written: &str) -> Option<ConstraintRefusal> {
        let reason = self.constraint_refusal()?;
        let (written, own) = (written.trim(), self.to_string());
        let note = match written == own {
            true => reason,
            false => format!("`{written}` is the rule `{own}`: {reason}"),
        };
        Some(ConstraintRefusal {
            headline: format!("the method `{written}` cannot be used with constraints"),
            note,
        })
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Method::Rule(m) => f.write_str(&m.name()),
            Method::Exact => f.write_str(EXACT),
        }
    }
}

/// `order 2`, or for `exact` what it is instead.
pub fn order_text(order: Option<u32>) -> String {
    order.map_or("the exact flow, by shooting".to_owned(), |p| {
        format!("order {p}")
    })
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
        assert_eq!(Method::parse("alpha-0.25").unwrap().order(), Some(1));
        assert_eq!(Method::parse("gauss-3").unwrap().order(), Some(6));
        assert_eq!(Method::parse("exact").unwrap(), Method::Exact);
        assert_eq!(Method::Exact.to_string(), "exact");
        assert_eq!(Method::Exact.order(), None);
    }

    /// The refusal with constraints names the method as written: `galerkin-3-gauss-3` and a
    /// composition of it, not only the rule's own name `gauss-3`.
    #[test]
    fn constraint_refusal_names_the_written_method() {
        for written in ["galerkin-3-gauss-3", "triple-jump-4(galerkin-2-gauss-2)"] {
            let refusal = Method::parse(written)
                .unwrap()
                .constraint_refusal_as_written(written)
                .unwrap();
            assert_eq!(
                refusal.headline,
                format!("the method `{written}` cannot be used with constraints")
            );
            assert!(
                refusal
                    .note
                    .starts_with(&format!("`{written}` is the rule `")),
                "{}",
                refusal.note
            );
        }
        let own = Method::parse("gauss-2")
            .unwrap()
            .constraint_refusal_as_written("gauss-2")
            .unwrap();
        assert!(own.note.starts_with("gauss-2 has no stage"), "{}", own.note);
        let lobatto = Method::parse("galerkin-2-lobatto-3").unwrap();
        assert_eq!(
            lobatto.constraint_refusal_as_written("galerkin-2-lobatto-3"),
            None
        );
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
