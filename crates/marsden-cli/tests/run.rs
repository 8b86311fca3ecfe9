//! End-to-end: `marsden run` on fixture files — reference values read back from
//! `trajectory.csv`, the summary's fields, the expression path against the Rust path, the
//! other output formats.

// The reference values are quoted with all the published digits of reference case R1's closed form.
#![allow(clippy::excessive_precision)]

use crate::util::{assert_close, column, fixture, number, run_ok};
use sha2::{Digest, Sha256};

/// Reference case R1 (the `marsden` crate documentation, Reference cases): `(q_N, p_N)` for N = 10,
/// 100, 1000.
const R1: [(usize, f64, f64); 3] = [
    (10, 0.54100229460035897, -0.84102111580931570),
    (100, -0.84356915087578985, 0.53702056542622173),
    (1000, 0.81725004081453757, 0.57628323833739662),
];

fn assert_r1(fixture_name: &str) {
    let run = run_ok(fixture_name, &[]);
    let t = run.trajectory();
    assert_eq!(t.n_rows(), 1001, "every step is stored");
    let names: Vec<&str> = t.names().collect();
    assert_eq!(names, ["t", "q_x", "p_x", "energy"]);
    for (n, q, p) in R1 {
        assert_close(column(&t, "t")[n], n as f64 * 0.1, 1e-15, "t_N");
        assert_close(column(&t, "q_x")[n], q, 1e-12, &format!("q_{n}"));
        assert_close(column(&t, "p_x")[n], p, 1e-12, &format!("p_{n}"));
    }
    // The midpoint rule conserves the quadratic energy (R1: to 1e-13).
    let max_de = column(&t, "energy")
        .iter()
        .map(|e| (e - 0.5).abs())
        .fold(0.0, f64::max);
    assert!(max_de <= 1e-13, "max |E − E0| = {max_de:e}");
    let s = run.summary();
    assert!(number(&s, "energy.max_abs_error") <= 1e-13);
    let q_final = s["final_state"]["q"][0].as_f64().unwrap();
    let p_final = s["final_state"]["p"][0].as_f64().unwrap();
    assert_close(q_final, R1[2].1, 1e-12, "final_state.q");
    assert_close(p_final, R1[2].2, 1e-12, "final_state.p");
}

#[test]
fn r1_builtin_matches_the_reference_table_from_trajectory_csv() {
    assert_r1("r1_builtin.toml");
}

#[test]
fn r1_expression_matches_the_reference_table_from_trajectory_csv() {
    assert_r1("r1_expression.toml");
}

