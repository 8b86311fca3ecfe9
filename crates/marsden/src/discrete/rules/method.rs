//! Methods by name: every rule of [`crate::discrete::rules`] as a value chosen at run time.
//!
//! [`Rule`] has generic associated types, so a rule chosen from a string cannot be a trait
//! object; [`Method`] is the closed set of rules. [`Method::dispatch`] calls a generic
//! [`WithRule`] visitor with the concrete rule (one monomorphised copy per rule type); a
//! [`Method`] is also a [`Rule`] itself ([`super::chosen`]: one copy for all rules, the same
//! numbers).
//!
//! Names (the grammar of [`METHOD_GRAMMAR`]):
//!
//! | name | rule | order |
//! |---|---|---|
//! | `midpoint`, `trapezoid` | [`Midpoint`], [`Trapezoid`] | 2 |
//! | `alpha-<a>`, `symmetrized-<a>` (0 ≤ a ≤ 1) | [`GeneralizedMidpoint`], [`SymmetrizedMidpoint`] | 1 (2 at a = ½), 2 |
//! | `gauss-<s>` (1 ≤ s ≤ 10) | [`Galerkin::gauss`]: `P_s`, s Gauss points | 2s |
//! | `lobatto-<s>` (2 ≤ s ≤ 11) | [`Galerkin::lobatto`]: `P_{s−1}`, s Lobatto points | 2s − 2 |
//! | `galerkin-<s>-gauss-<r>`, `galerkin-<s>-lobatto-<r>` | [`Galerkin::new`] | min(2s, 2r), min(2s, 2r − 2) |
//! | `<scheme>(<base>)`, e.g. `kahan-li-6(trapezoid)` | [`Composition`] of a base above | the scheme's |

use super::composition::{Composition, CompositionScheme};
use super::galerkin::{Galerkin, MAX_DEGREE};
use super::quadrature::{MAX_POINTS, QuadratureFamily};
use super::{GeneralizedMidpoint, Midpoint, Rule, SymmetrizedMidpoint, Trapezoid};
use crate::error::Error;
use crate::error::InputError;

/// The grammar of method names, for messages and `--help`.
pub const METHOD_GRAMMAR: &str = "midpoint, trapezoid, alpha-<a>, symmetrized-<a> (0 <= a <= 1), \
     gauss-<s> (1 <= s <= 10), lobatto-<s> (2 <= s <= 11), galerkin-<s>-gauss-<r>, \
     galerkin-<s>-lobatto-<r> (r >= s), and <scheme>(<base>) with a scheme among triple-jump-<p> \
     (p = 4, 6, 8, 10), suzuki-4, yoshida-6, kahan-li-6, suzuki-umeno-8 and a base above \
     (e.g. kahan-li-6(trapezoid))";

/// A one-step rule (anything but a composition).
#[derive(Debug, Clone, PartialEq)]
pub enum BaseMethod {
    /// [`Midpoint`].
    Midpoint,
    /// [`Trapezoid`].
    Trapezoid,
    /// [`GeneralizedMidpoint`] with this α.
    Alpha(f64),
    /// [`SymmetrizedMidpoint`] with this α.
    Symmetrized(f64),
    /// A [`Galerkin`] rule.
    Galerkin(Galerkin),
}

/// A rule chosen by name.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// A one-step rule.
    Single(BaseMethod),
    /// A composition of a one-step rule.
    Composed(CompositionScheme, BaseMethod),
}

/// A computation generic over the rule, run by [`Method::dispatch`].
pub trait WithRule {
    /// What the computation returns.
    type Output;
    /// Runs with the concrete rule.
    fn call<R: Rule>(self, rule: &R) -> Self::Output;
}

fn unknown(name: &str, reason: impl Into<String>) -> Error {
    Error::Input(InputError::UnknownMethod {
        name: name.to_owned(),
        reason: reason.into(),
        valid: METHOD_GRAMMAR.to_owned(),
    })
}

