//! End-to-end: `check`, `systems`, `plot` and usage errors.

use crate::util::{fixture, marsden, marsden_in, run_ok};

fn code(output: &std::process::Output) -> i32 {
    output.status.code().unwrap_or(-1)
}

#[test]
fn check_prints_the_resolved_problem_and_writes_nothing() {
    let run = marsden("check", &fixture("pendulum_builtin.toml"), &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    for fragment in [
        "system       pendulum: builtin pendulum",
        "parameters   m = 1, l = 1, g = 1",
        "v = [0.0], p = [0.0] (v given, p = ∂L/∂q̇)",
        "energy E0 = -0.0707372016677029",
        "midpoint (order 2), h = 0.05, 4000 steps, t = 0 → 200",
        "columns: t, q_theta, p_theta, energy",
        "ok: the problem file is valid",
    ] {
        assert!(
            run.stdout.contains(fragment),
            "lacks {fragment:?}:\n{}",
            run.stdout
        );
    }
    assert!(!run.out.exists());
    let bad = marsden("check", &fixture("bad/unknown_method.toml"), &[]);
    assert_eq!(bad.code, 2);
    assert!(bad.stderr.contains("unknown method `midpiont`"));
}

#[test]
fn systems_lists_the_catalog_with_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let out = marsden_in(dir.path(), &["systems"]);
    assert_eq!(code(&out), 0);
    let text = String::from_utf8(out.stdout).unwrap();
    for name in [
        "harmonic_oscillator",
        "free_fall",
        "pendulum",
        "double_pendulum",
        "kepler",
        "henon_heiles",
        "nbody",
    ] {
        assert!(
            text.contains(&format!("\n{name}  —  ")),
            "{name} missing:\n{text}"
        );
    }
    assert!(text.contains("parameters   m = 1 (mass), g = 9.81 (field strength)"));
    assert!(text.contains("masses = [..] (required: one mass per body), G = 1"));
    let one = marsden_in(dir.path(), &["systems", "kepler"]);
    let one = String::from_utf8(one.stdout).unwrap();
    assert!(
        one.starts_with("kepler  —  ") && !one.contains("pendulum"),
        "{one}"
    );
    let bad = marsden_in(dir.path(), &["systems", "keppler"]);
    assert_eq!(code(&bad), 2);
    assert!(
        String::from_utf8(bad.stderr)
            .unwrap()
            .contains("did you mean `kepler`?")
    );
}

#[test]
fn plot_redraws_a_finished_run() {
    let run = run_ok("kepler_symmetry.toml", &[]);
    for png in [
        "phase_portrait.png",
        "energy_error.png",
        "momentum_drift.png",
    ] {
        std::fs::remove_file(run.out.join(png)).unwrap();
    }
    let out = marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    assert_eq!(code(&out), 0, "{}", String::from_utf8_lossy(&out.stderr));
    for png in [
        "phase_portrait.png",
        "energy_error.png",
        "momentum_drift.png",
    ] {
        assert!(run.out.join(png).is_file(), "{png}");
    }
    let empty = tempfile::tempdir().unwrap();
    let out = marsden_in(empty.path(), &["plot", "."]);
    assert_eq!(code(&out), 2);
    assert!(
        String::from_utf8(out.stderr)
            .unwrap()
            .contains("is it the output directory of a run?")
    );
}

#[test]
fn plot_reads_npy_runs_through_the_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("npy.toml");
    let text = std::fs::read_to_string(fixture("kepler_symmetry.toml")).unwrap();
    std::fs::write(
        &file,
        text.replace("plots = true", "plots = false\nformat = \"npy\""),
    )
    .unwrap();
    let run = marsden("run", &file, &["--steps", "200"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.out.join("J.npy").is_file());
    let out = marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    assert_eq!(code(&out), 0, "{}", String::from_utf8_lossy(&out.stderr));
    assert!(run.out.join("momentum_drift.png").is_file());
}

#[test]
fn usage_errors_exit_with_2_and_help_with_0() {
    let dir = tempfile::tempdir().unwrap();
    let missing = marsden_in(dir.path(), &["run"]);
    assert_eq!(code(&missing), 2);
    assert!(
        String::from_utf8(missing.stderr)
            .unwrap()
            .contains("<FILE>")
    );
    assert_eq!(code(&marsden_in(dir.path(), &["frobnicate"])), 2);
    assert_eq!(
        code(&marsden_in(
            dir.path(),
            &["run", "x.toml", "--steps", "many"]
        )),
        2
    );
    let nofile = marsden_in(dir.path(), &["run", "nowhere.toml"]);
    assert_eq!(code(&nofile), 2);
    assert!(
        String::from_utf8(nofile.stderr)
            .unwrap()
            .contains("cannot read the problem file nowhere.toml")
    );
    let help = marsden_in(dir.path(), &["run", "--help"]);
    assert_eq!(code(&help), 0);
    assert!(String::from_utf8(help.stdout).unwrap().contains("--steps"));
}
