//! A sweep with checkpoints, killed with SIGKILL at pseudo-random moments and resumed with
//! `marsden resume`, leaves the table and summary of the uninterrupted sweep byte for byte: the
//! members in the table at the checkpoint are kept, the others rerun. Its members are forced
//! runs, which cannot be checkpointed one by one: a sweep checkpoints whole members.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::resume::{contents, delay};
use crate::util::marsden_in;

/// Twelve damped pendulums, each long enough for a kill to land while members run.
const SWEEP: &str = "[system]\nbuiltin = \"pendulum\"\nforces = [\"-0.05*theta_dot\"]\n\
    [initial]\nq = [1.0]\nv = [0.0]\n\
    [integrator]\nmethod = \"midpoint\"\nh = 0.01\nsteps = 400000\n\
    [output]\nplots = false\ncheckpoint_every = 1\n\
    [sweep]\ninitial = \"q[0]\"\nrange = { start = 0.2, stop = 2.4, count = 12 }\n";

/// `marsden <args…> -q --no-progress --threads 2` as a child process.
fn spawn(args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_marsden"))
        .args(args)
        .args(["-q", "--no-progress", "--threads", "2"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap()
}

#[test]
fn a_killed_sweep_resumes_to_the_uninterrupted_sweep_byte_for_byte() {
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("sweep.toml");
    std::fs::write(&file, SWEEP).unwrap();
    let run = |out: &Path| {
        spawn(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ])
    };
    let whole = tmp.path().join("whole");
    assert!(run(&whole).wait().unwrap().success());
    let expected = contents(&whole);
    let names: Vec<&str> = expected.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["summary.json", "sweep-checkpoint.bin", "sweep.csv"]);
    let mut killed_running = 0;
    for attempt in 0..3u64 {
        let out = tmp.path().join(format!("killed-{attempt}"));
        let mut child = run(&out);
        let clock = Instant::now();
        while !out.join("sweep-checkpoint.bin").exists() && clock.elapsed().as_secs() < 60 {
            std::thread::sleep(Duration::from_millis(5));
        }
        std::thread::sleep(delay(100 + attempt, 600));
        killed_running += usize::from(child.try_wait().unwrap().is_none());
        let _ = child.kill();
        let _ = child.wait();
        let resumed = marsden_in(tmp.path(), &["resume", out.to_str().unwrap(), "-q"]);
        let stderr = String::from_utf8_lossy(&resumed.stderr);
        assert!(resumed.status.success(), "{stderr}");
        let found = contents(&out);
        assert_eq!(found.len(), expected.len(), "attempt {attempt}");
        for ((name, a), (_, b)) in expected.iter().zip(&found) {
            assert!(a == b, "{name} differs after kill {attempt} and resume");
        }
    }
    assert!(
        killed_running > 0,
        "every kill came after the sweep had ended"
    );
}

/// Two shards run into one directory: `marsden resume DIR` cannot tell which to resume and
/// says so; `--shard` picks one, whose table is then rewritten to the same bytes.
#[test]
fn shards_in_one_directory_are_resumed_one_by_one() {
    let tmp = tempfile::tempdir().unwrap();
    let text = SWEEP.replace("steps = 400000", "steps = 200");
    std::fs::write(tmp.path().join("s.toml"), text).unwrap();
    for shard in ["0/2", "1/2"] {
        let r = marsden_in(
            tmp.path(),
            &["run", "s.toml", "--out", "o", "--shard", shard, "-q"],
        );
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    }
    let table = tmp.path().join("o/sweep.shard-1-of-2.csv");
    let before = std::fs::read(&table).unwrap();
    let r = marsden_in(tmp.path(), &["resume", "o"]);
    let stderr = String::from_utf8_lossy(&r.stderr);
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("several shards"), "{stderr}");
    assert!(
        stderr.contains("sweep-checkpoint.shard-0-of-2.bin"),
        "{stderr}"
    );
    assert!(stderr.contains("--shard i/n"), "{stderr}");
    let r = marsden_in(tmp.path(), &["resume", "o", "--shard", "1/2", "-q"]);
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    assert_eq!(std::fs::read(&table).unwrap(), before);
}
