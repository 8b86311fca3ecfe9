//! The bad inputs of `[[events]]`, `[output] observables` and `section`: each refused with its
//! message, pointing at the key or value at fault.

use crate::problem::{Overrides, from_toml_str};
use crate::{Diagnostic, RunSpec};
use marsden::run::events::{Action, Direction};

const HEAD: &str = "[system]
coordinates = [\"x\", \"y\"]
parameters = { k = 2.0 }
lagrangian = \"0.5*(x_dot^2 + y_dot^2) - 0.5*k*(x^2 + y^2)\"
[initial]
q = [1.0, 0.0]
v = [0.0, 1.0]
[integrator]
h = 0.1
steps = 10
";

fn load(tail: &str) -> Result<RunSpec, Diagnostic> {
    from_toml_str(
        &format!("{HEAD}{tail}"),
        "events.toml",
        &Overrides::default(),
    )
}

/// The diagnostic of `tail`, and the text its caret underlines.
fn refused(tail: &str) -> (Diagnostic, String) {
    let d = load(tail).expect_err("accepted");
    let at = d.location.as_ref().expect("no location");
    let underlined: String = (at.source_line.chars())
        .skip(at.column - 1)
        .take(at.width)
        .collect();
    (d, underlined)
}

#[test]
fn reads_events_observables_and_the_section() {
    let spec = load(
        "[output]
observables = { s = \"x*p_y - y*p_x + t*k\", r2 = \"x^2 + y^2\" }
section = [\"y\", \"p_x\"]
[[events]]
name = \"cross\"
when = \"r2 - 0.5\"
direction = \"down\"
action = \"stop\"
count = 2
[[events]]
name = \"plain\"
when = \"x\"
",
    )
    .unwrap();
    let e = &spec.events;
    assert_eq!(e.observables.names, ["s", "r2"], "the file's order");
    assert_eq!(e.events.len(), 2);
    let (cross, plain) = (&e.events[0], &e.events[1]);
    assert_eq!(
        (cross.direction, cross.action, cross.count),
        (Direction::Down, Action::Stop, Some(2))
    );
    assert_eq!(
        (plain.direction, plain.action, plain.count),
        (Direction::Both, Action::Record, None)
    );
    let section = e.section.as_ref().unwrap();
    assert_eq!(section.x.1, "y");
    assert_eq!(section.y.1, "p_x");
    // `cross` reads the observable r2 = x² + y² at (x, y) = (1, 2): 5 − 0.5.
    let g = marsden::run::events::EventFunction::value(
        &e.functions(2)[0],
        0.0,
        &[1.0, 2.0],
        &[0.0; 2],
        &[0.0; 2],
    );
    assert_eq!(g, 4.5);
}

#[test]
fn without_events_the_spec_is_empty_and_the_section_defaults_to_q1_p1() {
    let spec = load("").unwrap();
    assert!(spec.events.events.is_empty() && spec.events.observables.is_empty());
    let section = spec.events.section.unwrap();
    assert_eq!((section.x.1.as_str(), section.y.1.as_str()), ("x", "p_x"));
}

#[test]
fn an_event_naming_an_unknown_symbol() {
    let (d, at) = refused("[[events]]\nname = \"e\"\nwhen = \"x - zz\"\n");
    assert!(d.message.contains("[[events]] `e` when"), "{d}");
    assert!(d.message.contains("zz"), "{d}");
    assert_eq!(at, "zz");
}

#[test]
fn a_direction_that_does_not_exist() {
    let (d, at) = refused("[[events]]\nname = \"e\"\nwhen = \"x\"\ndirection = \"upward\"\n");
    assert_eq!(d.message, "unknown direction `upward`");
    assert_eq!(at, "\"upward\"");
}

#[test]
fn an_action_that_does_not_exist() {
    let (d, at) = refused("[[events]]\nname = \"e\"\nwhen = \"x\"\naction = \"halt\"\n");
    assert_eq!(d.message, "unknown action `halt`");
    assert_eq!(at, "\"halt\"");
}

#[test]
fn a_count_of_zero() {
    let (d, at) = refused("[[events]]\nname = \"e\"\nwhen = \"x\"\ncount = 0\n");
    assert_eq!(d.message, "`count` must be at least 1 (got 0)");
    assert_eq!(at, "0");
}

#[test]
fn an_event_without_a_name_or_when_and_two_of_one_name() {
    let (d, _) = refused("[[events]]\nwhen = \"x\"\n");
    assert_eq!(d.message, "event #1 has no `name`");
    let (d, _) = refused("[[events]]\nname = \"e\"\n");
    assert_eq!(d.message, "event #1 has no `when`");
    let (d, at) =
        refused("[[events]]\nname = \"e\"\nwhen = \"x\"\n[[events]]\nname = \"e\"\nwhen = \"y\"\n");
    assert_eq!(d.message, "two events are named `e`");
    assert_eq!(at, "\"e\"");
}

#[test]
fn an_observable_naming_an_unknown_symbol() {
    let (d, at) = refused("[output]\nobservables = { r = \"x + w\" }\n");
    assert!(d.message.contains("[output] observables.r"), "{d}");
    assert_eq!(at, "w");
}

#[test]
fn an_observable_shadowing_a_coordinate_a_momentum_or_a_parameter() {
    let (d, at) = refused("[output]\nobservables = { x = \"y\" }\n");
    assert_eq!(d.message, "the observable `x` shadows the coordinate `x`");
    assert_eq!(at, "x");
    let (d, _) = refused("[output]\nobservables = { p_y = \"y\" }\n");
    assert_eq!(d.message, "the observable `p_y` shadows the momentum `p_y`");
    let (d, _) = refused("[output]\nobservables = { k = \"y\" }\n");
    assert_eq!(d.message, "the observable `k` shadows the parameter `k`");
    let (d, _) = refused("[output]\nobservables = { energy = \"y\" }\n");
    assert_eq!(
        d.message,
        "the observable `energy` has the name of a trajectory column"
    );
}

#[test]
fn a_section_axis_that_is_not_a_state_name() {
    let (d, at) = refused("[output]\nsection = [\"x\", \"p_z\"]\n");
    assert!(d.message.contains("`p_z`"), "{d}");
    assert_eq!(at, "\"p_z\"");
    let (d, _) = refused("[output]\nsection = [\"x\"]\n");
    assert_eq!(d.message, "`section` names 1 axes, not 2");
}

#[test]
fn events_and_observables_are_refused_in_a_sweep() {
    let sweep = "[sweep]\nparameter = \"k\"\nvalues = [1.0, 2.0]\n";
    let (d, _) = refused(&format!("{sweep}[[events]]\nname = \"e\"\nwhen = \"x\"\n"));
    assert!(d.message.starts_with("[[events]] cannot be used"), "{d}");
}