#[test]
fn summary_has_every_contract_field() {
    let run = run_ok("r1_builtin.toml", &[]);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    assert!(s["error"].is_null());
    assert_eq!(s["method"], "midpoint");
    assert_eq!(number(&s, "h"), 0.1);
    assert_eq!(s["steps"], 1000);
    assert_close(number(&s, "t_final"), 100.0, 1e-15, "t_final");
    assert!(number(&s, "wall_seconds") > 0.0);
    assert_eq!(number(&s, "energy.initial"), 0.5);
    for key in [
        "max_abs_error",
        "max_rel_error",
        "final_rel_error",
        "drift_per_unit_time",
    ] {
        assert!(
            number(&s, &format!("energy.{key}")).abs() <= 1e-13,
            "energy.{key}"
        );
    }
    assert!(s["momenta"].as_object().unwrap().is_empty());
    assert!(s["constraints"]["max_residual"].is_null());
    // Linear equations: one Newton update per step.
    assert_eq!(s["newton"]["iterations_total"], 1000);
    assert_eq!(s["newton"]["iterations_max"], 1);
    assert_eq!(s["final_state"]["q"].as_array().unwrap().len(), 1);
    assert_eq!(s["final_state"]["p"].as_array().unwrap().len(), 1);
    assert_eq!(
        s["provenance"]["marsden_version"],
        env!("CARGO_PKG_VERSION")
    );
    let bytes = std::fs::read(fixture("r1_builtin.toml")).unwrap();
    let hash: String = Sha256::digest(&bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(s["provenance"]["problem_sha256"], hash);
    assert_eq!(s["output"]["rows"], 1001);
    // The stdout report names the run and what was preserved.
    assert!(
        run.stdout
            .contains("harmonic_oscillator: builtin harmonic_oscillator"),
        "{}",
        run.stdout
    );
    assert!(
        run.stdout.contains("completed   1000 steps"),
        "{}",
        run.stdout
    );
    assert!(run.stdout.contains("max |ΔE/E0|"), "{}", run.stdout);
}

/// The same Lagrangian typed as text and written in Rust, on the same path: by default both are
/// separable (the expression's structure is read off it) and take the α-rule Newton; with
/// `fast_paths = false` both take the general Newton path. The derivatives differ only in
/// rounding (symbolic against hand-written), so over 4000 steps the runs agree to 1e-13.
#[test]
fn expression_and_rust_pendulum_agree_to_1e13() {
    for (rust, expr) in [
        ("pendulum_builtin.toml", "pendulum_expression.toml"),
        (
            "pendulum_builtin_general.toml",
            "pendulum_expression_general.toml",
        ),
    ] {
        let rust = run_ok(rust, &[]).trajectory();
        let expr = run_ok(expr, &[]).trajectory();
        assert_eq!(rust.n_rows(), 4001);
        assert_eq!(expr.n_rows(), 4001);
        for name in ["t", "q_theta", "p_theta", "energy"] {
            let (a, b) = (column(&rust, name), column(&expr, name));
            let max = a
                .iter()
                .zip(b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(max <= 1e-13, "{name}: max difference {max:e}");
        }
    }
}

#[test]
fn symmetry_momentum_map_is_conserved_and_written() {
    let run = run_ok("kepler_symmetry.toml", &[]);
    let t = run.trajectory();
    let names: Vec<&str> = t.names().collect();
    assert_eq!(names, ["t", "q_x", "q_y", "p_x", "p_y", "energy", "J_Lz"]);
    assert_eq!(
        t.n_rows(),
        3000 / 7 + 2,
        "every 7th step, plus the first and the last"
    );
    let s = run.summary();
    assert_close(number(&s, "momenta.Lz.initial"), 0.8, 1e-15, "J0");
    let drift = number(&s, "momenta.Lz.max_abs_drift");
    assert!(drift <= 1e-12, "angular momentum drift {drift:e}");
    assert!(number(&s, "energy.max_rel_error") < 1e-2);
    for png in [
        "phase_portrait.png",
        "energy_error.png",
        "momentum_drift.png",
    ] {
        assert!(run.out.join(png).is_file(), "{png}");
    }
}

#[test]
fn constrained_run_writes_the_residual_column() {
    let run = run_ok("cartesian_pendulum.toml", &[]);
    let t = run.trajectory();
    // The multipliers, then the hidden constraint's residual (added last).
    let names: Vec<&str> = t.names().collect();
    assert_eq!(
        names[names.len() - 2..],
        ["lambda_0", "constraint_velocity_residual"]
    );
    let max = column(&t, "constraint_residual")
        .iter()
        .fold(0.0, |m: f64, r| m.max(*r));
    assert!(max <= 1e-10, "max |φ| = {max:e}");
    let s = run.summary();
    assert_eq!(s["constraints"]["count"], 1);
    assert_eq!(number(&s, "constraints.max_residual"), max);
    assert!(run.out.join("constraint_residual.png").is_file());
    // The bob stays on the circle of radius 1.
    for (x, y) in column(&t, "q_x").iter().zip(column(&t, "q_y")) {
        assert_close(x.hypot(*y), 1.0, 1e-10, "radius");
    }
}

#[test]
fn damping_force_removes_energy() {
    let run = run_ok("damped.toml", &[]);
    let t = run.trajectory();
    let e = column(&t, "energy");
    assert_eq!(t.n_rows(), 21);
    // E(t) ≈ ½ e^{−c t} (light damping, c = 0.2), averaged over the oscillation.
    let ratio = e[20] / e[0];
    assert!((0.012..0.025).contains(&ratio), "E(20)/E(0) = {ratio}");
    assert!(
        e.windows(2).all(|w| w[1] <= w[0] + 1e-15),
        "energy never grows"
    );
}

#[test]
fn npy_format_writes_one_array_per_group() {
    let run = run_ok("r1_builtin.toml", &["--steps", "100"]);
    drop(run);
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("r1_npy.toml");
    let text = std::fs::read_to_string(fixture("r1_builtin.toml")).unwrap();
    std::fs::write(
        &file,
        text.replace("plots = false", "plots = false\nformat = \"npy\""),
    )
    .unwrap();
    let run = crate::util::marsden("run", &file, &["--steps", "100"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let t = marsden_io::read_npy(run.out.join("t.npy")).unwrap();
    let q = marsden_io::read_npy(run.out.join("q.npy")).unwrap();
    assert_eq!(t.shape, [101]);
    assert_eq!(q.shape, [101, 1]);
    assert_close(q.data[100], R1[1].1, 1e-12, "q_100 from q.npy");
    assert!(!run.out.join("trajectory.csv").exists());
    assert_eq!(run.summary()["output"]["format"], "npy");
}

#[test]
fn overrides_replace_steps_h_and_out() {
    let run = run_ok("r1_builtin.toml", &["--steps", "20", "--h", "0.05"]);
    let s = run.summary();
    assert_eq!(s["steps"], 20);
    assert_eq!(number(&s, "h"), 0.05);
    assert_close(number(&s, "t_final"), 1.0, 1e-15, "t_final");
    assert_eq!(run.trajectory().n_rows(), 21);
}

#[test]
fn time_enters_lagrangians_and_forces_alike() {
    let force = run_ok("driven_by_force.toml", &[]).trajectory();
    let lagrangian = run_ok("driven_by_lagrangian.toml", &[]).trajectory();
    assert_eq!(force.n_rows(), 41);
    assert_close(
        column(&force, "t")[40],
        40.25,
        1e-14,
        "t starts at t0 = 0.25",
    );
    for name in ["t", "q_x", "p_x"] {
        let (a, b) = (column(&force, name), column(&lagrangian, name));
        let max = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(max <= 1e-12, "{name}: max difference {max:e}");
    }
    // The drive does work: the amplitude changes.
    let x = column(&force, "q_x");
    assert!(x.iter().any(|v| v.abs() > 1.05), "driven amplitude");
}

#[test]
fn a_new_run_replaces_the_files_of_the_previous_one() {
    let first = run_ok("kepler_symmetry.toml", &["--steps", "50"]);
    assert!(first.out.join("momentum_drift.png").is_file());
    std::fs::write(first.out.join("notes.txt"), "mine").unwrap();
    let out = first.out.to_str().unwrap();
    let file = fixture("cartesian_pendulum.toml");
    let second = crate::util::marsden_in(
        first.tmp.path(),
        &["run", file.to_str().unwrap(), "--out", out, "-q"],
    );
    assert_eq!(second.status.code(), Some(0));
    assert!(
        !first.out.join("momentum_drift.png").exists(),
        "stale plot removed"
    );
    assert!(first.out.join("constraint_residual.png").is_file());
    assert_eq!(
        std::fs::read_to_string(first.out.join("notes.txt")).unwrap(),
        "mine"
    );
}

/// A declared symmetry that is not one is reported (with ⟨dL, ξ_TQ⟩ by the core's check), and a
/// true one is not.
#[test]
fn a_declared_non_symmetry_is_reported_and_a_true_one_is_not() {
    let run = run_ok("henon_heiles_rotation.toml", &[]);
    assert!(
        run.stderr
            .contains("\"Lz\" is not a symmetry of the Lagrangian: ⟨dL, ξ_TQ⟩ ="),
        "{}",
        run.stderr
    );
    // −λ(x³ − 3xy²) at (0.5, 0.2): 0.065 (the analytic defect of a rotation).
    assert!(run.stderr.contains("6.500e-2"), "{}", run.stderr);
    let kepler = run_ok("kepler_symmetry.toml", &["--steps", "10"]);
    assert!(
        !kepler.stderr.contains("not a symmetry"),
        "{}",
        kepler.stderr
    );
}

/// `[integrator] compensated = true` reaches the integrator: gauss-4 on Kepler keeps the angular
/// momentum to round-off over 2·10⁴ steps, where the uncompensated run drifts by about 3e-12
/// (`marsden/tests/kepler_high_order.rs`).
#[test]
fn compensated_summation_keeps_the_angular_momentum() {
    let run = run_ok("kepler_gauss4_compensated.toml", &[]);
    let drift = number(&run.summary(), "momenta.Lz.max_abs_drift");
    assert!(drift <= 2e-14, "angular momentum drift {drift:e}");
}
