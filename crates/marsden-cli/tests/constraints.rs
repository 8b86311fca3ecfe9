//! End-to-end: constrained runs say what they did — the order of constrained methods in
//! `summary.json`, the multipliers `lambda_<i>`, the velocity-constraint residual, projected
//! starts off the manifold, the refusal of Gauss rules, the symmetry check of the constraints
//! and `marsden order` on a constrained problem (R7, the Cartesian pendulum).

use crate::util::{column, fixture, marsden, marsden_in, number, run_ok};

const OFF: &str = "cartesian_pendulum_off_manifold.toml";

/// `project = true` with positions off the circle (|q| = 1.1) and a non-tangent velocity: the
/// run starts on `T N`, `φ = 0` and `Dφ·v = 0` to 1e-12 at the first stored state.
#[test]
fn off_manifold_positions_are_projected_with_project_true() {
    let run = run_ok(OFF, &[]);
    let t = run.trajectory();
    let (x, y) = (column(&t, "q_x")[0], column(&t, "q_y")[0]);
    let (px, py) = (column(&t, "p_x")[0], column(&t, "p_y")[0]);
    // m = 1: v = p; φ = x² + y² − 1, Dφ·v = 2(x v_x + y v_y).
    assert!(
        (x * x + y * y - 1.0).abs() <= 1e-12,
        "φ = {:e}",
        x * x + y * y - 1.0
    );
    assert!(
        (x * px + y * py).abs() <= 1e-12,
        "Dφ·v = {:e}",
        x * px + y * py
    );
    // The nearest point of the circle (M = I): q / |q| = (0.6, −0.8).
    assert!(
        (x - 0.6).abs() <= 1e-14 && (y + 0.8).abs() <= 1e-14,
        "({x}, {y})"
    );
    let s = run.summary();
    assert!(number(&s, "constraints.max_residual") <= 1e-12);
    assert!(number(&s, "constraints.max_velocity_residual") <= 1e-12);
}

/// The order in `summary.json` and on the console is the constrained method's: lobatto-4 is 6
/// (measured 6 on R7, `marsden/tests/constraints/stage_constraints.rs`).
#[test]
fn summary_and_console_give_the_constrained_order() {
    let run = run_ok(OFF, &[]);
    let s = run.summary();
    assert_eq!(s["order"], 6, "{s}");
    assert!(run.stdout.contains("order 6"), "{}", run.stdout);
}

/// `lambda_0` is the multiplier implied by each stored state: for the pendulum (m = l = g = 1,
/// φ = x² + y² − 1, so Dφ = 2q) `2λ = |v|² − y`; and the multiplier plot is drawn.
#[test]
fn multipliers_are_written_and_plotted() {
    let run = run_ok(OFF, &[]);
    let t = run.trajectory();
    // The multipliers, then the hidden constraint's residual (added last).
    let names: Vec<&str> = t.names().collect();
    assert_eq!(
        names[names.len() - 2..],
        ["lambda_0", "constraint_velocity_residual"]
    );
    let (y, px, py) = (column(&t, "q_y"), column(&t, "p_x"), column(&t, "p_y"));
    for (i, lambda) in column(&t, "lambda_0").iter().enumerate() {
        let expected = 0.5 * (px[i] * px[i] + py[i] * py[i] - y[i]);
        assert!(
            (lambda - expected).abs() <= 1e-10,
            "row {i}: {lambda} vs {expected}"
        );
    }
    assert!(run.out.join("multipliers.png").is_file());
}

/// A translation is not a symmetry of the circle: the warning gives `Dφ·ξ_Q = 2x`.
#[test]
fn a_generator_that_breaks_the_constraint_is_reported() {
    let run = run_ok(OFF, &["--steps", "5"]);
    assert!(
        run.stderr
            .contains("\"Px\" does not keep the constraints invariant: Dφ(q)·ξ_Q(q) = 1.200e0"),
        "{}",
        run.stderr
    );
}

/// gauss-2 with constraints is refused before anything runs, naming lobatto-3.
#[test]
fn gauss_rules_are_refused_with_constraints() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("gauss.toml");
    let text = std::fs::read_to_string(fixture(OFF)).unwrap();
    std::fs::write(&file, text.replace("lobatto-4", "gauss-2")).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(run.stderr.contains("lobatto-3"), "{}", run.stderr);
    assert!(!run.out.exists());
}

/// `marsden check` says what a constrained run does.
#[test]
fn check_describes_the_constrained_scheme() {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture(OFF);
    let output = marsden_in(tmp.path(), &["check", path.to_str().unwrap()]);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(stdout.contains("RATTLE projection"), "{stdout}");
    assert!(!stdout.contains("not projected yet"), "{stdout}");
}

/// R7 through `marsden order`: the constrained reference (lobatto-5) and the measured orders of
/// midpoint (2), lobatto-3 (4) and kahan-li-6(trapezoid) (6).
#[test]
fn r7_order_study_of_a_constrained_problem() {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture("cartesian_pendulum.toml");
    let args = [
        "order",
        path.to_str().unwrap(),
        "--methods",
        "midpoint,lobatto-3,kahan-li-6(trapezoid)",
        "--h",
        "0.25,0.125,0.0625",
        "--t-end",
        "5",
    ];
    let output = marsden_in(tmp.path(), &args);
    let stdout = String::from_utf8(output.stdout).unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(
        stdout.contains("constrained reference (lobatto-5"),
        "{stdout}"
    );
    for (method, expected) in [
        ("midpoint", 2.0),
        ("lobatto-3", 4.0),
        ("kahan-li-6(trapezoid)", 6.0),
    ] {
        let cells: Vec<&str> = stdout
            .lines()
            .map(|l| l.split_whitespace().collect::<Vec<_>>())
            .find(|c| c.first() == Some(&method))
            .unwrap_or_else(|| panic!("no row for {method}:\n{stdout}"));
        let fitted: f64 = cells.last().unwrap().parse().unwrap();
        assert!(
            (fitted - expected).abs() <= 0.3,
            "{method}: {fitted}\n{stdout}"
        );
    }
}
