//! Every bad input of `[optimal_control]` and `[system] controls`: the message and the text the
//! caret points at.

use super::*;
use crate::problem::Overrides;

/// The double integrator ([OJM11] §5's simplest case: L = ½q̇², f = u, C = ½u²).
const GOOD: &str = r#"
[system]
coordinates = ["x"]
lagrangian = "0.5*x_dot^2"
controls = ["u"]
forces = ["u"]
[optimal_control]
cost = "0.5*u^2"
t_end = 1.0
steps = 20
start = { q = [0.0], v = [0.0] }
end = { q = [1.0], v = [0.0] }
"#;

fn check(text: &str) -> Result<OptimalControlSpec, Diagnostic> {
    from_toml_str(text, "oc.toml", &Overrides::default())
}

/// The rendered error and the source text under its caret.
fn refused(text: &str) -> (String, String) {
    let e = check(text).expect_err("should be refused").to_string();
    let lines: Vec<&str> = e.lines().collect();
    let caret = lines
        .iter()
        .position(|l| l.trim_start().starts_with('|') && l.contains('^'))
        .unwrap_or_else(|| panic!("no caret in\n{e}"));
    let source = lines[caret - 1];
    let bar = source.find("| ").unwrap() + 2;
    let marks = lines[caret];
    let start = marks.find('^').unwrap();
    let end = marks.rfind('^').unwrap() + 1;
    let under = source
        .get(start.max(bar)..end.min(source.len()))
        .unwrap_or("")
        .to_owned();
    (e.clone(), under)
}

fn edit(from: &str, to: &str) -> String {
    assert!(GOOD.contains(from), "{from}");
    GOOD.replacen(from, to, 1)
}

#[test]
fn reads_the_double_integrator() {
    let spec = check(GOOD).unwrap();
    assert_eq!(spec.controls, ["u"]);
    assert_eq!((spec.t0, spec.t_end, spec.steps), (0.0, 1.0, 20));
    assert_eq!(spec.start.q, [Some(0.0)]);
    assert_eq!(spec.end.rate, RateSpec::Velocity(vec![Some(0.0)]));
    assert_eq!(spec.guess, GuessKind::Simulation);
    assert!(!spec.control_bounds.any());
    // The force reads u from the slot after [x, x_dot, t].
    assert_eq!(spec.force.eval(&[0.0, 0.0, 0.0, 2.5]), [2.5]);
    assert_eq!(spec.cost.eval(&[0.0, 0.0, 0.0, 2.0]), 2.0);
}

#[test]
fn free_components_and_bounds() {
    let text = edit(
        "end = { q = [1.0], v = [0.0] }",
        "end = { q = [1.0], p = [\"free\"] }",
    ) + "[optimal_control.bounds]\nu = [-2, 3]\nx = [-1, 2]\n";
    let spec = check(&text).unwrap();
    assert_eq!(spec.end.rate, RateSpec::Momentum(vec![None]));
    assert_eq!(
        (spec.control_bounds.lower[0], spec.control_bounds.upper[0]),
        (-2.0, 3.0)
    );
    assert_eq!(
        (spec.state_bounds.lower[0], spec.state_bounds.upper[0]),
        (-1.0, 2.0)
    );
}

#[test]
fn refuses_a_control_no_force_uses() {
    let text = edit("controls = [\"u\"]", "controls = [\"u\", \"w\"]");
    let (e, under) = refused(&text);
    assert!(e.contains("control `w` is not used by any force"), "{e}");
    assert_eq!(under, "\"w\"");
}

#[test]
fn refuses_a_cost_with_an_unknown_symbol() {
    let (e, under) = refused(&edit("cost = \"0.5*u^2\"", "cost = \"0.5*v^2\""));
    assert!(e.contains("in [optimal_control] cost"), "{e}");
    assert!(e.contains("`v`"), "{e}");
    assert_eq!(under, "v");
}

#[test]
fn refuses_both_velocity_and_momentum_at_an_end() {
    let (e, under) = refused(&edit(
        "end = { q = [1.0], v = [0.0] }",
        "end = { q = [1.0], v = [0.0], p = [0.0] }",
    ));
    assert!(e.contains("`end` gives both `v` and `p`"), "{e}");
    assert_eq!(under, "[0.0]");
}

#[test]
fn refuses_bounds_with_lower_above_upper() {
    let (e, under) = refused(&(GOOD.to_owned() + "[optimal_control.bounds]\nu = [2.0, -2.0]\n"));
    assert!(
        e.contains("bounds on `u`: the lower bound 2 is above the upper bound -2"),
        "{e}"
    );
    assert_eq!(under, "[2.0, -2.0]");
}

