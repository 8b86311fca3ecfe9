//! Checkpoints and `marsden resume`: a run killed with SIGKILL at pseudo-random moments and
//! resumed leaves the files of the uninterrupted run byte for byte (`summary.json`'s wall-clock
//! times aside) — for the explicit Störmer–Verlet path, a Newton step (midpoint), a Galerkin
//! rule (gauss-2, with samples at chosen times reached by steps aside), a constrained run (RATTLE), runs with events, runs with `[sensitivity]`
//! (killed in the run or in its tangent run) and forced and time-dependent runs (their energy
//! and Noether balances carried), in CSV and `.npy`; bad
//! checkpoints and changed files are refused with nothing changed.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::util::{fixture, marsden_in};

/// A problem of one kind of step, long enough to be killed in the middle.
struct Case {
    name: &'static str,
    text: String,
    every: &'static str,
    /// The checkpoint file whose first appearance starts the clock of the kill
    /// (`sensitivity-checkpoint.bin`: the kill lands in the tangent run of `[sensitivity]`).
    wait_for: &'static str,
}

fn pendulum(method: &str, steps: u64) -> String {
    format!(
        "[system]\nbuiltin = \"pendulum\"\n[initial]\nq = [1.0]\nv = [0.0]\n\
         [integrator]\nmethod = \"{method}\"\nh = 0.01\nsteps = {steps}\n\
         [output]\nevery = 100\nplots = false\n"
    )
}

/// A pendulum whose `g` is a parameter of `L`, with `[sensitivity]` to `(q₀, p₀, g)`: 4·10⁵
/// midpoint steps, then as many of its tangent run.
const PARAMETRIC: &str = "[system]\ncoordinates = [\"theta\"]\n\
    lagrangian = \"0.5*theta_dot^2 + g*cos(theta)\"\nparameters = { g = 9.81 }\n\
    [initial]\nq = [1.0]\nv = [0.0]\n\
    [integrator]\nmethod = \"midpoint\"\nh = 0.01\nsteps = 400000\n\
    [sensitivity]\ninitial = true\nparameters = [\"g\"]\n\
    [output]\nevery = 100\nplots = false\n";