/// A whole-number argument of a method name; `what` and `valid` name it and its accepted range
/// for the message when it is too large to be one (more digits than any count can have).
fn parse_count(text: &str, name: &str, what: &str, valid: &str) -> Result<usize, Error> {
    text.parse::<usize>().map_err(|_| {
        let digits = !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit());
        match digits {
            true => unknown(name, format!("the {what} {text} is too large: {valid}")),
            false => unknown(name, format!("`{text}` is not a whole number")),
        }
    })
}

/// The accepted stage counts of `gauss-<s>`.
fn gauss_range() -> String {
    format!("gauss-<s> takes 1 ≤ s ≤ {MAX_DEGREE}")
}

/// The accepted stage counts of `lobatto-<s>`.
fn lobatto_range() -> String {
    format!("lobatto-<s> takes 2 ≤ s ≤ {}", MAX_DEGREE + 1)
}

fn parse_alpha(text: &str, name: &str) -> Result<f64, Error> {
    match text.parse::<f64>() {
        Ok(a) if (0.0..=1.0).contains(&a) => Ok(a),
        _ => Err(unknown(name, "the parameter must be a number in [0, 1]")),
    }
}

impl BaseMethod {
    /// Parses a one-step method name.
    pub fn parse(name: &str) -> Result<Self, Error> {
        match name {
            "midpoint" => return Ok(Self::Midpoint),
            "trapezoid" => return Ok(Self::Trapezoid),
            _ => {}
        }
        let Some((family, rest)) = name.split_once('-') else {
            return Err(unknown(name, "no such method"));
        };
        match family {
            "alpha" => parse_alpha(rest, name).map(Self::Alpha),
            "symmetrized" => parse_alpha(rest, name).map(Self::Symmetrized),
            "gauss" => {
                let s = parse_count(rest, name, "number of stages", &gauss_range())?;
                Galerkin::gauss(s).map(Self::Galerkin)
            }
            "lobatto" => {
                let s = parse_count(rest, name, "number of stages", &lobatto_range())?;
                Galerkin::lobatto(s).map(Self::Galerkin)
            }
            "galerkin" => parse_galerkin(rest, name).map(Self::Galerkin),
            _ => Err(unknown(name, "no such method")),
        }
    }

    /// The method's name (parses back to the same method).
    pub fn name(&self) -> String {
        match self {
            Self::Alpha(a) => format!("alpha-{a}"),
            Self::Symmetrized(a) => format!("symmetrized-{a}"),
            _ => self.dispatch(NameOf),
        }
    }

    /// Calls `visitor` with the concrete rule.
    pub fn dispatch<V: WithRule>(&self, visitor: V) -> V::Output {
        match self {
            Self::Midpoint => visitor.call(&Midpoint),
            Self::Trapezoid => visitor.call(&Trapezoid),
            Self::Alpha(alpha) => visitor.call(&GeneralizedMidpoint { alpha: *alpha }),
            Self::Symmetrized(alpha) => visitor.call(&SymmetrizedMidpoint { alpha: *alpha }),
            Self::Galerkin(g) => visitor.call(g),
        }
    }
}

/// `<s>-gauss-<r>` or `<s>-lobatto-<r>`.
fn parse_galerkin(rest: &str, name: &str) -> Result<Galerkin, Error> {
    let parts: Vec<&str> = rest.split('-').collect();
    let [s, family, r] = parts.as_slice() else {
        return Err(unknown(
            name,
            "expected galerkin-<s>-gauss-<r> or galerkin-<s>-lobatto-<r>",
        ));
    };
    let family = match *family {
        "gauss" => QuadratureFamily::Gauss,
        "lobatto" => QuadratureFamily::Lobatto,
        other => return Err(unknown(name, format!("no quadrature family `{other}`"))),
    };
    let degrees = format!("the degree s is at most {MAX_DEGREE}");
    let points = format!("the number of points r is at most {MAX_POINTS}");
    let s = parse_count(s, name, "degree", &degrees)?;
    let r = parse_count(r, name, "number of quadrature points", &points)?;
    if s > MAX_DEGREE {
        return Err(unknown(
            name,
            format!("the degree must be at most {MAX_DEGREE}"),
        ));
    }
    Galerkin::new(s, family, r)
}

