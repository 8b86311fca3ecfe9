//! Jointed rigid bodies from problem files (`[[system.body]]`, `[[system.joint]]`):
//!
//! * R21 from files: the compound double pendulum of `examples/compound_double_pendulum.toml`
//!   against its reduced-coordinate Lagrangian written as an expression and integrated by
//!   marsden at a tiny step (`gauss-4`, order 8): orders 2 (`trapezoid`) and 4
//!   (`triple-jump-4(trapezoid)`) fitted from three step sizes, the joints closed to round-off;
//! * R22, the 3D pendulum of `examples/pendulum_3d.toml`: the vertical angular momentum to
//!   round-off; the free satellite with a reaction wheel: the total angular momentum to
//!   round-off; the 10-link chain runs with every column named as the interface says;
//! * every bad input with its message, and `project = true` closing an open joint.

use std::path::PathBuf;

use serde_json::Value;

use crate::util::{Run, marsden, number, repo_root};

fn example(name: &str) -> PathBuf {
    repo_root().join("examples").join(name)
}

fn run_text(text: &str, extra: &[&str]) -> (Run, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bodies.toml");
    std::fs::write(&path, text).unwrap();
    (marsden("run", &path, extra), dir)
}

fn double_pendulum_text() -> String {
    std::fs::read_to_string(example("compound_double_pendulum.toml")).unwrap()
}

/// The hinge angle of body `name` from its final attitude `R = exp(θ ê_y)`: `atan2(R13, R11)`.
fn final_angle(s: &Value, name: &str) -> f64 {
    let r = &s["multibody"]["final_attitudes"][name];
    let entry = |i: usize, j: usize| r[i][j].as_f64().unwrap();
    entry(0, 2).atan2(entry(0, 0))
}

/// Component `axis` of `multibody.angular_momentum.<what>`.
fn momentum(s: &Value, what: &str, axis: usize) -> f64 {
    s["multibody"]["angular_momentum"][what][axis]
        .as_f64()
        .unwrap()
}

const T_END: f64 = 1.0;

