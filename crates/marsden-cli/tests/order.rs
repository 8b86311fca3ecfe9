//! End-to-end: `marsden order` — fitted orders parsed from the table on stdout, the errors of
//! reference case R6, and the refusals of bad input (exit status 2).

use crate::util::{fixture, marsden_in};

/// What one `marsden order` invocation did.
struct Order {
    code: i32,
    stdout: String,
    stderr: String,
}

fn order(file: &str, extra: &[&str]) -> Order {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture(file);
    let mut args = vec!["order", path.to_str().unwrap()];
    args.extend_from_slice(extra);
    let output = marsden_in(tmp.path(), &args);
    Order {
        code: output.status.code().unwrap_or(-1),
        stdout: String::from_utf8(output.stdout).unwrap(),
        stderr: String::from_utf8(output.stderr).unwrap(),
    }
}

/// The row of `method` in the table, split at whitespace.
fn row<'a>(stdout: &'a str, method: &str) -> Vec<&'a str> {
    stdout
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .find(|cells| cells.first() == Some(&method))
        .unwrap_or_else(|| panic!("no row for {method} in:\n{stdout}"))
}

/// The fitted order: the last field of the method's row.
fn fitted(stdout: &str, method: &str) -> f64 {
    let cells = row(stdout, method);
    cells.last().unwrap().parse().unwrap()
}

/// Reference case R6 (the `marsden` crate documentation; R5 for the midpoint rule's order 2):
/// pendulum `L = ½q̇² + cos q`, `q₀ = 1.5`, `p₀ = 0`, `T = 5`, `N = 10, 20, 40, 80`. The
/// midpoint rule (P1, Gauss 1 point) has order 2 and Gauss 2 (P2, 2 Gauss points) order 4;
/// the errors are those of the table of R6 (quoted to 4 digits).
#[test]
fn r6_pendulum_orders_of_midpoint_and_gauss_2() {
    let run = order(
        "pendulum_builtin.toml",
        &[
            "--methods",
            "midpoint,gauss-2",
            "--h",
            "0.5,0.25,0.125,0.0625",
            "--t-end",
            "5",
        ],
    );
    assert_eq!(run.code, 0, "stderr:\n{}", run.stderr);
    let midpoint = fitted(&run.stdout, "midpoint");
    let gauss = fitted(&run.stdout, "gauss-2");
    assert!(
        (midpoint - 2.0).abs() < 0.2,
        "midpoint: {midpoint}\n{}",
        run.stdout
    );
    assert!(
        (gauss - 4.0).abs() < 0.2,
        "gauss-2: {gauss}\n{}",
        run.stdout
    );
    let r6 = [
        (
            "midpoint",
            "2",
            ["4.914e-2", "1.225e-2", "3.059e-3", "7.647e-4"],
        ),
        (
            "gauss-2",
            "4",
            ["2.192e-4", "1.374e-5", "8.594e-7", "5.373e-8"],
        ),
    ];
    for (method, expected, errors) in r6 {
        let cells = row(&run.stdout, method);
        assert_eq!(cells[1], expected, "expected order of {method}");
        assert_eq!(cells[2..6], errors, "errors of {method}");
    }
}

#[test]
fn defaults_are_the_files_method_and_h_halved_three_times() {
    let run = order("r1_builtin.toml", &[]);
    assert_eq!(run.code, 0, "stderr:\n{}", run.stderr);
    assert!(run.stdout.contains("T = 100"), "{}", run.stdout);
    for h in ["e(h=0.1)", "e(h=0.05)", "e(h=0.025)", "e(h=0.0125)"] {
        assert!(run.stdout.contains(h), "no column {h}:\n{}", run.stdout);
    }
    assert!((fitted(&run.stdout, "midpoint") - 2.0).abs() < 0.05);
}

#[test]
fn unknown_method_lists_the_names() {
    let run = order("pendulum_builtin.toml", &["--methods", "midpoint,gauss2"]);
    assert_eq!(run.code, 2, "stdout:\n{}", run.stdout);
    assert!(
        run.stderr.contains("unknown method `gauss2`"),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr.contains("= note: methods: midpoint, trapezoid"),
        "{}",
        run.stderr
    );
    assert!(run.stdout.is_empty(), "nothing runs: {}", run.stdout);
}

#[test]
fn a_step_size_that_does_not_divide_the_span_is_named() {
    let run = order("pendulum_builtin.toml", &["--h", "0.5,0.3", "--t-end", "5"]);
    assert_eq!(run.code, 2);
    assert!(
        run.stderr
            .contains("h = 0.3 does not divide the time span T − t0 = 5 into whole steps"),
        "{}",
        run.stderr
    );
}

#[test]
fn empty_lists_and_non_positive_steps_are_refused() {
    for (args, message) in [
        (&["--methods="][..], "--methods is empty"),
        (&["--h="][..], "--h is empty"),
        (
            &["--h", "0.1,-0.05"][..],
            "must be positive and finite, got -0.05",
        ),
        (&["--h", "0"][..], "must be positive and finite, got 0"),
    ] {
        let run = order("pendulum_builtin.toml", args);
        assert_eq!(run.code, 2, "{args:?}");
        assert!(run.stderr.contains(message), "{args:?}: {}", run.stderr);
    }
}

// Constrained problems are studied against a constrained reference: see
// `constraints::r7_order_study_of_a_constrained_problem`.

#[test]
fn csv_has_one_line_per_run() {
    let tmp = tempfile::tempdir().unwrap();
    let csv = tmp.path().join("order.csv");
    let run = order(
        "pendulum_builtin.toml",
        &[
            "--methods",
            "midpoint,gauss-2",
            "--h",
            "0.5,0.25",
            "--t-end",
            "5",
            "--csv",
            csv.to_str().unwrap(),
        ],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "method,expected_order,h,steps,error,fitted_order");
    assert_eq!(lines.len(), 5);
    assert!(
        lines[1].starts_with("\"midpoint\",2,0.5,10,0.0491"),
        "{text}"
    );
}

/// The solution of `failure_mid_run.toml` runs into the singular mass at t ≈ 1.33: the
/// reference flow stops there with an error (status 1) instead of creeping towards it.
#[test]
fn a_reference_past_a_singularity_fails_quickly() {
    let run = order("failure_mid_run.toml", &[]);
    assert_eq!(run.code, 1, "{}", run.stdout);
    assert!(
        run.stderr
            .contains("cannot compute the reference solution at T = 10"),
        "{}",
        run.stderr
    );
}

/// One Newton iteration per step cannot reach round-off: every run fails, each shown as
/// `failed` in its cell, and the table is still printed (status 1).
#[test]
fn failed_runs_are_cells_not_aborts() {
    let run = order(
        "failure_first_step.toml",
        &["--methods", "midpoint,gauss-2"],
    );
    assert_eq!(run.code, 1, "{}", run.stderr);
    let cells = row(&run.stdout, "gauss-2");
    assert_eq!(cells[2], "failed", "{}", run.stdout);
    assert_eq!(cells.last(), Some(&"-"), "no fit: {}", run.stdout);
    assert!(run.stderr.contains("of the runs failed"), "{}", run.stderr);
}
