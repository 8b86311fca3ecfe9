//! End-to-end: every class of mistake in a problem file gets a message that points at it,
//! exit status 2, and nothing written; a run that fails mid-way exits with 1 and keeps
//! everything it computed.

use crate::util::{assert_rejected, assert_rejected_with, column, fixture, marsden, number};

#[test]
fn unknown_key_names_the_key_and_its_table() {
    assert_rejected(
        "unknown_key.toml",
        &[
            "error: unknown key `lagrangain` in [system]\n",
            "unknown_key.toml:4:1\n",
            "4 | lagrangain = ",
            "  | ^^^^^^^^^^\n",
            "= help: did you mean `lagrangian`?",
            "= note: valid keys in [system]: body, builtin, constraints, control_table, controls, \
             coordinates, damper, \
             discrete_lagrangian, forces, gravity, hamiltonian, joint, lagrangian, name, \
             parameters, particle, potential, rigid_body, spring, symmetry, torques",
        ],
    );
    assert_rejected(
        "unknown_key_output.toml",
        &["unknown key `plot` in [output]", "did you mean `plots`?"],
    );
}

#[test]
fn expression_syntax_error_shows_a_caret_at_the_position() {
    let run = assert_rejected(
        "syntax_error.toml",
        &["error: in [system] lagrangian: expected an operand after '+', found '*'\n"],
    );
    let lines: Vec<&str> = run.stderr.lines().collect();
    let source = lines
        .iter()
        .position(|l| l.contains("lagrangian = "))
        .unwrap();
    let caret = lines[source + 1].find('^').unwrap();
    assert_eq!(&lines[source][caret..caret + 1], "*", "{}", run.stderr);
    assert!(lines[source].contains(r#""0.5*m*l^2*theta_dot^2 + * cos(theta)""#));
}

#[test]
fn unknown_name_lists_the_known_ones() {
    assert_rejected(
        "unknown_name.toml",
        &[
            "error: in [system] lagrangian: unknown name `thetadot`",
            "^^^^^^^^",
            "= help: did you mean `theta_dot`?",
            "= note: known names: g, l, m, pi, t, theta, theta_dot",
        ],
    );
}

#[test]
fn wrong_vector_lengths_say_how_many_were_expected() {
    assert_rejected(
        "vector_length.toml",
        &[
            "initial.q has 2 values, but the system has 1 coordinate (theta)",
            "q = [1.5, 0.0]",
        ],
    );
    assert_rejected(
        "forces_length.toml",
        &["`forces` has 1 expression, but the system has 2 coordinates (x, y)"],
    );
}

#[test]
fn both_v_and_p_is_an_error() {
    assert_rejected(
        "both_v_and_p.toml",
        &[
            "give either `v` or `p` in [initial], not both",
            "9 | p = [0.0]",
        ],
    );
}

#[test]
fn non_finite_numbers_are_rejected() {
    assert_rejected(
        "non_finite_initial.toml",
        &["initial.v[0] is not a finite number (NaN)", "8 | v = [nan]"],
    );
    assert_rejected(
        "non_finite_parameter.toml",
        &["parameter `g` is not a finite number (inf)"],
    );
}

#[test]
fn time_step_must_be_positive() {
    assert_rejected(
        "h_zero.toml",
        &[
            "h must be a positive, finite time step, got 0",
            "12 | h = 0.0",
        ],
    );
    assert_rejected(
        "h_negative.toml",
        &["h must be a positive, finite time step, got -0.05"],
    );
    assert_rejected_with(
        "../r1_builtin.toml",
        &["--h", "-0.1"],
        &["--h must be a positive, finite time step, got -0.1"],
    );
}

#[test]
fn unknown_method_lists_the_valid_names() {
    assert_rejected(
        "unknown_method.toml",
        &[
            "unknown method `midpiont`",
            "did you mean `midpoint`?",
            "methods: midpoint, trapezoid, alpha-<a>, symmetrized-<a>",
            "gauss-<s>",
            "kahan-li-6(trapezoid)",
        ],
    );
}

#[test]
fn unknown_builtin_lists_the_catalog() {
    assert_rejected(
        "unknown_builtin.toml",
        &[
            "unknown builtin `pendulm`",
            "did you mean `pendulum`?",
            "builtins: harmonic_oscillator, free_fall, pendulum, double_pendulum, kepler, \
             henon_heiles, nbody",
        ],
    );
}

#[test]
fn unknown_builtin_parameter_lists_the_valid_ones() {
    assert_rejected(
        "unknown_builtin_parameter.toml",
        &[
            "unknown parameter `mm` for builtin `pendulum`",
            "parameters of pendulum: m = 1 (bob mass), l = 1 (rod length), g = 1 (gravity)",
        ],
    );
    assert_rejected(
        "nbody_without_masses.toml",
        &[
            "builtin `nbody` needs the masses of its bodies",
            "masses = [1.0, 1e-3, …]",
        ],
    );
}

#[test]
fn constraints_may_not_use_velocities() {
    assert_rejected(
        "constraint_velocity.toml",
        &["holonomic constraints φ(q) depend on the coordinates only, not on `x_dot`"],
    );
    assert_rejected(
        "constraint_violated.toml",
        &["the initial positions violate constraint [0]: x^2 + y^2 - 4 = -3e0"],
    );
    assert_rejected(
        "constrained_compensated.toml",
        &["`compensated = true` applies to unconstrained problems only"],
    );
}

#[test]
fn the_core_objections_point_at_the_file() {
    assert_rejected(
        "singular.toml",
        &[
            "the Lagrangian is singular",
            "4 | lagrangian = \"cos(theta)\"",
        ],
    );
    assert_rejected(
        "missing_integrator.toml",
        &["the problem file has no [integrator] table"],
    );
    assert_rejected(
        "toml_syntax.toml",
        &["the problem file is not valid: ", "toml_syntax.toml:12:"],
    );
}

#[test]
fn a_run_failing_mid_way_keeps_everything_on_disk() {
    let run = marsden("run", &fixture("failure_mid_run.toml"), &[]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("error: the simulation failed after 133 of 1000 steps"),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr
            .contains("Newton's method did not converge in step 133 (t = 1.33)")
    );
    let s = run.summary();
    assert_eq!(s["status"], "failed");
    assert!(
        s["error"]
            .as_str()
            .unwrap()
            .starts_with("Newton's method did not converge")
    );
    assert_eq!(s["steps"], 133);
    assert_eq!(s["steps_requested"], 1000);
    let t = run.trajectory();
    // Steps 0, 10, …, 130 by `every = 10`, then the last good state (step 133).
    assert_eq!(t.n_rows(), 15);
    let times = column(&t, "t");
    assert_eq!(times[14], number(&s, "t_final"));
    assert_eq!(
        column(&t, "q_x")[14],
        s["final_state"]["q"][0].as_f64().unwrap()
    );
    assert!((times[14] - 1.33).abs() < 1e-12);
    assert!(
        run.out.join("energy_error.png").is_file(),
        "plots of the partial run"
    );
    assert!(
        run.stdout.contains("FAILED      after 133 of 1000 steps"),
        "{}",
        run.stdout
    );
}

#[test]
fn a_run_failing_at_the_first_step_keeps_the_initial_state() {
    let run = marsden("run", &fixture("failure_first_step.toml"), &[]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["status"], "failed");
    assert!(
        s["error"]
            .as_str()
            .unwrap()
            .contains("after 1 iterations (tolerance 1.0e-15)")
    );
    assert_eq!(s["steps"], 0);
    assert_eq!(run.trajectory().n_rows(), 1);
    assert_eq!(number(&s, "t_final"), 0.0);
}

/// A copy of the Cartesian-pendulum fixture (`q = (0.6, −0.8)`, `|q| = l = 1`) with `v = (0, 0.3)`,
/// whose velocity constraint `Dφ(q)·v = 2 q_y v_y = −0.48` is violated.
fn off_constraint_file(tmp: &tempfile::TempDir, project: bool) -> std::path::PathBuf {
    let file = tmp.path().join("off.toml");
    let text = std::fs::read_to_string(fixture("cartesian_pendulum.toml")).unwrap();
    let data = if project {
        "v = [0.0, 0.3]\nproject = true"
    } else {
        "v = [0.0, 0.3]"
    };
    std::fs::write(&file, text.replace("v = [0.0, 0.0]", data)).unwrap();
    file
}

#[test]
fn velocities_off_the_constraint_are_refused_with_the_residual() {
    let tmp = tempfile::tempdir().unwrap();
    let run = marsden("run", &off_constraint_file(&tmp, false), &["--steps", "20"]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    for fragment in [
        "not tangent to the constraint manifold",
        "residual (Dφ(q0)·v0)_0 = -4.800e-1",
        "project = true",
    ] {
        assert!(
            run.stderr.contains(fragment),
            "lacks {fragment:?}:\n{}",
            run.stderr
        );
    }
    // The message speaks of the file, not of a library function it cannot call.
    assert!(!run.stderr.contains("project_onto"), "{}", run.stderr);
    assert!(!run.out.exists(), "nothing may be written for refused data");
}

/// With `project = true` the velocity is projected onto the tangent line of the circle
/// (RATTLE's projection with M = I is orthogonal): `v = (v·τ) τ` with `τ = (0.8, 0.6)`, so
/// `p₀ = 0.18 · (0.8, 0.6) = (0.144, 0.108)`.
#[test]
fn projected_initial_data_start_on_the_tangent_bundle() {
    let tmp = tempfile::tempdir().unwrap();
    let run = marsden("run", &off_constraint_file(&tmp, true), &["--steps", "20"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = run.trajectory();
    let (px, py) = (column(&table, "p_x")[0], column(&table, "p_y")[0]);
    assert!((px - 0.144).abs() < 1e-14, "p_x = {px}");
    assert!((py - 0.108).abs() < 1e-14, "p_y = {py}");
    assert!(!run.stderr.contains("warning"), "{}", run.stderr);
}
