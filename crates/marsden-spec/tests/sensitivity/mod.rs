//! `[sensitivity]` in problem files: the Jacobian of the final `(q, p)` in `summary.json` and
//! the stored Jacobians in `sensitivity.npy`, against the closed form of R1 and against central
//! finite differences of whole runs (Kepler's `mu`, a damping coefficient); the refusals.

use std::path::Path;

mod constrained;
mod controls;

use marsden_spec::{Controls, Outcome, RunSpec, RunStatus, Store, execute};

/// Runs `text` into `out` (files and memory) in the trajectory `format`, checking that it
/// completed.
fn run_as(text: &str, out: &Path, format: &str) -> Outcome {
    let text = format!(
        "{text}\n[output]\ndir = \"{}\"\nplots = false\nformat = \"{format}\"\n",
        out.display()
    );
    let spec = RunSpec::from_toml_str(&text, "sensitivity.toml").unwrap_or_else(|d| panic!("{d}"));
    let outcome = execute(&spec, Store::FilesAndMemory, &Controls::default()).unwrap();
    assert_eq!(outcome.summary.status, RunStatus::Completed);
    outcome
}

/// [`run_as`] in CSV (the Jacobians go to `sensitivity.csv`).
fn run(text: &str, out: &Path) -> Outcome {
    run_as(text, out, "csv")
}

/// [`run_as`] in npy (the Jacobians go to `sensitivity.npy`).
fn run_npy(text: &str, out: &Path) -> Outcome {
    run_as(text, out, "npy")
}