/// Why `scheme` is not a composition scheme: an order `triple-jump-<p>` does not take (too
/// large, odd, below 4), or no such name.
fn no_scheme(scheme: &str) -> String {
    let order = scheme.strip_prefix("triple-jump-");
    match order.filter(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit())) {
        Some(p) => format!("triple-jump-<p> takes the orders p = 4, 6, 8, 10, not {p}"),
        None => format!(
            "no composition scheme `{scheme}` (valid: {})",
            CompositionScheme::valid_names()
        ),
    }
}

impl Method {
    /// Parses a method name (see the module docs).
    ///
    /// # Errors
    /// [`crate::error::InputError::UnknownMethod`] with the valid grammar, or the rule's own
    /// error ([`crate::error::InputError::InvalidGalerkin`],
    /// [`crate::error::InputError::InvalidQuadrature`]) for inconsistent parameters.
    pub fn parse(name: &str) -> Result<Self, Error> {
        let name = name.trim();
        if let Some(inner) = name.strip_suffix(')') {
            let Some((scheme, base)) = inner.split_once('(') else {
                return Err(unknown(name, "unbalanced parentheses"));
            };
            let scheme =
                CompositionScheme::parse(scheme).map_err(|_| unknown(name, no_scheme(scheme)))?;
            if base.contains('(') {
                return Err(unknown(
                    name,
                    "compositions of compositions are not supported",
                ));
            }
            return Ok(Self::Composed(scheme, BaseMethod::parse(base)?));
        }
        BaseMethod::parse(name).map(Self::Single)
    }

    /// Calls `visitor` with the concrete rule.
    pub fn dispatch<V: WithRule>(&self, visitor: V) -> V::Output {
        match self {
            Self::Single(base) => base.dispatch(visitor),
            Self::Composed(scheme, base) => base.dispatch(Compose {
                scheme: *scheme,
                visitor,
            }),
        }
    }

    /// The method's name (parses back to the same method).
    pub fn name(&self) -> String {
        match self {
            Self::Single(base) => base.name(),
            Self::Composed(scheme, base) => format!("{}({})", scheme.name(), base.name()),
        }
    }

    /// The classical order of the method.
    pub fn order(&self) -> u32 {
        self.dispatch(OrderOf)
    }

    /// Why the method cannot impose holonomic constraints at its order, if it cannot (Gauss
    /// rules: [`crate::discrete::DiscreteAction::constrained_stages`]); with constraints every
    /// other method keeps [`Method::order`].
    pub fn constraint_refusal(&self) -> Option<String> {
        self.dispatch(RefusalOf)
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self, Error> {
        Self::parse(s)
    }
}

/// Wraps a visitor so that it receives the composition of the base rule.
struct Compose<V> {
    scheme: CompositionScheme,
    visitor: V,
}

impl<V: WithRule> WithRule for Compose<V> {
    type Output = V::Output;
    fn call<R: Rule>(self, rule: &R) -> V::Output {
        // Rules are small values (a Galerkin rule holds an `Arc`); the clone is cheap.
        let composed = Composition::new(RuleRef(rule), self.scheme);
        self.visitor.call(&composed)
    }
}

/// A borrowed rule used as a rule (so compositions need no `Clone` bound on the base).
struct RuleRef<'a, R>(&'a R);

impl<R: Rule> Rule for RuleRef<'_, R> {
    type Discrete<L: crate::mechanics::Lagrangian> = R::Discrete<L>;
    type DiscreteForce<F: crate::mechanics::Force> = R::DiscreteForce<F>;
    fn discretize<L: crate::mechanics::Lagrangian>(&self, lagrangian: L) -> Self::Discrete<L> {
        self.0.discretize(lagrangian)
    }
    fn discretize_force<F: crate::mechanics::Force>(
        &self,
        force: F,
        dof: usize,
    ) -> Self::DiscreteForce<F> {
        self.0.discretize_force(force, dof)
    }
    fn name(&self) -> String {
        self.0.name()
    }
    fn order(&self) -> u32 {
        self.0.order()
    }
}