fn cases() -> Vec<Case> {
    let constrained = "[system]\ncoordinates = [\"x\", \"y\"]\n\
        lagrangian = \"0.5*(x_dot^2 + y_dot^2) - y\"\nconstraints = [\"x^2 + y^2 - 1\"]\n\
        [initial]\nq = [0.9974949866040544, -0.0707372016677029]\nv = [0.0, 0.0]\n\
        [integrator]\nmethod = \"midpoint\"\nh = 0.01\nsteps = 300000\n\
        [output]\nevery = 50\nplots = false\n";
    let events = "[system]\nbuiltin = \"henon_heiles\"\nparameters = { lambda = 1.0 }\n\
        [initial]\nq = [0.0, 0.1]\nv = [0.4802776974487434, 0.1]\n\
        [integrator]\nmethod = \"trapezoid\"\nh = 0.05\nsteps = 400000\n\
        [[events]]\nname = \"x_up\"\nwhen = \"x\"\ndirection = \"up\"\n\
        [output]\nevery = 100\nplots = false\nobservables = { r = \"sqrt(x^2 + y^2)\" }\n";
    let npy = pendulum("midpoint", 1_000_000)
        .replace("plots = false", "plots = false\nformat = \"npy\"")
        .replace(
            "[output]",
            "[[events]]\nname = \"down\"\nwhen = \"theta\"\ndirection = \"down\"\n[output]",
        );
    // The tangent run of the parametric model (a parameter of L differentiated, `PARAMETRIC`),
    // killed while it goes; and a builtin's tangent run in `.npy`, killed in the run or in the
    // tangent run.
    let tangent_npy = pendulum("gauss-2", 200_000)
        .replace("plots = false", "plots = false\nformat = \"npy\"")
        .replace("[output]", "[sensitivity]\ninitial = true\n[output]");
    // Forced: an orbit with drag (the energy balance and the forced Noether balance of the
    // rotation, both in the summary); a driven oscillator whose L reads t (∂L_d/∂t₀ in the
    // energy balance).
    let drag = "[system]\ncoordinates = [\"x\", \"y\"]\n\
        lagrangian = \"0.5*(x_dot^2 + y_dot^2) + 1/sqrt(x^2 + y^2)\"\n\
        forces = [\"-0.00001*x_dot\", \"-0.00001*y_dot\"]\n\
        [[system.symmetry]]\nrotation = \"z\"\n\
        [initial]\nq = [1.0, 0.0]\nv = [0.0, 1.2]\n\
        [integrator]\nmethod = \"midpoint\"\nh = 0.01\nsteps = 600000\n\
        [output]\nevery = 100\nplots = false\n";
    let driven = "[system]\ncoordinates = [\"x\"]\n\
        lagrangian = \"0.5*x_dot^2 - 0.5*x^2 + 0.1*x*cos(1.3*t)\"\n\
        [initial]\nq = [1.0]\nv = [0.0]\n\
        [integrator]\nmethod = \"trapezoid\"\nh = 0.01\nsteps = 800000\n\
        [output]\nevery = 100\nplots = false\n";
    // Samples at 400 chosen times between grid points, with an observable at each.
    let times: Vec<String> = (0..400)
        .map(|j| format!("{}", 0.37 + 24.9 * f64::from(j)))
        .collect();
    let sampled = pendulum("midpoint", 1_000_000).replace(
        "plots = false",
        &format!(
            "plots = false\ntimes = [{}]\nobservables = {{ c = \"cos(theta)\" }}",
            times.join(", ")
        ),
    );
    // Gauss-2 (its predictor carried) with 300 times reached by steps of their own size, taken
    // aside between grid points.
    let exact: Vec<String> = (0..300)
        .map(|j| format!("{}", 0.37 + 13.1 * f64::from(j)))
        .collect();
    let gauss_exact = pendulum("gauss-2", 400_000).replace(
        "plots = false",
        &format!(
            "plots = false\ntimes = [{}]\nexact_times = true",
            exact.join(", ")
        ),
    );
    let case = |name, text: String, every| Case {
        name,
        text,
        every,
        wait_for: "checkpoint.bin",
    };
    vec![
        case("explicit", pendulum("trapezoid", 3_000_000), "100000"),
        case("midpoint", pendulum("midpoint", 1_000_000), "50000"),
        case("gauss-2", gauss_exact, "20000"),
        case("constrained", constrained.to_owned(), "20000"),
        case("events", events.to_owned(), "30000"),
        case("npy", npy, "50000"),
        Case {
            name: "sensitivity",
            text: PARAMETRIC.to_owned(),
            every: "20000",
            wait_for: "sensitivity-checkpoint.bin",
        },
        case("sensitivity-npy", tangent_npy, "20000"),
        case("forced", drag.to_owned(), "30000"),
        case("time-dependent", driven.to_owned(), "40000"),
        case("times", sampled, "50000"),
    ]
}

/// `marsden run FILE --out OUT --checkpoint-every N -q --no-progress` as a child process.
fn spawn_run(file: &Path, out: &Path, every: &str) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_marsden"))
        .args([
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
        .args(["--checkpoint-every", every, "-q", "--no-progress"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

/// The files of a run directory, `summary.json` without its wall-clock lines.
pub(crate) fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !p.file_name().unwrap().to_str().unwrap().starts_with('.'))
        .collect();
    files.sort();
    files
        .into_iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_str().unwrap().to_owned();
            let bytes = std::fs::read(&p).unwrap();
            let bytes = match name.as_str() {
                "summary.json" => String::from_utf8(bytes)
                    .unwrap()
                    .lines()
                    .filter(|l| !l.contains("wall_seconds") && !l.contains("jit_compile_seconds"))
                    .collect::<Vec<_>>()
                    .join("\n")
                    .into_bytes(),
                _ => bytes,
            };
            (name, bytes)
        })
        .collect()
}

