//! `[[events]]`, `[output] observables` and `[output] section` → [`EventsSpec`].
//!
//! ```toml
//! [[events]]
//! name = "section"           # required, unique
//! when = "x"                 # g(t, q, v, p): coordinates, <name>_dot, p_<name>, t,
//!                            # parameters, observables
//! direction = "up"           # up, down or both (default)
//! action = "record"          # record (default) or stop
//! count = 3                  # optional: stop at (record up to) the n-th crossing, n >= 1
//! [output]
//! observables = { x2 = "l1*sin(a) + l2*sin(b)" }   # columns after the state
//! section = ["y", "p_y"]     # the Poincaré section plot's axes (default: q_1, p_1)
//! ```
//!
//! The crossings are located by the core's event detector (`marsden::run::events`), on the
//! Hermite interpolant of the step they lie in.

use marsden::run::events::{Action, Direction};
use marsden_expr::{Program, Symbols, is_identifier};
use serde::Deserialize;
use serde::de::{Deserializer, MapAccess, Visitor};
use toml::Spanned;

use super::check::Checker;
use super::raw::{RawProblem, SpannedList};
use super::spec::SystemSpec;
use crate::error::Diagnostic;
use crate::model::hamiltonian::momentum_name;
use crate::model::observables::WhenCode;
use crate::model::observables::state_inputs;
use crate::model::slots::velocity_name;
use crate::model::{ExprEvent, Observables};

/// One `[[events]]` table as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEvent {
    /// The event's name (the summary's key, the CSV's `event` index names it).
    pub name: Option<Spanned<String>>,
    /// `g(t, q, v, p)`, whose zeros are the events.
    pub when: Option<Spanned<String>>,
    /// `up`, `down` or `both`.
    pub direction: Option<Spanned<String>>,
    /// `record` or `stop`.
    pub action: Option<Spanned<String>>,
    /// Stop at (or record up to) the n-th crossing.
    pub count: Option<Spanned<i64>>,
}

/// `observables = { name = "expression", … }`, in the file's order, keys with their spans.
#[derive(Debug, Clone, PartialEq)]
pub struct RawObservables(pub Vec<(Spanned<String>, Spanned<String>)>);

impl<'de> Deserialize<'de> for RawObservables {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(ObservablesVisitor)
    }
}

struct ObservablesVisitor;

impl<'de> Visitor<'de> for ObservablesVisitor {
    type Value = RawObservables;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a table of names and expressions")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawObservables, A::Error> {
        let mut entries = Vec::new();
        while let Some(entry) = map.next_entry::<Spanned<String>, Spanned<String>>()? {
            entries.push(entry);
        }
        // The file's order (the deserializer hands a table over sorted by key).
        entries.sort_by_key(|(key, _)| key.span().start);
        Ok(RawObservables(entries))
    }
}

/// A checked event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventSpec {
    /// Its name.
    pub name: String,
    /// `g`, compiled against the state's inputs then the observables ([`ExprEvent`]).
    pub when: Program,
    /// Its native code, compiled at the first use.
    pub code: WhenCode,
    /// The crossings watched.
    pub direction: Direction,
    /// Record them, or stop the run.
    pub action: Action,
    /// Stop at (record up to) the n-th crossing.
    pub count: Option<usize>,
}

/// One axis of the Poincaré section plot: a coordinate or its momentum (the columns of the
/// event records).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SectionAxis {
    /// `q_i`.
    Position(usize),
    /// `p_i` (`p_<name>`).
    Momentum(usize),
}

impl SectionAxis {
    /// The column of the event records it reads: `q_<name>` or `p_<name>`.
    pub fn column(self, coordinates: &[String]) -> Option<String> {
        match self {
            SectionAxis::Position(i) => coordinates.get(i).map(|c| format!("q_{c}")),
            SectionAxis::Momentum(i) => coordinates.get(i).map(|c| momentum_name(c)),
        }
    }
}

/// `[output] section`: the pair of axes, with their names as written.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// Horizontal axis and its name.
    pub x: (SectionAxis, String),
    /// Vertical axis and its name.
    pub y: (SectionAxis, String),
}

/// The events, observables and section of a file (all empty for a file without them).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct EventsSpec {
    /// `[output] observables`.
    pub observables: Observables,
    /// `[[events]]`, in the file's order.
    pub events: Vec<EventSpec>,
    /// The section plot's axes (`None` only for a system without coordinates).
    pub section: Option<Section>,
}

impl EventsSpec {
    /// The event functions of the core's detector for a system of `n` coordinates, in the
    /// file's order (their native code compiled here, at its first use).
    pub fn functions(&self, n: usize) -> Vec<ExprEvent<'_>> {
        (self.events.iter())
            .map(|e| ExprEvent::new(&e.when, &e.code, &self.observables, n))
            .collect()
    }
}

