//! Hostile conditions end to end: a full disk (the file that failed named, `rows` equal to the
//! whole rows on disk), methods whose every step solves a huge Newton system (said by `check`),
//! counts too large for a method name, constraints that do not depend on the coordinates.

use std::process::Command;

use serde_json::Value;

use crate::util::{assert_rejected, marsden};

/// A 1-DOF pendulum with `method`, checked by `marsden check`: (exit code, stderr).
fn check_pendulum(method: &str, lagrangian: &str) -> (i32, String) {
    let tmp = tempfile::tempdir().unwrap();
    let problem = tmp.path().join("pendulum.toml");
    std::fs::write(
        &problem,
        format!(
            "[system]\ncoordinates = [\"theta\"]\nlagrangian = \"{lagrangian}\"\n\
             [initial]\nq = [1.0]\nv = [0.0]\n\
             [integrator]\nmethod = \"{method}\"\nh = 0.05\nsteps = 10\n"
        ),
    )
    .unwrap();
    let run = marsden("check", &problem, &[]);
    (run.code, run.stderr)
}

/// `triple-jump-10(gauss-10)` composes 81 substeps of 10 segments into one step: 810 unknowns
/// per degree of freedom, named by `check` with a pointer; small or explicit steps get no
/// warning.
#[test]
fn check_warns_of_a_huge_composition_with_its_newton_system_size() {
    let pendulum = "0.5*theta_dot^2 + cos(theta)";
    let (code, stderr) = check_pendulum("triple-jump-10(gauss-10)", pendulum);
    assert_eq!(code, 0, "{stderr}");
    for fragment in [
        "warning: the method `triple-jump-10(gauss-10)`",
        "810 unknowns",
        "fewer substeps",
        "gauss-s with a smaller s",
    ] {
        assert!(stderr.contains(fragment), "lacks {fragment:?}:\n{stderr}");
    }
    // 27 substeps of gauss-2: 54 unknowns; gauss-10 alone: 10.
    for method in ["triple-jump-8(gauss-2)", "gauss-10"] {
        let (code, stderr) = check_pendulum(method, pendulum);
        assert_eq!((code, stderr.as_str()), (0, ""), "{method}");
    }
    // Velocity Störmer–Verlet substeps are explicit: no Newton system at all.
    let (code, stderr) = check_pendulum("triple-jump-10(trapezoid)", pendulum);
    assert_eq!((code, stderr.as_str()), (0, ""));
    // …unless L is not separable: then 81 implicit trapezoid substeps, 81 unknowns (at most 100
    // pass without a word); with gauss-3 substeps 243.
    let coupled = "0.5*(1 + 0.1*cos(theta))*theta_dot^2 + cos(theta)";
    let (code, stderr) = check_pendulum("triple-jump-10(trapezoid)", coupled);
    assert_eq!((code, stderr.as_str()), (0, ""));
    let (code, stderr) = check_pendulum("triple-jump-10(gauss-3)", coupled);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("243 unknowns"), "{stderr}");
}

/// A stage count with more digits than any count is "too large", with the accepted range.
#[test]
fn a_huge_stage_count_is_too_large_with_the_accepted_range() {
    let run = assert_rejected(
        "method_count_too_large.toml",
        &[
            "the number of stages 99999999999999999999 is too large",
            "gauss-<s> takes 1 ≤ s ≤ 10",
        ],
    );
    assert!(!run.stderr.contains("not a whole number"), "{}", run.stderr);
}

/// `constraints = [..., "0"]`: refused at load time with the file's line and column and a
/// caret under that array element.
#[test]
fn a_constraint_without_coordinates_is_pointed_at_with_a_caret() {
    let run = assert_rejected(
        "constraint_constant.toml",
        &[
            "constraint 1 does not depend on the coordinates",
            "constraint_constant.toml:4:",
        ],
    );
    let lines: Vec<&str> = run.stderr.lines().collect();
    let source = lines
        .iter()
        .position(|l| l.contains("constraints = [\"x^2 + y^2 - 1\", \"0\"]"))
        .unwrap_or_else(|| panic!("no source line:\n{}", run.stderr));
    let (text, caret) = (lines[source], lines[source + 1]);
    let column = text.find("\"0\"").unwrap() + 1;
    assert_eq!(caret.find('^'), Some(column), "{}", run.stderr);
}

/// A trajectory write that fails (here EFBIG under a 20 KiB file-size limit, SIGXFSZ ignored
/// as a batch system may) names `trajectory.csv`, ends the run as failed (exit 1) with a
/// summary saying so, and `rows` in `summary.json` equals the whole data rows in the CSV,
/// which ends on a row boundary.
#[test]
fn a_full_disk_names_the_trajectory_and_rows_match_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let problem = tmp.path().join("long.toml");
    std::fs::write(
        &problem,
        "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\n\
         [initial]\nq = [1]\nv = [0]\n[integrator]\nh = 0.01\nsteps = 100000\n\
         [output]\nplots = false\n",
    )
    .unwrap();
    let out = tmp.path().join("out");
    // dash counts `ulimit -f` in 512-byte blocks: 40 blocks = 20 KiB.
    let output = Command::new("sh")
        .arg("-c")
        .arg("trap '' XFSZ; ulimit -f 40; exec \"$0\" run \"$1\" --out \"$2\" --no-progress")
        .arg(env!("CARGO_BIN_EXE_marsden"))
        .arg(&problem)
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    let csv = out.join("trajectory.csv");
    assert!(
        stderr.contains(&csv.display().to_string()),
        "the message names {}:\n{stderr}",
        csv.display()
    );
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "failed");
    let error = summary["error"].as_str().unwrap();
    assert!(error.contains("trajectory.csv"), "{error}");
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.len() <= 40 * 512, "{} bytes", text.len());
    assert!(text.ends_with('\n'), "the CSV ends inside a row");
    let mut lines = text.lines();
    let width = lines.next().unwrap().split(',').count();
    let rows: Vec<&str> = lines.collect();
    assert!(rows.iter().all(|r| r.split(',').count() == width));
    assert!(!rows.is_empty() && rows.len() < 100_001);
    assert_eq!(summary["output"]["rows"].as_u64(), Some(rows.len() as u64));
}