/// A pseudo-random delay in `0..limit` ms (xorshift, seeded per attempt: reproducible).
pub(crate) fn delay(seed: u64, limit: u64) -> Duration {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    Duration::from_millis(x % limit)
}

/// Kills a run with SIGKILL after its first checkpoint plus `wait`, then resumes it; whether
/// the kill found the run still going.
fn killed_and_resumed(case: &Case, file: &Path, out: &Path, wait: Duration) -> bool {
    let mut child = spawn_run(file, out, case.every);
    let clock = Instant::now();
    let checkpoint = out.join(case.wait_for);
    while !checkpoint.exists() && clock.elapsed() < Duration::from_secs(60) {
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(wait);
    // The run may have ended already: the resume then replays its last stretch.
    let running = child.try_wait().unwrap().is_none();
    let _ = child.kill();
    let _ = child.wait();
    let resumed = marsden_in(
        out.parent().unwrap(),
        &["resume", out.to_str().unwrap(), "-q", "--no-progress"],
    );
    let stderr = String::from_utf8_lossy(&resumed.stderr);
    assert!(resumed.status.success(), "{stderr}");
    running
}

#[test]
fn sigkill_at_random_moments_then_resume_equals_the_uninterrupted_run() {
    for (c, case) in cases().iter().enumerate() {
        let tmp = tempfile::tempdir().unwrap();
        let file = tmp.path().join(format!("{}.toml", case.name));
        std::fs::write(&file, &case.text).unwrap();
        let whole = tmp.path().join("whole");
        let clock = Instant::now();
        let status = spawn_run(&file, &whole, case.every).wait().unwrap();
        assert!(status.success(), "{}", case.name);
        // The kills land within the first third of the run's own duration after the checkpoint
        // that starts their clock (at most 400 ms): on a fast machine as on a slow one, the run
        // is still going at most of them (the sensitivity case's clock starts half-way).
        let limit = (clock.elapsed().as_millis() / 3).clamp(1, 400) as u64;
        let expected = contents(&whole);
        assert!(
            expected.iter().any(|(n, _)| n == "checkpoint.bin"),
            "{}",
            case.name
        );
        let mut killed_running = 0;
        for attempt in 0..3 {
            let out = tmp.path().join(format!("killed-{attempt}"));
            let seed = (c * 10 + attempt) as u64;
            killed_running +=
                usize::from(killed_and_resumed(case, &file, &out, delay(seed, limit)));
            let found = contents(&out);
            let names =
                |v: &[(String, Vec<u8>)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
            assert_eq!(
                names(&found),
                names(&expected),
                "{} attempt {attempt}",
                case.name
            );
            for ((name, a), (_, b)) in expected.iter().zip(&found) {
                assert!(
                    a == b,
                    "{}: {name} differs after kill {attempt} and resume",
                    case.name
                );
            }
        }
        assert!(
            killed_running > 0,
            "{}: every kill came after the run had ended",
            case.name
        );
    }
}

/// A finished run's directory with its checkpoint, in a temporary directory.
fn finished_run(tmp: &Path) -> (PathBuf, PathBuf) {
    let file = tmp.join("p.toml");
    std::fs::write(&file, pendulum("midpoint", 20_000)).unwrap();
    let out = tmp.join("out");
    assert!(spawn_run(&file, &out, "5000").wait().unwrap().success());
    (file, out)
}

/// `marsden resume` on `out`: exit code, stderr; and whether the files are untouched.
fn refused_resume(out: &Path) -> (i32, String, bool) {
    let before = contents(out);
    let r = marsden_in(
        out.parent().unwrap(),
        &["resume", out.to_str().unwrap(), "-q"],
    );
    let untouched = contents(out) == before;
    (
        r.status.code().unwrap(),
        String::from_utf8_lossy(&r.stderr).into_owned(),
        untouched,
    )
}

#[test]
fn a_changed_problem_file_is_refused_and_nothing_is_changed() {
    let tmp = tempfile::tempdir().unwrap();
    let (file, out) = finished_run(tmp.path());
    std::fs::write(
        &file,
        pendulum("midpoint", 20_000).replace("q = [1.0]", "q = [1.1]"),
    )
    .unwrap();
    let (code, stderr, untouched) = refused_resume(&out);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("has changed since the checkpoint"),
        "{stderr}"
    );
    assert!(untouched);
}

#[test]
fn missing_damaged_and_future_checkpoints_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (_, out) = finished_run(tmp.path());
    let path = out.join("checkpoint.bin");
    let good = std::fs::read(&path).unwrap();
    let mut flipped = good.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 0x40;
    let mut future = good.clone();
    future[8] = 9;
    let torn = good[..good.len() / 2].to_vec();
    let cases: [(&[u8], &str); 4] = [
        (&flipped, "CRC-32"),
        (&future, "format version 9"),
        (&torn, "CRC-32"),
        (b"not a checkpoint", "does not start with"),
    ];
    for (bytes, says) in cases {
        std::fs::write(&path, bytes).unwrap();
        let (code, stderr, untouched) = refused_resume(&out);
        assert_eq!(code, 2, "{stderr}");
        assert!(stderr.contains(says), "{says}: {stderr}");
        assert!(untouched, "{says}");
    }
    std::fs::remove_file(&path).unwrap();
    let (code, stderr, _) = refused_resume(&out);
    assert_eq!(code, 2);
    assert!(stderr.contains("there is no checkpoint"), "{stderr}");
}