struct NameOf;

impl WithRule for NameOf {
    type Output = String;
    fn call<R: Rule>(self, rule: &R) -> String {
        rule.name()
    }
}

struct OrderOf;

impl WithRule for OrderOf {
    type Output = u32;
    fn call<R: Rule>(self, rule: &R) -> u32 {
        rule.order()
    }
}

struct RefusalOf;

impl WithRule for RefusalOf {
    type Output = Option<String>;
    fn call<R: Rule>(self, rule: &R) -> Option<String> {
        use crate::discrete::DiscreteAction;
        rule.discretize(Probe).constrained_stages().err()
    }
}

/// `L = ½v²` in one dimension: asks a rule for its stage constraints (they do not depend on
/// the Lagrangian).
struct Probe;

impl crate::mechanics::Lagrangian for Probe {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: crate::scalar::Scalar>(&self, _t: S, _q: &[S], v: &[S]) -> S {
        v[0] * v[0] * 0.5
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_with_orders() {
        let cases = [
            ("midpoint", 2),
            ("trapezoid", 2),
            ("alpha-0.25", 1),
            ("symmetrized-0.25", 2),
            ("gauss-3", 6),
            ("lobatto-4", 6),
            ("galerkin-2-gauss-3", 4),
            ("kahan-li-6(trapezoid)", 6),
            ("suzuki-umeno-8(trapezoid)", 8),
            ("triple-jump-4(midpoint)", 4),
            ("triple-jump-6(gauss-2)", 6),
        ];
        for (name, order) in cases {
            let m = Method::parse(name).unwrap();
            assert_eq!((m.name().as_str(), m.order()), (name, order));
        }
    }

    #[test]
    fn rejections_list_the_valid_choices() {
        for bad in [
            "gauss-0",
            "gauss-x",
            "lobatto-1",
            "galerkin-4-gauss-3",
            "galerkin-2-radau-3",
            "rk4",
            "yoshida-5(trapezoid)",
            "kahan-li-6(kahan-li-6(trapezoid))",
            "alpha-2",
        ] {
            let e = Method::parse(bad).unwrap_err();
            let message = e.to_string();
            assert!(
                message.contains("valid") || message.contains("valid choices"),
                "{bad}: {message}"
            );
        }
        assert!(matches!(
            Method::parse("galerkin-4-gauss-3"),
            Err(Error::Input(InputError::InvalidGalerkin { .. }))
        ));
    }

    /// Counts with more digits than a `usize` holds are too large, with the accepted range
    /// (not "not a whole number").
    #[test]
    fn huge_counts_are_too_large_with_the_accepted_range() {
        let huge = "99999999999999999999";
        let cases = [
            (format!("gauss-{huge}"), "1 ≤ s ≤ 10"),
            (format!("lobatto-{huge}"), "2 ≤ s ≤ 11"),
            (format!("galerkin-{huge}-gauss-3"), "at most 10"),
            (format!("galerkin-2-lobatto-{huge}"), "at most 24"),
            (format!("kahan-li-6(gauss-{huge})"), "1 ≤ s ≤ 10"),
        ];
        for (name, range) in cases {
            let message = Method::parse(&name).unwrap_err().to_string();
            assert!(message.contains("too large"), "{name}: {message}");
            assert!(message.contains(range), "{name}: {message}");
            assert!(!message.contains("not a whole number"), "{name}: {message}");
        }
        let message = Method::parse(&format!("triple-jump-{huge}(midpoint)"))
            .unwrap_err()
            .to_string();
        assert!(message.contains("p = 4, 6, 8, 10, not"), "{message}");
        let message = Method::parse("gauss-x").unwrap_err().to_string();
        assert!(message.contains("not a whole number"), "{message}");
    }
}
