//! End-to-end: `[system] discrete_lagrangian = "…"`, a researcher's own `L_d` run through the
//! discrete Legendre transforms: R1's midpoint map from the hand-written midpoint `L_d`, no
//! energy reported, momentum maps monitored, sweeps, and every refusal (exit status 2, key
//! named).

use crate::util::{
    Run, assert_close, assert_rejected, column, fixture, marsden_in, number, run_ok,
};

/// R1 (m = k = 1, (q, p) = (1, 0), h = 0.1): `q_N`, `p_N` of the midpoint map at N = 10, 100,
/// 1000 (reference case R1's closed form at 40 digits; the digits as published).
#[allow(clippy::excessive_precision)]
const R1: [(usize, f64, f64); 3] = [
    (10, 0.54100229460035897, -0.84102111580931570),
    (100, -0.84356915087578985, 0.53702056542622173),
    (1000, 0.81725004081453757, 0.57628323833739662),
];

/// Asserts that every column of `user` and `rule` holds the same bits (the user's file has
/// no energy column: the columns of `user` are compared), and that the summaries agree bit for
/// bit on the final state, the momentum maps and the steps; returns the number of rows.
fn assert_bit_for_bit(user: &Run, rule: &Run) -> usize {
    let (a, b) = (user.trajectory(), rule.trajectory());
    let (s, r) = (user.summary(), rule.summary());
    let names: Vec<String> = s["output"]["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap().to_owned())
        .collect();
    assert!(names.len() >= 3, "{names:?}");
    let mut rows = 0;
    for name in &names {
        let (x, y) = (column(&a, name), column(&b, name));
        assert_eq!(x.len(), y.len(), "{name}: rows");
        for (k, (u, w)) in x.iter().zip(y).enumerate() {
            assert_eq!(u.to_bits(), w.to_bits(), "{name}[{k}]: {u:e} vs {w:e}");
        }
        rows = x.len();
    }
    for field in ["final_state", "steps", "status"] {
        assert_eq!(s[field], r[field], "summary.{field}");
    }
    // The momentum maps bit for bit; what their symmetry was checked against differs (the
    // file's `L_d`, the rule's `L`).
    let (maps, rule_maps) = (s["momenta"].as_object().unwrap(), &r["momenta"]);
    for (name, m) in maps {
        for field in ["initial", "max_abs_drift", "symmetry"] {
            assert_eq!(
                m[field], rule_maps[name][field],
                "summary.momenta.{name}.{field}"
            );
        }
    }
    rows
}

/// R1 through the file's own `L_d`: the midpoint rule's discrete Lagrangian written by hand
/// reproduces `lagrangian` with `method = "midpoint"` (general path) bit for bit over 1000
/// steps — the file's `L_d` is evaluated in the displacement the integrator steps, with the
/// rule's operations (`marsden_expr::DisplacementForm`) — and both are on R1's closed form to
/// 1e-12 at N = 10, 100, 1000.
#[test]
fn r1_hand_written_midpoint_discrete_lagrangian_reproduces_method_midpoint_bit_for_bit() {
    let user = run_ok("discrete_oscillator_r1.toml", &["--quiet"]);
    let rule = run_ok("midpoint_oscillator_general.toml", &["--quiet"]);
    assert_eq!(assert_bit_for_bit(&user, &rule), 1001);
    let a = user.trajectory();
    for (n, q, p) in R1 {
        assert_close(column(&a, "q_x")[n], q, 1e-12, &format!("q_{n}"));
        assert_close(column(&a, "p_x")[n], p, 1e-12, &format!("p_{n}"));
    }
}

/// The example `examples/discrete_oscillator.toml` (a parameter `w`, `t_end = 20`) against the
/// same system as a continuous L with `method = "midpoint"` (general path): bit for bit, on
/// R1's map (w = 1, h = 0.1) to 1e-12 at N = 10, 100.
#[test]
fn discrete_oscillator_example_reproduces_method_midpoint_bit_for_bit() {
    let file = crate::util::repo_root().join("examples/discrete_oscillator.toml");
    let user = crate::util::marsden("run", &file, &["--quiet"]);
    assert_eq!(user.code, 0, "{}", user.stderr);
    let rule = run_ok("midpoint_discrete_oscillator_example.toml", &["--quiet"]);
    assert_eq!(assert_bit_for_bit(&user, &rule), 201);
    let a = user.trajectory();
    for (n, q, p) in &R1[..2] {
        assert_close(column(&a, "q_x")[*n], *q, 1e-12, &format!("q_{n}"));
        assert_close(column(&a, "p_x")[*n], *p, 1e-12, &format!("p_{n}"));
    }
}

/// Two degrees of freedom: the isotropic oscillator's hand-written midpoint `L_d` (the 2-DOF
/// step kernel) against `method = "midpoint"` on the general path, bit for bit over 1000 steps,
/// the rotation's momentum map included.
#[test]
fn two_dof_hand_written_midpoint_reproduces_method_midpoint_bit_for_bit() {
    let user = run_ok("discrete_rotation.toml", &["--quiet"]);
    let rule = run_ok("midpoint_rotation_general.toml", &["--quiet"]);
    assert_eq!(assert_bit_for_bit(&user, &rule), 101);
    assert!(user.summary()["momenta"]["rotation"].is_object());
}

/// R1's file run: no continuous L, so no energy anywhere — no column, every number of
/// `energy` null, the reason in `energy_not_available` and on the console; the method is the
/// file's `L_d` (no order).
#[test]
fn r1_discrete_lagrangian_run_reports_no_energy() {
    let run = run_ok("discrete_oscillator_r1.toml", &[]);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    assert_eq!(s["system"], "discrete_lagrangian");
    assert_eq!(s["method"], "discrete_lagrangian");
    assert!(s["order"].is_null());
    let why = "not available (no continuous Lagrangian: the file gives L_d)";
    assert_eq!(s["energy_not_available"], why);
    for field in [
        "initial",
        "max_abs_error",
        "max_rel_error",
        "final_rel_error",
        "drift_per_unit_time",
    ] {
        assert!(
            s["energy"][field].is_null(),
            "energy.{field}: {}",
            s["energy"][field]
        );
    }
    assert_eq!(s["energy"]["samples"], 0);
    let columns = &s["output"]["columns"];
    assert_eq!(columns, &serde_json::json!(["t", "q_x", "p_x"]));
    assert!(run.trajectory().values("energy").is_none());
    assert!(
        run.stdout.contains(&format!("energy      {why}")),
        "{}",
        run.stdout
    );
    let q = s["final_state"]["q"][0].as_f64().unwrap();
    assert_close(q, R1[2].1, 1e-12, "q_1000");
}

/// The rotation of the plane is a symmetry of the isotropic oscillator's midpoint `L_d`, and
/// `J = x p_y − y p_x` (a function of `(q, p)` alone) is a quadratic invariant of the midpoint
/// map: monitored with the file's `L_d`, it stays at `J₀ = 0.5` to round-off over 1000 steps.
#[test]
fn discrete_lagrangian_monitors_the_momentum_map_of_a_symmetry() {
    let run = run_ok("discrete_rotation.toml", &["--quiet"]);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    assert_close(number(&s, "momenta.rotation.initial"), 0.5, 1e-15, "J0");
    let drift = number(&s, "momenta.rotation.max_abs_drift");
    assert!(drift <= 1e-12, "max |J − J0| = {drift:e}");
    assert_eq!(column(&run.trajectory(), "J_rotation").len(), 101);
}

/// A declared symmetry is checked against the file's `L_d` at the start: the translation in x
/// is not one of the oscillator's (`⟨dL_d, ξ⟩ = −h x̄ = −h(q₀ + h p₀/2)·1` at the first step,
/// here −0.1), so the run warns with the defect and goes on; the rotation is one (no warning).
#[test]
fn discrete_lagrangian_symmetries_are_checked_at_the_start() {
    let run = run_ok("discrete_translation_not_symmetric.toml", &["--quiet"]);
    assert!(
        run.stderr
            .contains("\"shift\" is not a symmetry of the discrete Lagrangian"),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains("1.000e-1"), "{}", run.stderr);
    let rotation = run_ok("discrete_rotation.toml", &["--quiet"]);
    assert!(
        !rotation.stderr.contains("not a symmetry"),
        "{}",
        rotation.stderr
    );
}

fn rejected(name: &str, fragments: &[&str]) -> Run {
    assert_rejected(name, fragments)
}

#[test]
fn discrete_lagrangian_refuses_a_continuous_lagrangian_beside_it() {
    rejected(
        "discrete_and_lagrangian.toml",
        &[
            "give either `discrete_lagrangian` or `lagrangian`, not both",
            "^",
        ],
    );
}

#[test]
fn discrete_lagrangian_refuses_a_method() {
    rejected(
        "discrete_with_method.toml",
        &[
            "`method` cannot be used with `discrete_lagrangian`",
            "is the method",
            "^",
        ],
    );
}

#[test]
fn discrete_lagrangian_refuses_velocities_and_says_to_give_momenta() {
    rejected(
        "discrete_with_velocity.toml",
        &[
            "`v` cannot be used with `discrete_lagrangian`",
            "no continuous Lagrangian to turn a velocity into a momentum",
            "p = [...]",
            "^",
        ],
    );
}

#[test]
fn discrete_lagrangian_refuses_forces_constraints_sensitivities_and_certificates() {
    for (file, key) in [
        ("discrete_with_forces.toml", "forces"),
        ("discrete_with_constraints.toml", "constraints"),
        ("discrete_with_sensitivity.toml", "[sensitivity]"),
        ("discrete_with_certify.toml", "certify"),
    ] {
        let message = format!("`{key}` cannot be used with `discrete_lagrangian`");
        rejected(file, &[&message, "^"]);
    }
}

#[test]
fn discrete_lagrangian_points_at_unknown_names_and_missing_coordinates() {
    let run = rejected(
        "discrete_unknown_name.toml",
        &["x_dot", "^", "[system] discrete_lagrangian"],
    );
    assert!(
        run.stderr.contains("x_0") || run.stderr.contains("x_1"),
        "{}",
        run.stderr
    );
    rejected(
        "discrete_without_coordinates.toml",
        &[
            "a `discrete_lagrangian` needs `coordinates` in [system]",
            "^",
        ],
    );
}

/// `marsden order` studies rules against a reference from a continuous L: refused, exit 2.
#[test]
fn order_refuses_a_discrete_lagrangian_file() {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture("discrete_oscillator_r1.toml");
    let output = marsden_in(tmp.path(), &["order", path.to_str().unwrap()]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("`marsden order` cannot study a `discrete_lagrangian` file"),
        "{stderr}"
    );
}

/// The 2-DOF rotation file with a frequency parameter `w`, written to `dir` with `extra` appended.
fn rotation_file(dir: &std::path::Path, w: f64, extra: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string(fixture("discrete_rotation.toml"))
        .unwrap()
        .replace(
            "[system]",
            &format!("[system]\nparameters = {{ w = {w:?} }}"),
        )
        .replace("- 0.5*(((x_0", "- 0.5*w^2*(((x_0");
    let path = dir.join(format!("rotation_{w}.toml"));
    std::fs::write(&path, text + extra).unwrap();
    path
}

/// `[sweep]` over a `discrete_lagrangian` file: one row per member with the momentum map of the
/// declared rotation and the final state (no energy columns: there is no energy), each
/// member's final state equal bit for bit to the single run of the file at that `w`; a
/// member whose `L_d` overflows (`w = 1e200`) fails in its row while the others complete.
#[test]
fn sweep_over_a_discrete_lagrangian_keeps_each_members_final_state_and_momentum_map() {
    let dir = tempfile::tempdir().unwrap();
    let values = [0.5, 1.0, 1e200, 2.0];
    let sweep = format!("\n[sweep]\nparameter = \"w\"\nvalues = {values:?}\n");
    let run = crate::util::marsden("run", &rotation_file(dir.path(), 1.0, &sweep), &[]);
    assert_eq!(
        run.code, 1,
        "a member failed: {}\n{}",
        run.stdout, run.stderr
    );
    let table = crate::util::SweepTable::read(&run.out.join("sweep.csv"));
    assert!(
        !table
            .header
            .iter()
            .any(|h| h.starts_with("energy") || h.starts_with("balance")),
        "{:?}",
        table.header
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(run.out.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["members"], 4);
    assert_eq!(summary["failed"], 1);
    assert!(summary["energy_not_available"].is_string(), "{summary:#}");
    let text = std::fs::read_to_string(run.out.join("sweep.csv")).unwrap();
    let failed = text.lines().nth(3).unwrap();
    assert!(
        failed.starts_with("2,") && failed.contains(",failed,"),
        "{failed}"
    );
    for (k, w) in values.iter().enumerate().filter(|(k, _)| *k != 2) {
        let single = crate::util::marsden("run", &rotation_file(dir.path(), *w, ""), &["--quiet"]);
        assert_eq!(single.code, 0, "{}", single.stderr);
        let s = single.summary();
        for (i, c) in ["x", "y"].iter().enumerate() {
            for (v, name) in [("q", format!("q_{c}")), ("p", format!("p_{c}"))] {
                let alone = s["final_state"][v][i].as_f64().unwrap();
                let member = table.column(&name)[k];
                assert_eq!(member.to_bits(), alone.to_bits(), "w = {w}: {name}");
            }
        }
        assert_eq!(
            table.column("J_rotation")[k],
            0.5,
            "w = {w}: J₀ = x p_y − y p_x"
        );
        let drift = table.column("J_rotation_drift")[k];
        assert!(drift <= 1e-12, "w = {w}: J drift {drift:e}");
    }
    assert_eq!(table.column("steps")[2], 0.0);
}

/// What still cannot be swept in a `discrete_lagrangian` file is refused with the reason: its
/// initial data are momenta, so there is no velocity `v[i]` to sweep.
#[test]
fn discrete_lagrangian_sweep_of_a_velocity_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let sweep = "\n[sweep]\ninitial = \"v[0]\"\nvalues = [0.1, 0.2]\n";
    let run = crate::util::marsden("run", &rotation_file(dir.path(), 1.0, sweep), &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains("cannot sweep `v[0]`") && run.stderr.contains("^"),
        "{}",
        run.stderr
    );
}
