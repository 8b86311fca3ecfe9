//! Every problem file in `examples/` runs (with fewer steps), as CI does; `pendulum.toml` also
//! the way README.md quotes it, from the repository root with a relative path.

use crate::util::{marsden, marsden_in, repo_root};

#[test]
fn every_example_runs_with_reduced_steps() {
    let mut files: Vec<_> = std::fs::read_dir(repo_root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "examples: {files:?}");
    for file in &files {
        let name = file.display();
        if std::fs::read_to_string(file)
            .unwrap()
            .contains("\n[optimal_control]")
        {
            optimal_control_example(file);
            continue;
        }
        let run = marsden("run", file, &["--steps", "40", "--quiet"]);
        assert_eq!(run.code, 0, "{name}: {}", run.stderr);
        assert!(run.stdout.is_empty(), "--quiet");
        let s = run.summary();
        assert_eq!(s["status"], "completed", "{name}");
        assert_eq!(s["steps"], 40, "{name}");
        // An energy error where energy is conserved, the balance of the forces otherwise, and
        // for a file's own L_d (no continuous L) the reason there is none.
        if !s["energy_not_available"].is_null() {
            assert!(s["energy"]["max_rel_error"].is_null(), "{name}: energy");
            continue;
        }
        match s["energy_not_conserved"].is_null() {
            true => assert!(
                s["energy"]["max_rel_error"].as_f64().is_some(),
                "{name}: energy"
            ),
            false => assert!(
                s["energy_balance"]["max_defect"].as_f64().is_some(),
                "{name}: energy balance"
            ),
        }
    }
}

/// An optimal control example: `marsden run` refuses it (exit 2, pointing at `marsden
/// optimize`); `marsden optimize` converges at the file's own N (a few seconds at most: the
/// solve is not reduced, since a local optimum found at one N need not exist at another) and
/// writes its files.
fn optimal_control_example(file: &std::path::Path) {
    let name = file.display();
    let run = marsden("run", file, &["--steps", "40", "--quiet"]);
    assert_eq!(run.code, 2, "{name}: {}", run.stderr);
    assert!(
        run.stderr.contains("solve it with `marsden optimize`"),
        "{name}: {}",
        run.stderr
    );
    let solve = marsden("optimize", file, &["--quiet"]);
    assert_eq!(solve.code, 0, "{name}: {}", solve.stderr);
    assert!(solve.stdout.is_empty(), "--quiet");
    let s = solve.summary();
    assert_eq!(s["optimal_control"]["status"], "converged", "{name}");
    let steps = s["steps"].as_u64().unwrap() as usize;
    let trajectory = marsden_io::read_csv(solve.out.join("trajectory.csv")).unwrap();
    assert_eq!(trajectory.values("t").unwrap().len(), steps + 1, "{name}");
    for f in [
        "trajectory.csv",
        "controls.csv",
        "controls.png",
        "convergence.png",
    ] {
        assert!(solve.out.join(f).is_file(), "{name}: {f}");
    }
}

#[test]
fn every_catalog_system_has_an_example() {
    let root = repo_root().join("examples");
    for name in [
        "harmonic_oscillator",
        "free_fall",
        "pendulum",
        "double_pendulum",
        "kepler",
        "henon_heiles",
        "nbody",
        "free_rigid_body",
        "heavy_top",
    ] {
        assert!(
            root.join(format!("{name}.toml")).is_file(),
            "examples/{name}.toml"
        );
    }
}

#[test]
fn readme_command_works_from_the_repository_root() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("pendulum");
    let args = [
        "run",
        "examples/pendulum.toml",
        "--steps",
        "200",
        "--out",
        out.to_str().unwrap(),
    ];
    let output = marsden_in(&repo_root(), &args);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(
        stdout.starts_with("pendulum: expression, 1 coordinate (theta), midpoint"),
        "{stdout}"
    );
    assert!(out.join("trajectory.csv").is_file() && out.join("energy_error.png").is_file());
}