/// Trajectory columns an observable may not be named after (or by their prefix).
const COLUMNS: [&str; 4] = [
    "t",
    "energy",
    "constraint_residual",
    "constraint_velocity_residual",
];
const PREFIXES: [&str; 4] = ["q_", "p_", "J_", "lambda_"];

/// Validates `[[events]]`, `[output] observables` and `[output] section` of `raw` for
/// `system`.
///
/// # Errors
/// A diagnostic pointing at the key or value at fault.
pub fn events(
    ck: &Checker<'_>,
    raw: &RawProblem,
    system: &SystemSpec,
) -> Result<EventsSpec, Diagnostic> {
    let output = raw.output.as_ref().map(|o| o.get_ref());
    let mut symbols = state_symbols(ck, system)?;
    let observables = match output.and_then(|o| o.observables.as_ref()) {
        Some(raw) => observables(ck, raw.get_ref(), &mut symbols, system)?,
        None => Observables::none(),
    };
    let raw_events = raw.events.as_deref().unwrap_or(&[]);
    if let (Some(first), false) = (raw_events.first(), system.has_energy()) {
        return Err(ck
            .error(
                Some(first.span()),
                "[[events]] needs a continuous Lagrangian",
            )
            .note(
                "events are located on the interpolant of each step, which needs the \
                 velocities v = FL⁻¹(q, p); a file's own `discrete_lagrangian` has no FL",
            ));
    }
    let mut events = Vec::with_capacity(raw_events.len());
    for (k, e) in raw_events.iter().enumerate() {
        let event = event(ck, e, k, &symbols)?;
        if let Some(twin) = events.iter().find(|x: &&EventSpec| x.name == event.name) {
            let span = e.get_ref().name.as_ref().map(|n| n.span());
            return Err(ck.error(span, format!("two events are named `{}`", twin.name)));
        }
        events.push(event);
    }
    let section = section(ck, output.and_then(|o| o.section.as_ref()), system)?;
    Ok(EventsSpec {
        observables,
        events,
        section,
    })
}

/// The state's inputs (`q`, `q̇`, `p`, `t`) and the parameters as constants.
fn state_symbols(ck: &Checker<'_>, system: &SystemSpec) -> Result<Symbols, Diagnostic> {
    let inputs = state_inputs(&system.coordinates);
    let mut symbols = Symbols::with_inputs(&inputs).map_err(|e| ck.error(None, e.to_string()))?;
    for (name, value) in &system.parameters {
        // A parameter named like a momentum (`p_x`) stays the momentum here.
        if !inputs.contains(name) {
            symbols
                .add_constant(name, *value)
                .map_err(|e| ck.error(None, format!("parameter `{name}`: {e}")))?;
        }
    }
    Ok(symbols)
}

/// What an existing name of the symbol table is, for a message.
fn what_is(name: &str, symbols: &Symbols, system: &SystemSpec) -> Option<String> {
    let c = &system.coordinates;
    if c.iter().any(|c| c == name) {
        Some(format!("the coordinate `{name}`"))
    } else if c.iter().any(|c| velocity_name(c) == name) {
        Some(format!("the velocity `{name}`"))
    } else if c.iter().any(|c| momentum_name(c) == name) {
        Some(format!("the momentum `{name}`"))
    } else if name == "t" {
        Some("the time `t`".to_owned())
    } else {
        symbols.get(name).map(|_| format!("the parameter `{name}`"))
    }
}

/// Compiles the observables in order, each added to `symbols` as the next input slot.
fn observables(
    ck: &Checker<'_>,
    raw: &RawObservables,
    symbols: &mut Symbols,
    system: &SystemSpec,
) -> Result<Observables, Diagnostic> {
    let mut out = Observables::none();
    let state = symbols.clone();
    let slot = symbols.input_count();
    for (key, value) in &raw.0 {
        let name = key.get_ref();
        let at = |message: String| ck.error(Some(key.span()), message);
        if let Some(what) = what_is(name, &state, system) {
            return Err(at(format!("the observable `{name}` shadows {what}"))
                .help("give the observable another name"));
        }
        if COLUMNS.contains(&name.as_str()) || PREFIXES.iter().any(|p| name.starts_with(p)) {
            return Err(at(format!(
                "the observable `{name}` has the name of a trajectory column"
            ))
            .note("the trajectory's columns are t, q_<name>, p_<name>, energy, J_<name>, constraint_residual, lambda_<i>, constraint_velocity_residual")
            .help("give the observable another name"));
        }
        if !is_identifier(name) {
            return Err(at(format!(
                "the observable `{name}` is not a name (letters, digits and `_`, not starting with a digit)"
            )));
        }
        let context = format!("[output] observables.{name}");
        let program = ck
            .parse_expr(&context, value)?
            .compile(&state)
            .map_err(|e| ck.expr_error(&context, value, &e))?;
        symbols
            .add_input(name, slot + out.len())
            .map_err(|e| at(format!("the observable `{name}`: {e}")))?;
        out.names.push(name.clone());
        out.programs.push(program);
    }
    Ok(out)
}

