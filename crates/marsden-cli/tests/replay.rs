//! `[system] control_table`: the controls `marsden optimize` wrote fed to `marsden run`. The
//! optimal trajectory solves the forced discrete Euler–Lagrange equations with its controls
//! ([OJM11] §3), which are the run's steps with the same rule and grid, so the run reproduces
//! it node for node; and every table that does not fit the run is refused at load time.

use std::path::Path;

use crate::util::{Run, column, marsden, repo_root};

/// The swing-up's system (`examples/pendulum_swing_up.toml`) as a run from rest at θ = 0 over
/// its horizon T = 6 with N = 100 steps (h = T/N = 0.06), its controls read from the table.
const REPLAY: &str = r#"[system]
coordinates = ["theta"]
parameters = { m = 1.0, l = 1.0, g = 1.0 }
lagrangian = "0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)"
controls = ["u"]
forces = ["u"]
control_table = "controls.csv"
[initial]
q = [0.0]
v = [0.0]
[integrator]
method = "midpoint"
h = 0.06
steps = 100
tolerance = 1e-14
[output]
plots = false
"#;

/// Solves the swing-up and copies its controls.csv beside a run file with `text`; returns the
/// optimisation and the run.
fn optimize_then_run(dir: &Path, text: &str) -> (Run, Run) {
    let example = repo_root().join("examples/pendulum_swing_up.toml");
    let optimized = marsden("optimize", &example, &["--quiet"]);
    assert_eq!(optimized.code, 0, "{}", optimized.stderr);
    std::fs::copy(optimized.out.join("controls.csv"), dir.join("controls.csv")).unwrap();
    let file = dir.join("replay.toml");
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    (optimized, run)
}

/// [OJM11] §3: fed back through `marsden run` (midpoint, h = T/N), the optimal controls
/// reproduce the optimal trajectory's positions and momenta at every node, to the solvers'
/// tolerances (measured: max |Δq| ≈ 5e-13).
#[test]
fn the_swing_up_controls_reproduce_the_optimal_trajectory() {
    let dir = tempfile::tempdir().unwrap();
    let (optimized, run) = optimize_then_run(dir.path(), REPLAY);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let want = marsden_io::read_csv(optimized.out.join("trajectory.csv")).unwrap();
    let got = run.trajectory();
    for name in ["t", "q_theta", "p_theta"] {
        let (a, b) = (column(&want, name), column(&got, name));
        assert_eq!(a.len(), 101);
        assert_eq!(b.len(), 101, "every node written");
        let worst = a
            .iter()
            .zip(b)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, marsden::numerics::dense::max_or_nan);
        println!("replay: max |Δ{name}| = {worst:.3e}");
        assert!(worst <= 1e-8, "{name}: {worst}");
    }
    // It ends upright at rest, as the optimal control problem asked.
    let q = column(&got, "q_theta");
    assert!((q[100] - std::f64::consts::PI).abs() < 1e-8, "{}", q[100]);
    // Without the table the controls are zero: the pendulum stays down.
    let text = REPLAY.replace("control_table = \"controls.csv\"\n", "");
    let file = dir.path().join("zero.toml");
    std::fs::write(&file, text).unwrap();
    let zero = marsden("run", &file, &[]);
    assert_eq!(zero.code, 0, "{}", zero.stderr);
    let q = column(&zero.trajectory(), "q_theta").to_vec();
    assert!(q.iter().all(|q| q.abs() < 1e-12), "at rest: {:?}", &q[..3]);
}

/// Each table that does not fit: exit 2, the reason at `control_table` (or the method).
#[test]
fn tables_that_do_not_fit_the_run_exit_two() {
    let dir = tempfile::tempdir().unwrap();
    let (_optimized, run) = optimize_then_run(dir.path(), REPLAY);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let cases = [
        (
            ("\"controls.csv\"", "\"missing.csv\""),
            "cannot read the control table",
        ),
        (
            ("steps = 100", "steps = 99"),
            "the control table has 100 rows, the run has 99 steps",
        ),
        (
            ("h = 0.06", "h = 0.05"),
            "the control table's row 1 has t = 0.06, the run's t_1 = 0.05",
        ),
        (
            (
                "controls = [\"u\"]\nforces = [\"u\"]",
                "controls = [\"w\"]\nforces = [\"w\"]",
            ),
            "the control table has no column `w`",
        ),
        (
            ("method = \"midpoint\"", "method = \"trapezoid\""),
            "the method `trapezoid` cannot read a control table",
        ),
        (
            ("controls = [\"u\"]\nforces = [\"u\"]", "forces = [\"0\"]"),
            "`control_table` gives values of controls, but none are declared",
        ),
    ];
    for ((from, to), message) in cases {
        assert!(REPLAY.contains(from), "{from}");
        let file = dir.path().join("bad.toml");
        std::fs::write(&file, REPLAY.replacen(from, to, 1)).unwrap();
        let run = marsden("run", &file, &[]);
        assert_eq!(run.code, 2, "{message}: {}", run.stderr);
        assert!(run.stderr.contains(message), "{message}: {}", run.stderr);
        assert!(run.stderr.contains('^'), "caret: {}", run.stderr);
        assert!(!run.out.exists(), "{message}: nothing written");
    }
}

/// `marsden optimize` computes the controls: a table there is refused, not ignored.
#[test]
fn optimize_refuses_a_control_table() {
    let text = std::fs::read_to_string(repo_root().join("examples/pendulum_swing_up.toml"))
        .unwrap()
        .replace(
            "forces = [\"u\"]",
            "forces = [\"u\"]\ncontrol_table = \"controls.csv\"",
        );
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("p.toml");
    std::fs::write(&file, text).unwrap();
    let run = marsden("optimize", &file, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains("`marsden optimize` computes them"),
        "{}",
        run.stderr
    );
}
