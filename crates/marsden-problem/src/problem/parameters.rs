//! `[system] parameters` and `coordinates`: values checked, builtin defaults filled in,
//! names checked before they become symbols of the expressions.

use std::ops::Range;

use toml::Spanned;

use super::check::{Checker, count_coordinates};
use super::raw::{RawParameter, RawSystem, SpannedList};
use crate::catalog::{Builtin, MASSES};
use crate::error::Diagnostic;
use crate::model::slots::velocity_name;
use marsden_expr::closest;
use marsden_expr::{is_identifier, is_reserved};

/// A scalar parameter as written.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    /// Its name.
    pub name: String,
    /// Its value (finite).
    pub value: f64,
    /// Where the value is.
    pub span: Range<usize>,
}

/// The parameters of a file, checked for finiteness and split into numbers and lists.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Parameters {
    /// `name = number`, in the file's order.
    pub numbers: Vec<Written>,
    /// `name = [numbers]`, in the file's order, with their spans.
    pub lists: Vec<(String, Vec<f64>, Range<usize>)>,
}

impl Parameters {
    /// Reads and checks `[system] parameters`.
    pub fn read(ck: &Checker<'_>, system: &RawSystem) -> Result<Self, Diagnostic> {
        let mut out = Parameters::default();
        let Some(table) = &system.parameters else {
            return Ok(out);
        };
        for (name, value) in &table.get_ref().0 {
            let what = format!("parameter `{name}`");
            match value.get_ref() {
                RawParameter::Number(v) => out.numbers.push(Written {
                    name: name.clone(),
                    value: ck.finite(&what, &Spanned::new(value.span(), *v))?,
                    span: value.span(),
                }),
                RawParameter::List(values) => {
                    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                        let msg = format!("{what}[{i}] is not a finite number ({v})");
                        return Err(ck.error(Some(value.span()), msg));
                    }
                    out.lists.push((name.clone(), values.clone(), value.span()));
                }
            }
        }
        Ok(out)
    }

    /// Fails on any list parameter (`what` says who only takes numbers).
    pub fn numbers_only(&self, ck: &Checker<'_>, what: &str) -> Result<(), Diagnostic> {
        match self.lists.first() {
            None => Ok(()),
            Some((name, _, span)) => Err(ck.error(
                Some(span.clone()),
                format!("parameter `{name}` is a list, but {what} takes numbers only"),
            )),
        }
    }

    /// The number called `name`, if written.
    pub fn number(&self, name: &str) -> Option<&Written> {
        self.numbers.iter().find(|w| w.name == name)
    }
}

/// A builtin's parameter values (defaults filled in), extra parameters for the expressions,
/// and the `nbody` masses.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltinParameters {
    /// The catalog parameters' values, in catalog order.
    pub values: Vec<f64>,
    /// Every scalar parameter (catalog first, then extras): the constants of the expressions.
    pub all: Vec<(String, f64)>,
    /// `nbody` masses (empty otherwise).
    pub masses: Vec<f64>,
}

/// Resolves the parameters of `builtin`. Parameters that are not the builtin's are allowed
/// only when an expression of the file (`used`) needs them; otherwise they are typos.
pub fn resolve_builtin(
    ck: &Checker<'_>,
    builtin: (Builtin, Range<usize>),
    params: &Parameters,
    used: &[String],
) -> Result<BuiltinParameters, Diagnostic> {
    let (builtin, span) = builtin;
    let catalog = builtin.parameters();
    let mut all: Vec<(String, f64)> = catalog
        .iter()
        .map(|p| {
            (
                p.name.to_owned(),
                params.number(p.name).map_or(p.default, |w| w.value),
            )
        })
        .collect();
    let values = all.iter().map(|(_, v)| *v).collect();
    for w in &params.numbers {
        if catalog.iter().any(|p| p.name == w.name) {
            continue;
        }
        if !used.contains(&w.name) {
            let names = catalog.iter().map(|p| p.name);
            let listed: Vec<String> = catalog
                .iter()
                .map(|p| format!("{} = {} ({})", p.name, p.default, p.doc))
                .collect();
            return Err(ck
                .error(
                    Some(w.span.clone()),
                    format!("unknown parameter `{}` for builtin `{}`", w.name, builtin.name()),
                )
                .suggest(closest(&w.name, names))
                .note(format!("parameters of {}: {}", builtin.name(), listed.join(", ")))
                .note("other parameters are allowed only where forces, constraints or symmetries use them"));
        }
        all.push((w.name.clone(), w.value));
    }
    let masses = masses(ck, builtin, span, params)?;
    Ok(BuiltinParameters {
        values,
        all,
        masses,
    })
}