/// `summary.json` as written, read back.
fn summary_json(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn matrix(value: &serde_json::Value) -> Vec<Vec<f64>> {
    (value.as_array().unwrap().iter())
        .map(|row| {
            (row.as_array().unwrap().iter())
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

fn names(value: &serde_json::Value) -> Vec<String> {
    (value.as_array().unwrap().iter())
        .map(|x| x.as_str().unwrap().to_owned())
        .collect()
}

fn product(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

const OSCILLATOR: &str = r#"
[system]
builtin = "harmonic_oscillator"
[initial]
q = [1.0]
p = [0.0]
[integrator]
method = "midpoint"
h = 0.1
steps = 200
[sensitivity]
initial = true
"#;

/// R1: for m = k = 1, h = 0.1 the midpoint step is the Cayley matrix
/// `[[399, 40], [−40, 399]]/401`, so the final Jacobian after N steps is its N-th power; the
/// stored samples' Jacobians go to `sensitivity.npy`, shape `[samples, 2, 2]`.
#[test]
fn r1_final_jacobian_is_the_cayley_matrix_to_the_nth_power() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run_npy(OSCILLATOR, dir.path());
    let json = summary_json(dir.path());
    let block = &json["sensitivity"];
    assert_eq!(names(&block["rows"]), ["q_x", "p_x"]);
    assert_eq!(names(&block["columns"]), ["q0_x", "p0_x"]);
    let got = matrix(&block["final"]);
    let step = [
        [399.0 / 401.0, 40.0 / 401.0],
        [-40.0 / 401.0, 399.0 / 401.0],
    ];
    let mut want = [[1.0, 0.0], [0.0, 1.0]];
    for _ in 0..200 {
        want = product(&step, &want);
    }
    for i in 0..2 {
        for j in 0..2 {
            let error = (got[i][j] - want[i][j]).abs();
            assert!(
                error <= 1e-13,
                "entry ({i}, {j}): {} vs {}",
                got[i][j],
                want[i][j]
            );
        }
    }
    let npy = marsden_io::read_npy(dir.path().join("sensitivity.npy")).unwrap();
    assert_eq!(npy.shape, [201, 2, 2]);
    let last: Vec<f64> = got.concat();
    assert_eq!(&npy.data[npy.data.len() - 4..], last.as_slice());
    assert!(
        outcome
            .summary
            .output
            .files
            .iter()
            .any(|f| f == "sensitivity.npy")
    );
}

/// With `format = "csv"` the stored Jacobians go to `sensitivity.csv`, one row per stored step
/// (`t`, then the entries row by row), the first row the identity.
#[test]
fn csv_output_flattens_the_jacobians_with_a_header() {
    let dir = tempfile::tempdir().unwrap();
    let text = OSCILLATOR.replace("[sensitivity]", "[sensitivity]\nparameters = [\"k\"]");
    let spec_text = format!(
        "{text}\n[output]\ndir = \"{}\"\nplots = false\nformat = \"csv\"\nevery = 50\n",
        dir.path().display()
    );
    let spec = RunSpec::from_toml_str(&spec_text, "csv.toml").unwrap();
    let outcome = execute(&spec, Store::Files, &Controls::default()).unwrap();
    assert_eq!(outcome.summary.status, RunStatus::Completed);
    let table = marsden_io::read_csv(dir.path().join("sensitivity.csv")).unwrap();
    let header: Vec<&str> = table.names().collect();
    assert_eq!(
        header,
        [
            "t", "q_x/q0_x", "q_x/p0_x", "q_x/k", "p_x/q0_x", "p_x/p0_x", "p_x/k"
        ]
    );
    assert_eq!(table.n_rows(), 5);
    assert_eq!(table.row(0).unwrap(), [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
}

/// A Kepler problem file (e = 0.6, gauss-3, h = 0.01, 1000 steps) with `mu` given.
fn kepler(mu: f64) -> String {
    format!(
        r#"
[system]
builtin = "kepler"
parameters = {{ mu = {mu:?} }}
[initial]
q = [0.4, 0.0]
p = [0.0, 2.0]
[integrator]
method = "gauss-3"
h = 0.01
steps = 1000
[sensitivity]
initial = true
parameters = ["mu"]
"#
    )
}

/// The sensitivity check: `∂(q, p)_final/∂mu` of the file equals the central difference of two runs
/// at `mu ± δ` (δ = 1e-5), relative to the column's size, to 1e-6.
#[test]
fn kepler_d_final_d_mu_matches_a_central_difference_of_two_runs() {
    let dir = tempfile::tempdir().unwrap();
    let outcome = run(&kepler(1.0), &dir.path().join("base"));
    let block = outcome.summary.sensitivity.as_ref().unwrap();
    assert_eq!(block.columns, ["q0_x", "q0_y", "p0_x", "p0_y", "mu"]);
    let column: Vec<f64> = block.final_jacobian.iter().map(|row| row[4]).collect();
    let delta = 1e-5;
    let end = |mu: f64, name: &str| {
        let s = run(&kepler(mu), &dir.path().join(name)).summary.final_state;
        [s.q, s.p].concat()
    };
    let (plus, minus) = (end(1.0 + delta, "plus"), end(1.0 - delta, "minus"));
    let fd: Vec<f64> = (plus.iter().zip(&minus))
        .map(|(a, b)| (a - b) / (2.0 * delta))
        .collect();
    let scale = column.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    for (row, (got, want)) in column.iter().zip(&fd).enumerate() {
        let error = (got - want).abs() / scale;
        assert!(
            error <= 1e-6,
            "row {row}: {got} vs {want} (relative {error:e})"
        );
    }
}

/// A forced system: `∂/∂c` of the damping `f = −c ẋ` (a parameter of the forces only) against
/// central differences, R12's damped oscillator (m = k = 1, c = 0.1, midpoint).
#[test]
fn r12_damping_sensitivity_matches_a_central_difference() {
    let file = |c: f64| {
        format!(
            r#"
[system]
coordinates = ["x"]
parameters = {{ c = {c:?} }}
lagrangian = "0.5*x_dot^2 - 0.5*x^2"
forces = ["-c*x_dot"]
[initial]
q = [1.0]
v = [0.0]
[integrator]
method = "midpoint"
h = 0.1
steps = 300
[sensitivity]
parameters = ["c"]
"#
        )
    };
    let dir = tempfile::tempdir().unwrap();
    let outcome = run(&file(0.1), &dir.path().join("base"));
    let block = outcome.summary.sensitivity.unwrap();
    assert_eq!(block.columns, ["c"]);
    let delta = 1e-5;
    let end = |c: f64, name: &str| {
        let s = run(&file(c), &dir.path().join(name)).summary.final_state;
        [s.q[0], s.p[0]]
    };
    let (plus, minus) = (end(0.1 + delta, "plus"), end(0.1 - delta, "minus"));
    let scale = block
        .final_jacobian
        .iter()
        .fold(0.0_f64, |m, r| m.max(r[0].abs()));
    for row in 0..2 {
        let want = (plus[row] - minus[row]) / (2.0 * delta);
        let got = block.final_jacobian[row][0];
        assert!(
            (got - want).abs() <= 1e-6 * scale,
            "row {row}: {got} vs {want}"
        );
    }
}

fn refusal(text: &str) -> String {
    match RunSpec::from_toml_str(text, "refused.toml") {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(d) => d.to_string(),
    }
}

#[test]
fn an_unknown_parameter_is_refused_with_a_suggestion() {
    let text = kepler(1.0).replace("parameters = [\"mu\"]", "parameters = [\"muu\"]");
    let message = refusal(&text);
    assert!(
        message.contains("`muu`, which is not a parameter"),
        "{message}"
    );
    assert!(message.contains("mu"), "{message}");
    assert!(message.contains("scalar parameters: mu"), "{message}");
}

/// A pendulum in Cartesian coordinates, `x² + y² = 1`, `L = ½|v|² − g y` (so `p = v`), from
/// `q = (1, 0)`, `v = (0, 0.5)`.
const CARTESIAN_PENDULUM: &str = r#"
[system]
coordinates = ["x", "y"]
parameters = { g = 1.0 }
lagrangian = "0.5*(x_dot^2 + y_dot^2) - g*y"
constraints = ["x^2 + y^2 - 1"]
[initial]
q = [1.0, 0.0]
v = [0.0, 0.5]
[integrator]
method = "midpoint"
h = 0.01
steps = 500
[sensitivity]
initial = true
"#;

/// A constrained run's final Jacobian carries tangent vectors of `T*N` at the start to tangent
/// vectors at the end (the property the issue asks of the constrained tangent map): for
/// `δ = (δq, δp)` with `q₀·δq = 0` and `δq·p₀ + q₀·δp = 0`, the image satisfies
/// `q_K·δq_K = 0` (the constraint's derivative) and `δq_K·p_K + q_K·δp_K = 0` (the hidden
/// constraint `q·v = 0`'s), each relative to its terms' sizes to 1e-10; and the summary says
/// how to read the matrix.
#[test]
fn constrained_jacobian_maps_tangent_vectors_of_the_cotangent_bundle_to_tangent_vectors() {
    let out = tempfile::tempdir().unwrap();
    let outcome = run(CARTESIAN_PENDULUM, out.path());
    let s = outcome.summary.sensitivity.as_ref().unwrap();
    assert_eq!(s.error, None);
    assert!(
        s.note
            .as_deref()
            .unwrap_or("")
            .contains("tangent vectors of T*N")
    );
    let j = &s.final_jacobian;
    let f = &outcome.summary.final_state;
    let (q, p) = (&f.q, &f.p);
    // At the start q₀ = (1, 0), p₀ = (0, 0.5): δq = (0, 1) needs δp_x = −0.5.
    for delta in [[0.0, 1.0, -0.5, 0.0], [0.0, 0.0, 0.0, 1.0]] {
        let image: Vec<f64> = (0..4)
            .map(|r| (0..4).map(|c| j[r][c] * delta[c]).sum())
            .collect();
        let (dq, dp) = image.split_at(2);
        let position = q[0] * dq[0] + q[1] * dq[1];
        let position_scale = (q[0] * dq[0]).abs() + (q[1] * dq[1]).abs();
        let hidden = dq[0] * p[0] + dq[1] * p[1] + q[0] * dp[0] + q[1] * dp[1];
        let hidden_scale = (dq[0] * p[0]).abs()
            + (dq[1] * p[1]).abs()
            + (q[0] * dp[0]).abs()
            + (q[1] * dp[1]).abs();
        assert!(position_scale > 1e-3 && hidden_scale > 1e-3, "{image:?}");
        assert!(
            position.abs() <= 1e-10 * position_scale,
            "q·δq = {position:e} (scale {position_scale:e})"
        );
        assert!(
            hidden.abs() <= 1e-10 * hidden_scale,
            "δ(q·p) = {hidden:e} (scale {hidden_scale:e})"
        );
    }
}

#[test]
fn empty_tables_are_refused() {
    let empty = OSCILLATOR.replace("initial = true", "");
    assert!(refusal(&empty).contains("asks for no derivative"));
}
