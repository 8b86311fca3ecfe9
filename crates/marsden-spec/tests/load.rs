//! Problem text from memory: the checked spec, and the same diagnostics as `marsden run`.

use marsden_spec::{Overrides, RunSpec, from_toml_str};

const PENDULUM: &str = r#"
[system]
coordinates = ["theta"]
parameters = { m = 1.0, l = 1.0, g = 9.81 }
lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"

[initial]
q = [1.0]
v = [0.0]

[integrator]
method = "gauss-2"
h = 0.05
steps = 40
"#;

#[test]
fn text_becomes_a_spec_named_after_its_origin() {
    let spec = RunSpec::from_toml_str(PENDULUM, "notebook/pendulum.toml").unwrap();
    assert_eq!(spec.name, "pendulum");
    assert_eq!(spec.system.coordinates, ["theta"]);
    assert_eq!(spec.integrator.method.to_string(), "gauss-2");
    assert_eq!(spec.integrator.grid.steps, 40);
    assert_eq!(spec.source.path().to_str(), Some("notebook/pendulum.toml"));
}

#[test]
fn overrides_apply_to_text_too() {
    let overrides = Overrides {
        steps: Some(7),
        h: Some(0.01),
        out: Some("elsewhere".into()),
        checkpoint_every: None,
        every: None,
    };
    let spec = from_toml_str(PENDULUM, "p.toml", &overrides).unwrap();
    assert_eq!(
        (spec.integrator.grid.steps, spec.integrator.grid.h),
        (7, 0.01)
    );
    assert_eq!(spec.output.dir.to_str(), Some("elsewhere"));
}

#[test]
fn mistakes_point_into_the_text_with_a_caret_and_a_suggestion() {
    let text = PENDULUM.replace("cos(theta)", "cos(thetaa)");
    let d = RunSpec::from_toml_str(&text, "p.toml").unwrap_err();
    let shown = d.to_string();
    assert!(
        shown.starts_with("error: in [system] lagrangian: unknown name `thetaa`\n"),
        "{shown}"
    );
    assert!(shown.contains(" --> p.toml:5:"), "{shown}");
    assert!(shown.contains("^^^^^^"), "{shown}");
    assert!(shown.contains("= help: did you mean `theta`?"), "{shown}");
}

#[test]
fn toml_errors_are_diagnostics_as_well() {
    let d = RunSpec::from_toml_str("[integrator]\nh = 0.05.1\n", "p.toml").unwrap_err();
    assert!(
        d.message.starts_with("the problem file is not valid"),
        "{d}"
    );
}