/// The tangent run of `[sensitivity]` continues from `sensitivity-checkpoint.bin`, not from its
/// start: the sensitivity file's rows before the checkpoint are kept as they are on disk (a
/// byte changed in the first row survives the resume, where a tangent run redone from step 0
/// would rewrite it), and the Jacobians handed on before it are counted in the summary. A
/// damaged tangent checkpoint is refused with nothing changed.
#[test]
fn the_tangent_run_resumes_from_its_own_checkpoint() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("p.toml");
    let text =
        pendulum("midpoint", 4_000).replace("[output]", "[sensitivity]\ninitial = true\n[output]");
    std::fs::write(&file, text).unwrap();
    let out = tmp.path().join("out");
    assert!(spawn_run(&file, &out, "1000").wait().unwrap().success());
    let csv = out.join("sensitivity.csv");
    let mut bytes = std::fs::read(&csv).unwrap();
    let first_row = bytes.iter().position(|&b| b == b'\n').unwrap() + 1;
    // The leading digit of t = 0 in the first data row, turned into a 7.
    assert_eq!(bytes[first_row], b'0');
    bytes[first_row] = b'7';
    std::fs::write(&csv, &bytes).unwrap();
    let resumed = marsden_in(tmp.path(), &["resume", "out", "--no-progress"]);
    let said = String::from_utf8_lossy(&resumed.stdout);
    assert!(
        said.contains("then its tangent run ([sensitivity]) from step 4000"),
        "{said}"
    );
    assert!(
        resumed.status.success(),
        "{}",
        String::from_utf8_lossy(&resumed.stderr)
    );
    assert_eq!(
        std::fs::read(&csv).unwrap(),
        bytes,
        "the rows before the checkpoint kept"
    );
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"samples\": 41"), "{summary}");

    let path = out.join("sensitivity-checkpoint.bin");
    let good = std::fs::read(&path).unwrap();
    std::fs::write(&path, &good[..good.len() / 2]).unwrap();
    let (code, stderr, untouched) = refused_resume(&out);
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("sensitivity-checkpoint.bin is damaged"),
        "{stderr}"
    );
    assert!(untouched);
}