/// One `[[events]]` table.
fn event(
    ck: &Checker<'_>,
    raw: &Spanned<RawEvent>,
    k: usize,
    symbols: &Symbols,
) -> Result<EventSpec, Diagnostic> {
    let e = raw.get_ref();
    let missing = |key: &str, help: &str| {
        ck.error(Some(raw.span()), format!("event #{} has no `{key}`", k + 1))
            .help(help.to_owned())
    };
    let name = e
        .name
        .as_ref()
        .ok_or_else(|| missing("name", "e.g. `name = \"pericentre\"`"))?;
    if !is_identifier(name.get_ref()) {
        return Err(ck.error(
            Some(name.span()),
            format!(
                "the event name `{}` is not a name (letters, digits and `_`, not starting with a digit)",
                name.get_ref()
            ),
        ));
    }
    let label = name.get_ref().clone();
    let when = e
        .when
        .as_ref()
        .ok_or_else(|| missing("when", "e.g. `when = \"x\"`: the events are the zeros of x"))?;
    let context = format!("[[events]] `{label}` when");
    let program = ck
        .parse_expr(&context, when)?
        .compile(symbols)
        .map_err(|err| ck.expr_error(&context, when, &err))?;
    let direction = match e.direction.as_ref() {
        None => Direction::Both,
        Some(d) => match d.get_ref().as_str() {
            "up" => Direction::Up,
            "down" => Direction::Down,
            "both" => Direction::Both,
            other => {
                return Err(ck
                    .error(Some(d.span()), format!("unknown direction `{other}`"))
                    .help("`up` (g rises through 0), `down` (g falls through 0) or `both`"));
            }
        },
    };
    let action = match e.action.as_ref() {
        None => Action::Record,
        Some(a) => match a.get_ref().as_str() {
            "record" => Action::Record,
            "stop" => Action::Stop,
            other => {
                return Err(ck
                    .error(Some(a.span()), format!("unknown action `{other}`"))
                    .help("`record` (write each crossing to events.csv) or `stop` (end the run there)"));
            }
        },
    };
    let count = match e.count.as_ref() {
        None => None,
        Some(c) if *c.get_ref() >= 1 => usize::try_from(*c.get_ref()).ok(),
        Some(c) => {
            return Err(ck
                .error(
                    Some(c.span()),
                    format!("`count` must be at least 1 (got {})", c.get_ref()),
                )
                .help("count = n stops at (or records up to) the n-th crossing; leave it out for no limit"));
        }
    };
    Ok(EventSpec {
        name: label,
        when: program,
        code: WhenCode::default(),
        direction,
        action,
        count,
    })
}

/// `[output] section`, or its default (the first coordinate and its momentum).
fn section(
    ck: &Checker<'_>,
    raw: Option<&SpannedList<String>>,
    system: &SystemSpec,
) -> Result<Option<Section>, Diagnostic> {
    let c = &system.coordinates;
    let Some(raw) = raw else {
        return Ok(c.first().map(|first| Section {
            x: (SectionAxis::Position(0), first.clone()),
            y: (SectionAxis::Momentum(0), momentum_name(first)),
        }));
    };
    let list = raw.get_ref();
    if list.len() != 2 {
        return Err(ck
            .error(
                Some(raw.span()),
                format!("`section` names {} axes, not 2", list.len()),
            )
            .help("e.g. `section = [\"y\", \"p_y\"]`"));
    }
    let axis = |s: &Spanned<String>| -> Result<(SectionAxis, String), Diagnostic> {
        let name = s.get_ref();
        let find = |f: &dyn Fn(&String) -> bool| c.iter().position(f);
        let axis = find(&|c| c == name)
            .map(SectionAxis::Position)
            .or_else(|| find(&|c| &momentum_name(c) == name).map(SectionAxis::Momentum));
        match axis {
            Some(a) => Ok((a, name.clone())),
            None => Err(ck
                .error(
                    Some(s.span()),
                    format!("`section` names `{name}`, which is not a coordinate or a momentum"),
                )
                .help(format!(
                    "the section's axes are among {} (the columns of events.csv)",
                    what_names(c).join(", ")
                ))),
        }
    };
    Ok(Some(Section {
        x: axis(&list[0])?,
        y: axis(&list[1])?,
    }))
}

/// The names an axis may take.
fn what_names(coordinates: &[String]) -> Vec<String> {
    let q = coordinates.iter().cloned();
    q.chain(coordinates.iter().map(|c| momentum_name(c)))
        .collect()
}
