//! A run stopped by SIGTERM (a cluster's time limit) or SIGINT writes its summary with status
//! "interrupted" and the last state, and exits with 1.

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

fn stopped_by(signal: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let problem = tmp.path().join("long.toml");
    std::fs::write(
        &problem,
        "[system]\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2 - 0.5*x^2\"\n\
         [initial]\nq = [1]\nv = [0]\n[integrator]\nh = 0.01\nsteps = 1000000000\n\
         [output]\nevery = 1000\nplots = false\n",
    )
    .unwrap();
    let out = tmp.path().join("out");
    let mut child = Command::new(env!("CARGO_BIN_EXE_marsden"))
        .arg("run")
        .arg(&problem)
        .arg("--out")
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the run has written rows, then signal it.
    let clock = Instant::now();
    while !out.join("trajectory.csv").exists() && clock.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(50));
    }
    std::thread::sleep(Duration::from_millis(300));
    let status = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let code = child.wait().unwrap().code();
    assert_eq!(code, Some(1), "{signal}");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["status"], "interrupted", "{signal}");
    let steps = summary["steps"].as_u64().unwrap();
    assert!(steps > 0 && steps < 1_000_000_000, "{steps}");
    let t = summary["final_state"]["t"].as_f64().unwrap();
    assert!(
        (t - steps as f64 * 0.01).abs() < 1e-6 * t.max(1.0),
        "{t} after {steps}"
    );
}

#[test]
fn sigterm_writes_an_interrupted_summary_with_the_last_state() {
    stopped_by("-TERM");
}

#[test]
fn sigint_writes_an_interrupted_summary_with_the_last_state() {
    stopped_by("-INT");
}