/// The reduced model: hinge angles `θ₁, θ₂` of two uniform rods (1 kg, 1 m, `I = 1/12` about
/// their centres) under `g = 9.81`, as an expression, at `T_END` by gauss-4 with 2000 steps.
fn reduced_angles() -> [f64; 2] {
    let text = format!(
        "[system]\ncoordinates = [\"theta1\", \"theta2\"]\n\
         lagrangian = \"0.5*(1.25*theta1_dot^2 + 0.25*theta2_dot^2 + theta1_dot*theta2_dot*cos(theta1 - theta2)) \
         + 0.5*(1/12)*(theta1_dot^2 + theta2_dot^2) + 9.81*(1.5*cos(theta1) + 0.5*cos(theta2))\"\n\
         [initial]\nq = [0.9, -0.4]\nv = [0.0, 0.0]\n\
         [integrator]\nmethod = \"gauss-4\"\nh = {h:?}\nsteps = 2000\ntolerance = 1e-15\n\
         [output]\nevery = 2000\nplots = false\n",
        h = T_END / 2000.0
    );
    let (run, _dir) = run_text(&text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let q = &run.summary()["final_state"]["q"];
    [q[0].as_f64().unwrap(), q[1].as_f64().unwrap()]
}

fn slope(hs: &[f64], errors: &[f64]) -> f64 {
    let x: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

/// The errors of the file's final angles against the reduced model, for each `h`.
fn errors(method: &str, hs: &[f64]) -> Vec<f64> {
    let reference = reduced_angles();
    let text = double_pendulum_text()
        .replace(
            "method = \"trapezoid\"",
            &format!("method = \"{method}\"\ntolerance = 1e-14"),
        )
        .replace("every = 10", "every = 1\nplots = false");
    hs.iter()
        .map(|&h| {
            let steps = ((T_END / h).round() as usize).to_string();
            let (run, _dir) = run_text(&text, &["--h", &h.to_string(), "--steps", &steps]);
            assert_eq!(run.code, 0, "{method}, h = {h}: {}", run.stderr);
            let s = run.summary();
            // Every step is stored (`every = 1`): the joints at every step.
            let residual = number(&s, "multibody.max_joint_residual");
            assert!(
                residual <= 1e-13,
                "{method}, h = {h}: joints open by {residual:e}"
            );
            let a = (final_angle(&s, "a") - reference[0]).abs();
            let b = (final_angle(&s, "b") - reference[1]).abs();
            a.max(b)
        })
        .collect()
}

#[test]
fn r21_compound_double_pendulum_file_is_second_order_against_reduced_coordinates() {
    let hs = [0.02, 0.01, 0.005];
    let e = errors("trapezoid", &hs);
    let order = slope(&hs, &e);
    assert!((order - 2.0).abs() < 0.1, "order {order}, errors {e:?}");
}

#[test]
fn r21_compound_double_pendulum_file_is_fourth_order_by_the_triple_jump() {
    let hs = [0.02, 0.01, 0.005];
    let e = errors("triple-jump-4(trapezoid)", &hs);
    let order = slope(&hs, &e);
    assert!((order - 4.0).abs() < 0.2, "order {order}, errors {e:?}");
}

#[test]
fn r22_three_dimensional_pendulum_keeps_its_vertical_angular_momentum() {
    let run = marsden("run", &example("pendulum_3d.toml"), &["--steps", "2000"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["system"], "multibody");
    let lz = momentum(&s, "initial", 2);
    let drift = momentum(&s, "max_abs_drift", 2);
    assert!(lz.abs() > 0.1, "L_z = {lz}");
    assert!(drift <= 1e-12 * lz.abs(), "L_z drift {drift:e} of {lz}");
    assert!(number(&s, "multibody.max_joint_residual") <= 1e-13);
    assert!(number(&s, "multibody.orthogonality_defect") <= 1e-13);
    // The energy error is bounded (a symplectic map of fixed step), not zero.
    assert!(number(&s, "energy.max_rel_error") < 1e-3);
    for png in [
        "energy_error.png",
        "constraint_residual.png",
        "multipliers.png",
    ] {
        assert!(run.out.join(png).exists(), "{png} not drawn");
    }
}

#[test]
fn free_satellite_with_a_reaction_wheel_keeps_its_total_angular_momentum() {
    let run = marsden(
        "run",
        &example("satellite_reaction_wheel.toml"),
        &["--steps", "2000"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    let size = (0..3)
        .map(|a| momentum(&s, "initial", a).abs())
        .fold(0.0, f64::max);
    for a in 0..3 {
        let drift = momentum(&s, "max_abs_drift", a);
        assert!(drift <= 1e-12 * size, "axis {a}: drift {drift:e} of {size}");
    }
    assert!(number(&s, "multibody.max_joint_residual") <= 1e-13);
}

#[test]
fn a_chain_names_its_columns_by_body_and_joint() {
    let run = marsden("run", &example("chain_10.toml"), &["--steps", "200"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = run.trajectory();
    for c in [
        "t",
        "link0_x",
        "link9_z",
        "link0_R11",
        "link9_R33",
        "link0_p_x",
        "link3_Pi2",
        "energy",
        "constraint_residual",
        "lambda_hinge0_0",
        "lambda_hinge9_4",
    ] {
        assert!(table.values(c).is_some(), "no column {c}");
    }
    let s = run.summary();
    assert_eq!(s["multibody"]["bodies"], 10);
    assert_eq!(s["constraints"]["count"], 50);
    assert!(number(&s, "multibody.max_joint_residual") <= 1e-12);
}

/// Runs `text` and checks exit 2 with every fragment in the message.
fn refused(text: &str, fragments: &[&str]) {
    let (run, _dir) = run_text(text, &[]);
    assert_eq!(run.code, 2, "exit code; stderr:\n{}", run.stderr);
    for f in fragments {
        assert!(
            run.stderr.contains(f),
            "message lacks {f:?}:\n{}",
            run.stderr
        );
    }
}

#[test]
fn a_joint_naming_an_unknown_body_is_refused_with_the_names() {
    let text = double_pendulum_text().replace("bodies = [\"a\", \"b\"]", "bodies = [\"a\", \"c\"]");
    refused(&text, &["names an unknown body `c`", "\"a\", \"b\"", "^"]);
}

#[test]
fn a_start_off_a_joint_is_refused_with_the_joint_and_residual_and_project_closes_it() {
    let off = double_pendulum_text().replace(
        "x = [-0.5886177384731581, 0.0, -1.082140465272107]",
        "x = [-0.5786177384731581, 0.0, -1.082140465272107]",
    );
    refused(
        &off,
        &["start off joint `elbow`", "1.000e-2", "project = true"],
    );
    let projected = off.replace("[initial.a]", "[initial]\nproject = true\n\n[initial.a]");
    let (run, _dir) = run_text(&projected, &["--steps", "100"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(number(&run.summary(), "multibody.max_joint_residual") <= 1e-13);
}

#[test]
fn velocities_that_break_a_joint_are_refused() {
    let text =
        double_pendulum_text().replace("[initial.b]\n", "[initial.b]\nv = [0.0, 0.3, 0.0]\n");
    refused(&text, &["initial velocities break joint `elbow`"]);
}

#[test]
fn redundant_joints_are_refused() {
    let text = double_pendulum_text().replace(
        "[initial.a]",
        "[[system.joint]]\nkind = \"spherical\"\nbodies = [\"ground\", \"a\"]\n\
         at = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]\n\n[initial.a]",
    );
    refused(&text, &["redundant or singular"]);
}

#[test]
fn bad_bodies_joints_and_initial_tables_are_refused_with_their_messages() {
    let base = double_pendulum_text();
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            base.replace(
                "kind = \"revolute\"\nbodies = [\"a\", \"b\"]",
                "kind = \"hinge\"\nbodies = [\"a\", \"b\"]",
            ),
            vec!["unknown joint kind `hinge`", "\"revolute\""],
        ),
        (
            base.replace("name = \"b\"", "name = \"ground\""),
            vec!["`ground` names the space frame"],
        ),
        (
            base.replace("[initial.b]", "[initial.c]"),
            vec!["[initial.c] names no body"],
        ),
        (
            base.replace("[initial.a]\n", "[initial]\nq = [1.0]\n\n[initial.a]\n"),
            vec!["`q` in [initial] does not say which body"],
        ),
        (
            base.replace(
                "gravity = [0.0, 0.0, -9.81]",
                "gravity = [0.0, 0.0, -9.81]\ntorques = [\"0\", \"0\", \"a_z\"]",
            ),
            vec!["`torques` cannot be used with `[[system.body]]`"],
        ),
        (
            base.replace("method = \"trapezoid\"", "method = \"gauss-2\""),
            vec!["has no rigid-body version"],
        ),
        (
            base.replace(
                "inertia = [0.08333333333333333, 0.08333333333333333, 0.001]\n\n[[system.body]]",
                "\n[[system.body]]",
            ),
            vec!["body `a` has no `inertia`"],
        ),
        (
            base.replace(
                "axis = [[0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]\n\n[initial.a]",
                "axis = [[0.0, 1.0, 0.0]]\n\n[initial.a]",
            ),
            vec!["`axis` must be two vectors"],
        ),
        (
            base.replace(
                "[initial.a]\nrotation_vector",
                "[initial.a]\nOmegaa = [0.0, 0.0, 0.0]\nrotation_vector",
            ),
            vec!["Omegaa", "Omega"],
        ),
        (
            format!("{base}\n[sweep]\nparameter = \"h\"\nvalues = [0.01, 0.02]\n"),
            vec!["not available for a multibody system"],
        ),
    ];
    for (text, fragments) in cases {
        refused(&text, &fragments);
    }
}

#[test]
fn a_body_table_in_a_file_without_bodies_is_refused() {
    let text = std::fs::read_to_string(example("pendulum.toml")).unwrap()
        + "\n[initial.a]\nx = [0.0, 0.0, 0.0]\n";
    refused(&text, &["unknown table [initial.a]", "[[system.body]]"]);
}