fn masses(
    ck: &Checker<'_>,
    builtin: Builtin,
    span: Range<usize>,
    params: &Parameters,
) -> Result<Vec<f64>, Diagnostic> {
    let list = params.lists.iter().find(|(name, ..)| name == MASSES);
    if !builtin.needs_masses() {
        return params
            .numbers_only(ck, &format!("builtin `{}`", builtin.name()))
            .map(|_| vec![]);
    }
    if let Some((name, _, span)) = params.lists.iter().find(|(name, ..)| name != MASSES) {
        let msg = format!("unknown list parameter `{name}` for builtin `nbody` (only `masses`)");
        return Err(ck.error(Some(span.clone()), msg));
    }
    let Some((_, masses, list_span)) = list else {
        return Err(ck
            .error(Some(span), "builtin `nbody` needs the masses of its bodies")
            .help("add `masses = [1.0, 1e-3, …]` to `parameters`, one per body"));
    };
    if masses.is_empty() || masses.iter().any(|m| *m <= 0.0) {
        let msg = "`masses` must list at least one body, each mass positive";
        return Err(ck.error(Some(list_span.clone()), msg));
    }
    Ok(masses.clone())
}

/// The checked `coordinates` of `[system]` that the expression `key = text` is written in, or an
/// error at the expression naming `key`, with `help` (how the expression names its inputs).
///
/// # Errors
/// No `coordinates` in `[system]`, or a bad name in them ([`check_coordinates`]).
pub fn expression_coordinates(
    ck: &Checker<'_>,
    key: &str,
    text: &Spanned<String>,
    system: &RawSystem,
    help: &str,
) -> Result<Vec<String>, Diagnostic> {
    let Some(list) = &system.coordinates else {
        let message = format!("a `{key}` needs `coordinates` in [system]");
        return Err(ck.error(Some(text.span()), message).help(help.to_owned()));
    };
    check_coordinates(ck, list)
}

/// Checks coordinate names: identifiers, not built-in names, not `t`, unique, and no name is
/// another's velocity (`x` and `x_dot`).
pub fn check_coordinates(
    ck: &Checker<'_>,
    list: &SpannedList<String>,
) -> Result<Vec<String>, Diagnostic> {
    let names: Vec<String> = list.get_ref().iter().map(|s| s.get_ref().clone()).collect();
    if names.is_empty() {
        return Err(ck.error(Some(list.span()), "`coordinates` is empty"));
    }
    for (i, value) in list.get_ref().iter().enumerate() {
        let name = value.get_ref();
        let problem = if !is_identifier(name) {
            Some("is not a valid name (letters, digits and '_', not starting with a digit)")
        } else if is_reserved(name) || name == "t" {
            Some("is reserved (a built-in function or constant, or the time `t`)")
        } else if names[..i].contains(name) {
            Some("is listed twice")
        } else if names.iter().any(|other| velocity_name(other) == *name) {
            Some("clashes with the velocity of another coordinate")
        } else {
            None
        };
        if let Some(problem) = problem {
            return Err(ck.error(Some(value.span()), format!("coordinate `{name}` {problem}")));
        }
    }
    Ok(names)
}

/// The coordinates of a builtin, renamed by `coordinates` if the file gives them.
pub fn builtin_coordinates(
    ck: &Checker<'_>,
    builtin: Builtin,
    bodies: usize,
    given: Option<&SpannedList<String>>,
) -> Result<Vec<String>, Diagnostic> {
    let default = builtin.coordinates(bodies);
    let Some(list) = given else {
        return Ok(default);
    };
    let names = check_coordinates(ck, list)?;
    if names.len() != default.len() {
        let msg = format!(
            "`coordinates` lists {} names, but builtin `{}` has {}",
            names.len(),
            builtin.name(),
            count_coordinates(&default)
        );
        return Err(ck.error(Some(list.span()), msg));
    }
    Ok(names)
}
