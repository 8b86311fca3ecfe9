//! Silent wrong answers users met, each guarded: a run never reports a state, a conservation
//! or a "completed" status it does not have.

use crate::util::{assert_close, fixture, marsden, number};

/// `method = "exact"` with a step too long for its shooting: the boundary value problem of
/// `L_d^E` has no solution near the chord's guess, so the step fails (status "failed", exit 1,
/// the message says why) instead of returning the initial state as "completed".
#[test]
fn exact_step_whose_shooting_fails_is_a_failure_not_the_initial_state() {
    for name in [
        "exact_long_step.toml",
        "exact_spring_pendulum_long_step.toml",
    ] {
        let run = marsden("run", &fixture(name), &[]);
        assert_eq!(run.code, 1, "{name}: {}\n{}", run.stdout, run.stderr);
        let s = run.summary();
        assert_eq!(s["status"], "failed", "{name}");
        assert_eq!(number(&s, "steps"), 0.0, "{name}: no step was taken");
        let error = s["error"].as_str().unwrap_or_default();
        assert!(
            error.contains("shooting") || error.contains("not finite"),
            "{name}: {error}"
        );
        // Only the initial state was written.
        assert_eq!(
            crate::util::column(&run.trajectory(), "t").len(),
            1,
            "{name}"
        );
    }
}