#[test]
fn a_checkpoint_interval_of_zero_is_refused_with_a_caret() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("p.toml");
    let text =
        pendulum("midpoint", 100).replace("plots = false", "plots = false\ncheckpoint_every = 0");
    std::fs::write(&file, text).unwrap();
    let r = marsden_in(tmp.path(), &["run", "p.toml"]);
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("checkpoint_every must be at least 1, got 0"),
        "{stderr}"
    );
    assert!(stderr.contains('^'), "{stderr}");
    let flag = marsden_in(tmp.path(), &["run", "p.toml", "--checkpoint-every", "0"]);
    assert_eq!(flag.status.code(), Some(2));
    assert!(!tmp.path().join("out").exists(), "nothing written");
}

#[test]
fn runs_that_cannot_be_checkpointed_yet_say_why() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            std::fs::read_to_string(crate::util::repo_root().join("examples/heavy_top.toml"))
                .unwrap(),
            "a rigid body",
        ),
        (
            std::fs::read_to_string(
                crate::util::repo_root().join("examples/exact_oscillator.toml"),
            )
            .unwrap(),
            "the method `exact`",
        ),
    ];
    for (text, says) in cases {
        let file = tmp.path().join("p.toml");
        std::fs::write(&file, text).unwrap();
        let r = marsden_in(
            tmp.path(),
            &["run", "p.toml", "--checkpoint-every", "10", "--out", "o"],
        );
        let stderr = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(says), "{says}: {stderr}");
        assert!(!tmp.path().join("o").exists(), "nothing written");
    }
}