#[test]
fn refuses_bounds_on_an_unknown_name() {
    let (e, _) = refused(&(GOOD.to_owned() + "[optimal_control.bounds]\nuu = [-1, 1]\n"));
    assert!(e.contains("neither a control nor a coordinate"), "{e}");
    assert!(e.contains("controls: u; coordinates: x"), "{e}");
}

#[test]
fn refuses_wrong_lengths_and_partial_velocities() {
    let (e, under) = refused(&edit(
        "start = { q = [0.0], v = [0.0] }",
        "start = { q = [0.0, 1.0], v = [0.0] }",
    ));
    assert!(
        e.contains("start q has 2 values, but the system has 1 coordinate (x)"),
        "{e}"
    );
    assert_eq!(under, "[0.0, 1.0]");
    let two = GOOD
        .replace("[\"x\"]", "[\"x\", \"y\"]")
        .replace("0.5*x_dot^2", "0.5*x_dot^2 + 0.5*y_dot^2")
        .replace("forces = [\"u\"]", "forces = [\"u\", \"0\"]")
        .replace(
            "start = { q = [0.0], v = [0.0] }",
            "start = { q = [0.0, 0.0], v = [0.0, \"free\"] }",
        )
        .replace("end = { q = [1.0], v = [0.0] }", "end = { q = [1.0, 0.0] }");
    let (e, _) = refused(&two);
    assert!(e.contains("`start v` has free and fixed components"), "{e}");
}

#[test]
fn refuses_exact_and_unknown_guesses() {
    let (e, under) = refused(&edit("steps = 20", "steps = 20\nmethod = \"exact\""));
    assert!(
        e.contains("`exact` cannot be used for optimal control"),
        "{e}"
    );
    assert_eq!(under, "\"exact\"");
    for rule in ["gauss-2", "lobatto-3", "triple-jump-4(midpoint)"] {
        let text = edit("steps = 20", &format!("steps = 20\nmethod = \"{rule}\""));
        assert_eq!(check(&text).unwrap().method.to_string(), rule);
    }
    let (e, _) = refused(&edit("steps = 20", "steps = 20\nguess = \"lines\""));
    assert!(
        e.contains("unknown guess `lines`") && e.contains("did you mean `line`"),
        "{e}"
    );
}

#[test]
fn refuses_a_missing_horizon_and_bad_steps() {
    let (e, _) = refused(&edit("t_end = 1.0", "t_end = 0.0"));
    assert!(e.contains("t_end = 0 is not after t0 = 0"), "{e}");
    let (e, under) = refused(&edit("steps = 20", "steps = 0"));
    assert!(e.contains("steps must be at least 1"), "{e}");
    assert_eq!(under, "0");
}

#[test]
fn refuses_control_names_that_clash() {
    let (e, under) = refused(&edit("controls = [\"u\"]", "controls = [\"x_dot\"]"));
    assert!(
        e.contains("control `x_dot` has the name of a coordinate"),
        "{e}"
    );
    assert_eq!(under, "\"x_dot\"");
}

#[test]
fn run_refuses_the_section_and_runs_controls_as_zero() {
    let e = crate::problem::from_toml_str(GOOD, "oc.toml", &Overrides::default()).unwrap_err();
    assert!(
        e.to_string().contains("solve it with `marsden optimize`"),
        "{e}"
    );
    let run = "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2\"\ncontrols = [\"u\"]\n\
               forces = [\"u - x\"]\n[initial]\nq = [1.0]\nv = [0.0]\n[integrator]\nh = 0.1\nsteps = 1\n";
    let spec = crate::problem::from_toml_str(run, "run.toml", &Overrides::default()).unwrap();
    let set = spec.system.force.components();
    assert_eq!(set.eval(&[2.0, 0.0, 0.0]), [-2.0]);
}

#[test]
fn unknown_keys_name_the_optimal_control_tables() {
    let e = check(&edit("t_end = 1.0", "t_end = 1.0\nhorizon = 2"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown key `horizon` in [optimal_control]"),
        "{e}"
    );
    let e = check(&edit(
        "end = { q = [1.0], v = [0.0] }",
        "end = { q = [1.0], w = [0.0] }",
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("in `start` or `end` of [optimal_control]"),
        "{e}"
    );
}

#[test]
fn refuses_outputs_it_does_not_write() {
    let (e, under) = refused(&(GOOD.to_owned() + "[output]\nformat = \"npy\"\n"));
    assert!(e.contains("writes CSV only"), "{e}");
    assert_eq!(under, "\"npy\"");
    let (e, _) = refused(&(GOOD.to_owned() + "[output]\nevery = 10\n"));
    assert!(e.contains("`every` is not used"), "{e}");
}