/// The same pendulum over the same T = 4 in steps the shooting solves: the exact flow,
/// θ(4) from the closed form (Jacobi elliptic functions, `marsden::special::pendulum`).
#[test]
fn exact_method_in_short_steps_reaches_the_closed_form_state() {
    let run = marsden("run", &fixture("exact_short_steps.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    let exact = marsden::special::pendulum::Pendulum::new(1.5, 0.0, 1.0).unwrap();
    let (theta, thetadot) = exact.state(4.0).unwrap();
    assert!((theta + 1.4391).abs() < 1e-4, "closed form θ(4) = {theta}");
    let q = s["final_state"]["q"][0].as_f64().unwrap();
    let p = s["final_state"]["p"][0].as_f64().unwrap();
    assert_close(q, theta, 1e-9, "θ(4)");
    assert_close(p, thetadot, 1e-9, "p(4)");
}

/// A generator that annihilates `dL` at the initial state only (`L = ½ẋ² − ½x²`, translation,
/// `x₀ = 0`) is checked at states near it too, and the run says it is no symmetry: a warning,
/// `symmetry = false` and what was checked in summary.json, and the printed line.
#[test]
fn a_symmetry_true_only_at_the_initial_state_is_reported_as_none() {
    for (name, map) in [
        ("symmetry_only_at_start.toml", "P"),
        ("symmetry_magnetic_translation.toml", "Px"),
    ] {
        let run = marsden("run", &fixture(name), &[]);
        assert_eq!(run.code, 0, "{name}: {}", run.stderr);
        assert!(
            run.stderr
                .contains(&format!("\"{map}\" is not a symmetry of the Lagrangian"))
                && run.stderr.contains("8 states near it"),
            "{name}: {}",
            run.stderr
        );
        let m = &run.summary()["momenta"][map];
        assert_eq!(m["symmetry"], false, "{name}: {m}");
        assert!(
            m["checked"]
                .as_str()
                .unwrap()
                .starts_with("L at the initial state and 8 states"),
            "{m}"
        );
        assert!(
            run.stdout
                .contains("not a symmetry: monitored, not conserved"),
            "{}",
            run.stdout
        );
    }
}

/// A true symmetry (Kepler's rotation) passes the same check at every state: no warning,
/// `symmetry = true`, a relative defect at round-off.
#[test]
fn a_true_symmetry_passes_the_check_at_every_state() {
    let run = marsden("run", &fixture("kepler_symmetry.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(!run.stderr.contains("is not a symmetry"), "{}", run.stderr);
    let s = run.summary();
    let (_, m) = s["momenta"].as_object().unwrap().iter().next().unwrap();
    assert_eq!(m["symmetry"], true, "{m}");
    let checked = m["checked"].as_str().unwrap();
    let defect: f64 = checked.rsplit(' ').next().unwrap().parse().unwrap();
    assert!(defect <= 1e-14, "{checked}");
    assert!(!run.stdout.contains("not a symmetry"), "{}", run.stdout);
}

/// A step system larger than memory (a 10-fold triple jump of gauss-10 on 50 coordinates:
/// 40 500 unknowns, a 13 GB Jacobian) is refused before anything is allocated or written:
/// exit 2, the size, the alternatives, a caret at the method; `check` says the same.
#[test]
fn a_step_system_larger_than_memory_is_refused_with_its_size() {
    let tmp = tempfile::tempdir().unwrap();
    let names: Vec<String> = (1..=50).map(|i| format!("x{i}")).collect();
    let kinetic: Vec<String> = names.iter().map(|x| format!("{x}_dot^2")).collect();
    let potential: Vec<String> = names.iter().map(|x| format!("{x}^2")).collect();
    let text = format!(
        "[system]\ncoordinates = [{}]\nlagrangian = \"0.5*({}) - 0.5*({})\"\n\
         [initial]\nq = [{}]\nv = [{}]\n[integrator]\nmethod = \"triple-jump-10(gauss-10)\"\n\
         h = 0.1\nsteps = 10\n",
        names
            .iter()
            .map(|x| format!("\"{x}\""))
            .collect::<Vec<_>>()
            .join(", "),
        kinetic.join(" + "),
        potential.join(" + "),
        vec!["0.1"; 50].join(", "),
        vec!["0.0"; 50].join(", "),
    );
    let file = tmp.path().join("huge.toml");
    std::fs::write(&file, text).unwrap();
    for command in ["run", "check"] {
        let run = marsden(command, &file, &[]);
        assert_eq!(run.code, 2, "{command}: {}", run.stderr);
        for fragment in ["40500 unknowns", "GiB", "triple-jump-4", "^"] {
            assert!(
                run.stderr.contains(fragment),
                "{command}: {fragment}: {}",
                run.stderr
            );
        }
        assert!(!run.out.exists(), "nothing written");
    }
}

/// `marsden order` on a constrained file with a Gauss rule is refused before any run, with the
/// message `marsden run` gives (no row of "failed" at every step size).
#[test]
fn order_refuses_a_gauss_rule_on_a_constrained_file_up_front() {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture("cartesian_pendulum.toml");
    let args = [
        "order",
        path.to_str().unwrap(),
        "--methods",
        "midpoint,gauss-2",
    ];
    let output = crate::util::marsden_in(tmp.path(), &args);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("the method `gauss-2` cannot be used with constraints"),
        "{stderr}"
    );
    assert!(String::from_utf8(output.stdout).unwrap().is_empty());
}

/// A `discrete_lagrangian` run with a symmetry, every 10th step stored: the momentum line counts
/// the rows it was monitored at (101), not the energy samples a file's own `L_d` does not have.
#[test]
fn a_discrete_lagrangian_run_counts_its_monitored_rows() {
    let run = marsden("run", &fixture("discrete_rotation.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let line = run
        .stdout
        .lines()
        .find(|l| l.trim_start().starts_with("momentum"))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    assert!(line.contains("(over 101 stored samples)"), "{line}");
}

/// An explicit run (Kepler, trapezoid: Störmer–Verlet) says it solved no Newton system, instead
/// of "0.00 iterations/step (max 0)"; summary.json counts its explicit steps.
#[test]
fn an_explicit_run_says_it_solved_no_newton_system() {
    let file = crate::util::repo_root().join("examples/henon_heiles.toml");
    let run = marsden("run", &file, &["--steps", "100"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stdout.contains("none: every step explicit"),
        "{}",
        run.stdout
    );
    assert_eq!(number(&run.summary(), "newton.explicit_steps"), 100.0);
}

/// `[sensitivity]`, `certify` and `every_step` in a sweep file were ignored with exit 0: they are
/// refused with a caret at the option.
#[test]
fn options_a_sweep_cannot_give_are_refused() {
    for (name, what) in [
        ("sweep_with_sensitivity.toml", "[sensitivity]"),
        ("sweep_with_certify.toml", "`certify = true`"),
        ("sweep_with_every_step.toml", "`every_step = true`"),
    ] {
        crate::util::assert_rejected(
            name,
            &[
                &format!("{what} cannot be used in a file with [sweep]"),
                "^",
            ],
        );
    }
}

/// `discrete_lagrangian = "0"` "completed" with a constant trajectory: a singular `D₁₂L_d` is
/// refused at the start, as a singular `∂²L/∂q̇²` is.
#[test]
fn a_singular_discrete_lagrangian_is_refused_at_the_start() {
    crate::util::assert_rejected(
        "discrete_lagrangian_zero.toml",
        &["the discrete Lagrangian is not regular", "D₁₂L_d", "^"],
    );
}

/// The order study's reference for a stiff spring pendulum over T = 1.8 is computed twice
/// (whole interval, pieces) and agrees with itself; midpoint then measures order 2 and gauss-2
/// order 4 (R5/R6), instead of a reference that diverged and blamed the Lagrangian.
#[test]
fn order_study_reference_is_validated() {
    let tmp = tempfile::tempdir().unwrap();
    let path = fixture("spring_pendulum_k20.toml");
    let args = [
        "order",
        path.to_str().unwrap(),
        "--methods",
        "midpoint,gauss-2",
        "--h",
        "0.05,0.025,0.0125,0.00625",
        "--t-end",
        "1.8",
    ];
    let output = crate::util::marsden_in(tmp.path(), &args);
    let stdout = String::from_utf8(output.stdout).unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(stdout.contains("two computations agree"), "{stdout}");
    for (method, expected) in [("midpoint", 2.0), ("gauss-2", 4.0)] {
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

/// `check` on a sweep file says it is a sweep (members, what varies), and a sweep's
/// summary.json names the method, `h` and the swept values every member shares.
#[test]
fn sweeps_say_what_they_sweep_in_check_and_summary() {
    let check = marsden("check", &fixture("pendulum_sweep.toml"), &[]);
    assert_eq!(check.code, 0, "{}", check.stderr);
    let line = check
        .stdout
        .lines()
        .find(|l| l.starts_with("sweep"))
        .unwrap_or_else(|| panic!("{}", check.stdout));
    assert!(
        line.contains("8 members") && line.contains("first (0.2)"),
        "{line}"
    );
    let run = marsden("run", &fixture("pendulum_sweep.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["kind"], "sweep");
    assert_eq!(s["method"], "midpoint");
    assert_eq!(number(&s, "h"), 0.05);
    assert_eq!(s["values"]["first"][0].as_f64(), Some(0.2));
    assert_eq!(s["values"]["last"][0].as_f64(), Some(1.6));
}

/// Under `ulimit -f` the run died by SIGXFSZ with no message and no summary: the write fails
/// like a full disk, the run says so (exit 1) and summary.json records the failure.
#[cfg(unix)]
#[test]
fn a_file_size_limit_fails_the_write_with_a_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let file = crate::util::repo_root().join("examples/pendulum.toml");
    let script = format!(
        "ulimit -f 64; exec '{}' run '{}' --steps 200000 --out '{}'",
        env!("CARGO_BIN_EXE_marsden"),
        file.display(),
        out.display()
    );
    let output = std::process::Command::new("bash")
        .args(["-c", &script])
        .output()
        .unwrap();
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("writing the trajectory failed"), "{stderr}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "failed");
    assert!(
        summary["error"]
            .as_str()
            .unwrap()
            .contains("writing the trajectory failed"),
        "{summary}"
    );
}

/// `marsden plot DIR` of a forced run says that it cannot redraw `energy_balance.png` (its
/// series is not in the run's files) instead of saying nothing.
#[test]
fn plot_says_it_cannot_redraw_the_energy_balance() {
    let run = marsden("run", &fixture("damped.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let output = crate::util::marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(output.status.code(), Some(0));
    assert!(
        stdout.contains("energy_balance.png is not redrawn"),
        "{stdout}"
    );
}

/// `hamiltonian = "0.25*p_x^4"` at p = 1 was refused as "not regular" at v = 0: the state's
/// velocity is v = ∂H/∂p = 1, where ∂²H/∂p² = 3. It runs; the free motion keeps p = 1 and
/// moves x by v·t = 1 over t = 1.
#[test]
fn a_hamiltonian_regular_at_the_state_but_not_at_rest_runs() {
    let run = marsden("run", &fixture("hamiltonian_quartic.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_close(
        s["final_state"]["p"][0].as_f64().unwrap(),
        1.0,
        1e-12,
        "p(1)",
    );
    assert_close(
        s["final_state"]["q"][0].as_f64().unwrap(),
        1.0,
        1e-12,
        "x(1)",
    );
}

/// `marsden plot` on a CSV run whose trajectory is gone names the missing trajectory.csv
/// (it once said "cannot open q.npy").
#[test]
fn plot_of_a_csv_run_without_its_trajectory_names_the_file() {
    let run = marsden("run", &fixture("damped.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    std::fs::remove_file(run.out.join("trajectory.csv")).unwrap();
    let output = crate::util::marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("has no trajectory.csv"), "{stderr}");
}

/// `marsden plot` on a directory whose trajectory.csv is `/dev/zero` (no line ends) is refused
/// with the file named, instead of reading until memory runs out.
#[cfg(unix)]
#[test]
fn plot_refuses_a_trajectory_without_line_ends() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    std::fs::create_dir(&dir).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("trajectory.csv")).unwrap();
    let output = crate::util::marsden_in(tmp.path(), &["plot", dir.to_str().unwrap()]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("trajectory.csv") && stderr.contains("longer than"),
        "{stderr}"
    );
}

/// `galerkin-3-gauss-3` with constraints was refused as "the method `gauss-3` …": a name the
/// user never wrote. The refusal of `run` and of `order --methods` names the written method
/// (and says which rule it is), with the caret on the file's `method`.
#[test]
fn constraint_refusal_names_the_method_as_written() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("galerkin.toml");
    let text = std::fs::read_to_string(fixture("cartesian_pendulum.toml")).unwrap();
    let text = text.replace("h = 0.05", "method = \"galerkin-3-gauss-3\"\nh = 0.05");
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("the method `galerkin-3-gauss-3` cannot be used with constraints")
            && run
                .stderr
                .contains("`galerkin-3-gauss-3` is the rule `gauss-3`")
            && run.stderr.contains("^^^"),
        "{}",
        run.stderr
    );
    let path = fixture("cartesian_pendulum.toml");
    let written = "midpoint,triple-jump-4(galerkin-2-gauss-2)";
    let args = ["order", path.to_str().unwrap(), "--methods", written];
    let output = crate::util::marsden_in(tmp.path(), &args);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains(
            "the method `triple-jump-4(galerkin-2-gauss-2)` cannot be used with constraints"
        ),
        "{stderr}"
    );
}

/// `marsden plot` on a trajectory.csv with bytes that are not UTF-8 (0xff) said only "stream
/// did not contain valid UTF-8": the message names the file, in the header and in a row (with
/// its line).
#[test]
fn plot_of_a_trajectory_that_is_not_utf8_names_the_file() {
    let run = marsden("run", &fixture("damped.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let csv = run.out.join("trajectory.csv");
    let text = std::fs::read(&csv).unwrap();
    let header_end = text.iter().position(|&b| b == b'\n').unwrap();
    let mut in_header = text.clone();
    in_header.insert(1, 0xff);
    let mut in_row = text;
    in_row.insert(header_end + 2, 0xff);
    for (bytes, fragment) in [(in_header, "first line is not UTF-8"), (in_row, "line 2")] {
        std::fs::write(&csv, bytes).unwrap();
        let output = crate::util::marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains(csv.to_str().unwrap()) && stderr.contains(fragment),
            "{stderr}"
        );
    }
}

/// `triple-jump-8(gauss-10)` was announced with "each step may take seconds": the warning of
/// `marsden check` states the cost up front. One degree of freedom, 27 substeps of 10
/// segments: u = 270 unknowns; the Jacobian and its LU factors hold 2·270²·8 B = 1.1 MiB; the
/// Jacobian is assembled from ⌈270/4⌉² = 4624 hyper-dual evaluations of the action, each of L at
/// its 270 Gauss nodes (1248480 evaluations of L), and factored in 2·270³/3 ≈ 1.3e7 flops
/// (Golub–Van Loan §3.2).
#[test]
fn large_step_system_warning_states_unknowns_bytes_and_flops() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("composed.toml");
    let text = "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\n\n\
                [initial]\nq = [1.0]\nv = [0.0]\n\n\
                [integrator]\nmethod = \"triple-jump-8(gauss-10)\"\nh = 0.1\nsteps = 1\n";
    std::fs::write(&file, text).unwrap();
    let output = crate::util::marsden_in(tmp.path(), &["check", file.to_str().unwrap()]);
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    for fragment in [
        "270 unknowns",
        "take 1.1 MiB",
        "from 4624 evaluations of the step's action",
        "(1248480 evaluations of L)",
        "≈ 1.3e7 flops",
    ] {
        assert!(stderr.contains(fragment), "{fragment}: {stderr}");
    }
    assert!(!stderr.contains("may take seconds"), "{stderr}");
}

/// `constraint_residual.png` drew `|φ(q)|` only: a constrained run now writes the hidden
/// constraint's residual `|Dφ(q)·v|` as the last column `constraint_velocity_residual` (every
/// earlier column keeps its name and place, observables included), and the plot draws it.
/// Cartesian pendulum (R7's system, unit mass, so `v = p`): `Dφ(q)·v = 2(x p_x + y p_y)`,
/// recomputed here from the written `q` and `p`; RATTLE keeps it at round-off
/// (HLW06 §VII.1).
#[test]
fn constrained_trajectory_records_the_hidden_constraint_residual() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("pendulum.toml");
    let text = std::fs::read_to_string(fixture("cartesian_pendulum.toml")).unwrap();
    let text = text.replace(
        "plots = true",
        "plots = true\nobservables = { r = \"sqrt(x^2 + y^2)\" }",
    );
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let csv = std::fs::read_to_string(run.out.join("trajectory.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "t",
            "q_x",
            "q_y",
            "p_x",
            "p_y",
            "energy",
            "constraint_residual",
            "lambda_0",
            "r",
            "constraint_velocity_residual"
        ]
    );
    let table = run.trajectory();
    let col = |name| crate::util::column(&table, name);
    let (x, y, px, py) = (col("q_x"), col("q_y"), col("p_x"), col("p_y"));
    let hidden = col("constraint_velocity_residual");
    assert_eq!(hidden.len(), 401);
    let mut largest: f64 = 0.0;
    for k in 0..hidden.len() {
        let expected = (2.0 * (x[k] * px[k] + y[k] * py[k])).abs();
        assert!(
            (hidden[k] - expected).abs() <= 1e-13,
            "row {k}: {} vs {expected}",
            hidden[k]
        );
        largest = largest.max(hidden[k]);
    }
    assert!(largest < 1e-10, "max |Dφ(q)·v| = {largest:e}");
    // The summary's maximum is over the same stored states.
    let recorded = number(&run.summary(), "constraints.max_velocity_residual");
    assert_eq!(recorded, largest, "summary's max |Dφ(q)·v|");
    assert!(run.out.join("constraint_residual.png").exists());
}

/// A short run's ns/step included the JIT's compilation of its tapes. The summary says the
/// compilation time (`jit_compile_seconds`, a part of `wall_seconds`), the report says it
/// apart, and the time per step printed is `(wall − jit)/steps`; with `MARSDEN_JIT=0`
/// nothing is compiled and the field is 0.
#[test]
fn time_per_step_leaves_out_the_jit_compilation() {
    let run = marsden("run", &fixture("pendulum_expression.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    let (wall, jit) = (
        number(&s, "wall_seconds"),
        number(&s, "jit_compile_seconds"),
    );
    assert!(jit > 0.0 && jit < wall, "jit {jit} s of wall {wall} s");
    let line = run
        .stdout
        .lines()
        .find(|l| l.contains("4000 steps"))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    assert!(line.contains("of it compiling native code"), "{line}");
    // The printed time per step, back in seconds.
    let per_step = line
        .split(" (")
        .nth(1)
        .unwrap()
        .split("/step")
        .next()
        .unwrap();
    let (value, unit) = per_step.split_once(' ').unwrap();
    let scale = match unit {
        "ns" => 1e-9,
        "µs" => 1e-6,
        "ms" => 1e-3,
        other => panic!("unit {other} in {line}"),
    };
    let printed = value.parse::<f64>().unwrap() * scale;
    let expected = (wall - jit) / 4000.0;
    assert!(
        (printed - expected).abs() <= 0.01 * expected + 0.5e-9,
        "{line}: {printed:e} vs (wall − jit)/steps = {expected:e}"
    );

    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let path = fixture("pendulum_expression.toml");
    let args = [
        "run",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_marsden"))
        .args(args)
        .env("MARSDEN_JIT", "0")
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0));
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(number(&s, "jit_compile_seconds"), 0.0);
    assert!(
        !String::from_utf8(output.stdout)
            .unwrap()
            .contains("compiling native code")
    );
}

/// A grid sweep's `sweep.png` drew every member against the first axis as loose dots,
/// ignoring the second axis: it now draws one curve per value of the second axis. A grid of
/// 2 values of `l` × 9 of `q[0]` has 9 curves, of which the plot shows the first 8 and says so.
#[test]
fn a_grid_sweep_plot_draws_one_curve_per_value_of_the_second_axis() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("grid.toml");
    let text = "[system]\nbuiltin = \"pendulum\"\nparameters = { l = 1.0 }\n\n\
                [initial]\nq = [0.5]\nv = [0.0]\n\n\
                [integrator]\nh = 0.05\nsteps = 20\n\n[output]\nplots = false\n\n\
                [sweep]\nparameter = \"l\"\nvalues = [0.5, 1.0]\n\n[sweep.and]\n\
                initial = \"q[0]\"\nvalues = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9]\n";
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let output = crate::util::marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(output.status.code(), Some(0), "{stdout}");
    assert!(run.out.join("sweep.png").is_file());
    assert!(
        stdout.contains("note: showing the first 8 of 9 combinations of q[0]"),
        "{stdout}"
    );
}

/// The N-body configuration plot listed every body in its legend, past the picture's bottom at
/// N = 64: the legend names the first 8 and ends with "… 56 more", and `marsden plot` says so.
#[test]
fn an_nbody_legend_of_64_bodies_is_capped() {
    let tmp = tempfile::tempdir().unwrap();
    let mut bodies = String::from("64\n1.0 0 0 0 0 0 0\n");
    for k in 1..64 {
        let a = k as f64 * std::f64::consts::TAU / 63.0;
        let r = 1.0 + (k % 4) as f64;
        let v = 1.0 / r.sqrt();
        bodies.push_str(&format!(
            "1e-6 {} {} 0 {} {} 0\n",
            r * a.cos(),
            r * a.sin(),
            -v * a.sin(),
            v * a.cos()
        ));
    }
    std::fs::write(tmp.path().join("bodies.txt"), bodies).unwrap();
    let file = tmp.path().join("nbody.toml");
    let text = "[system]\nbuiltin = \"nbody\"\nparameters = { G = 1.0, softening = 0.01 }\n\n\
                [initial]\nfile = \"bodies.txt\"\n\n\
                [integrator]\nmethod = \"trapezoid\"\nh = 0.01\nsteps = 20\n\n\
                [output]\nplots = true\n";
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.out.join("configuration.png").is_file());
    let output = crate::util::marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(output.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("note: the legend names the first 8 of 64 curves"),
        "{stdout}"
    );
}

/// `phi = "(x^2 + y^2 - 1)^2"` with `project = true` was accepted and the run failed at step 0
/// ("singular Newton Jacobian"); without `project` it was refused with no caret. Both are now
/// refused when the file is read, pointing at the constraint: its gradient vanishes on its zero
/// set (the constraint forces −Dφᵀλ cannot act, HLW06 §VII.1). The circle itself still runs.
#[test]
fn a_constraint_whose_gradient_vanishes_on_its_zero_set_is_refused_at_load() {
    let tmp = tempfile::tempdir().unwrap();
    let text = "[system]\ncoordinates = [\"x\", \"y\"]\n\
                lagrangian = \"0.5*(x_dot^2 + y_dot^2) - y\"\n\
                constraints = [\"(x^2 + y^2 - 1)^2\"]\n\n\
                [initial]\nq = [0.6, -0.9]\nv = [0.0, 0.0]\nproject = true\n\n\
                [integrator]\nh = 0.05\nsteps = 40\n";
    let on_manifold = text
        .replace("-0.9]", "-0.8]")
        .replace("project = true\n", "");
    for (name, text) in [
        ("projected.toml", text.to_owned()),
        ("on.toml", on_manifold),
    ] {
        let file = tmp.path().join(name);
        std::fs::write(&file, &text).unwrap();
        let run = marsden("run", &file, &[]);
        assert_eq!(run.code, 2, "{name}: {}", run.stderr);
        assert!(
            run.stderr.contains(
                "the gradient of constraint 0 `(x^2 + y^2 - 1)^2` vanishes on its zero set"
            ) && run.stderr.contains("^^^"),
            "{name}: {}",
            run.stderr
        );
        assert!(!run.out.exists(), "{name}: nothing is written");
        let circle = file.with_extension("circle.toml");
        std::fs::write(&circle, text.replace("(x^2 + y^2 - 1)^2", "x^2 + y^2 - 1")).unwrap();
        let run = marsden("run", &circle, &[]);
        assert_eq!(run.code, 0, "{name}: {}", run.stderr);
    }
}