/// A checkpoint written by this version (format 1), kept as a fixture: later versions must
/// still resume it. Its problem file was a temporary file, gone since, so the resume takes the
/// problem's text from the checkpoint; the result must equal a fresh run of that text.
#[test]
fn a_version_one_checkpoint_fixture_still_resumes() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("fixture");
    std::fs::create_dir(&out).unwrap();
    for name in ["checkpoint.bin", "trajectory.csv"] {
        std::fs::copy(fixture("resume").join(name), out.join(name)).unwrap();
    }
    let r = marsden_in(tmp.path(), &["resume", "fixture", "-q", "--no-progress"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let file = tmp.path().join("p.toml");
    std::fs::write(&file, pendulum("midpoint", 20_000)).unwrap();
    let whole = tmp.path().join("whole");
    assert!(spawn_run(&file, &whole, "5000").wait().unwrap().success());
    let csv = |d: &Path| std::fs::read(d.join("trajectory.csv")).unwrap();
    assert!(
        csv(&out) == csv(&whole),
        "the fixture's resumed trajectory differs"
    );
}

/// A forced run's checkpoint of format version 2 (its energy balance inside), kept as a fixture:
/// its resume — the trajectory cut back from step 20000 to the checkpoint's 15000, the last
/// 5000 steps run again — leaves the trajectory and the `summary.json` (balances included) of
/// a fresh run of the same text.
#[test]
fn a_version_two_checkpoint_fixture_of_a_forced_run_still_resumes() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("fixture");
    std::fs::create_dir(&out).unwrap();
    for name in ["checkpoint.bin", "trajectory.csv"] {
        std::fs::copy(fixture("resume-v2").join(name), out.join(name)).unwrap();
    }
    let r = marsden_in(tmp.path(), &["resume", "fixture", "-q", "--no-progress"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let file = tmp.path().join("p.toml");
    let damped = pendulum("midpoint", 20_000)
        .replace("[initial]", "forces = [\"-0.1*theta_dot\"]\n[initial]");
    std::fs::write(&file, damped).unwrap();
    let whole = tmp.path().join("whole");
    assert!(spawn_run(&file, &whole, "15000").wait().unwrap().success());
    let read = |d: &Path, name: &str| {
        contents(d)
            .into_iter()
            .find(|(n, _)| n == name)
            .map(|(_, bytes)| bytes)
    };
    for name in ["trajectory.csv", "summary.json"] {
        let resumed = read(&out, name).unwrap();
        let resumed = String::from_utf8_lossy(&resumed);
        let fresh = read(&whole, name).unwrap();
        let fresh = String::from_utf8_lossy(&fresh);
        // The fixture's problem file was elsewhere: the summaries name different paths.
        let strip = |s: &str| -> String {
            s.lines()
                .filter(|l| !l.contains("\"problem_file\"") && !l.contains("\"dir\""))
                .collect::<Vec<_>>()
                .join("\n")
        };
        assert!(
            strip(&resumed) == strip(&fresh),
            "the fixture's resumed {name} differs"
        );
    }
    assert!(
        String::from_utf8_lossy(&read(&out, "summary.json").unwrap()).contains("energy_balance")
    );
}

/// A run stopped by SIGTERM (a cluster's time limit) is checkpointed where it stopped: with
/// no periodic checkpoint before the signal (the only one is 100 steps before the end),
/// `marsden resume` continues from the stop and leaves the uninterrupted run's files byte for
/// byte, that last checkpoint included — for a run, and for the tangent run of `[sensitivity]`
/// (the signal sent once the run has ended and the tangent run goes).
#[test]
fn sigterm_checkpoints_where_the_run_stops_and_the_resume_equals_the_uninterrupted_run() {
    let steps = 3_000_000;
    let text = pendulum("midpoint", steps);
    sigterm_then_resume(&text, steps, "trajectory.csv", "checkpoint.bin");
    let (wait_for, written) = ("checkpoint.bin", "sensitivity-checkpoint.bin");
    sigterm_then_resume(PARAMETRIC, 400_000, wait_for, written);
}

/// Runs `text` whole, then three times stopped by SIGTERM a pseudo-random moment after
/// `wait_for` appears, each checked for the checkpoint `written` at the stop, resumed and
/// compared with the whole run.
fn sigterm_then_resume(text: &str, steps: u64, wait_for: &str, written: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("problem.toml");
    std::fs::write(&file, text).unwrap();
    let every = (steps - 100).to_string();
    let whole = tmp.path().join("whole");
    let clock = Instant::now();
    assert!(spawn_run(&file, &whole, &every).wait().unwrap().success());
    // The signal lands between a sixteenth and three sixteenths of the whole run's duration
    // (at most 100–300 ms) after `wait_for` appears: inside the run, or the tangent run.
    let limit = (clock.elapsed().as_millis() / 4).clamp(4, 400) as u64;
    let expected = contents(&whole);
    assert!(expected.iter().any(|(name, _)| name == "checkpoint.bin"));
    let mut interrupted = 0;
    for attempt in 0..3_u64 {
        let out = tmp.path().join(format!("term-{attempt}"));
        let mut child = spawn_run(&file, &out, &every);
        let clock = Instant::now();
        while !out.join(wait_for).exists() && clock.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(5));
        }
        std::thread::sleep(Duration::from_millis(limit / 4) + delay(100 + attempt, limit / 2));
        let signal = Command::new("kill")
            .args(["-TERM", &child.id().to_string()])
            .status()
            .unwrap();
        assert!(signal.success());
        match child.wait().unwrap().code() {
            Some(0) => continue, // finished before the signal
            code => assert_eq!(code, Some(1), "{wait_for}: attempt {attempt}"),
        }
        interrupted += 1;
        assert!(
            out.join(written).exists(),
            "{wait_for}: attempt {attempt}: no {written} written at the stop"
        );
        let resumed = marsden_in(
            tmp.path(),
            &["resume", out.to_str().unwrap(), "-q", "--no-progress"],
        );
        assert!(
            resumed.status.success(),
            "{}",
            String::from_utf8_lossy(&resumed.stderr)
        );
        let found = contents(&out);
        assert_eq!(found.len(), expected.len(), "{wait_for}: attempt {attempt}");
        for ((name, a), (_, b)) in expected.iter().zip(&found) {
            assert!(
                a == b,
                "{wait_for}: attempt {attempt}: {name} differs after SIGTERM and resume"
            );
        }
    }
    assert!(
        interrupted > 0,
        "{wait_for}: every signal came after the run had ended"
    );
}
