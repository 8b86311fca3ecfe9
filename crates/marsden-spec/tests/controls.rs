//! The caller's hold on a run: the progress callback (every 256 steps, then once when done)
//! and the stop flag (the run ends within 256 steps, its samples and summary kept).

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use marsden_spec::sweep::{self, NOT_RUN, SweepOptions};
use marsden_spec::{Controls, Progress, RunStatus, Store, execute};

use crate::load_example;

#[test]
fn progress_is_reported_every_256_steps_and_at_the_end() {
    let dir = tempfile::tempdir().unwrap();
    let spec = load_example("harmonic_oscillator.toml", dir.path(), Some(1000));
    let seen = RefCell::new(Vec::new());
    let record = |p: Progress| seen.borrow_mut().push((p.step, p.total, p.done));
    let controls = Controls {
        progress: Some(&record),
        stop: None,
    };
    let outcome = execute(&spec, Store::Memory, &controls).unwrap();
    assert_eq!(outcome.summary.status, RunStatus::Completed);
    assert_eq!(
        seen.into_inner(),
        [
            (256, 1000, false),
            (512, 1000, false),
            (768, 1000, false),
            (1000, 1000, true)
        ]
    );
}

#[test]
fn a_stopped_run_keeps_its_samples_and_says_interrupted() {
    let dir = tempfile::tempdir().unwrap();
    let spec = load_example("harmonic_oscillator.toml", dir.path(), Some(100_000));
    let stop = Arc::new(AtomicBool::new(false));
    let request = |p: Progress| {
        if p.step >= 512 {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let controls = Controls {
        progress: Some(&request),
        stop: Some(stop.clone()),
    };
    let outcome = execute(&spec, Store::FilesAndMemory, &controls).unwrap();
    let s = &outcome.summary;
    assert_eq!(s.status, RunStatus::Interrupted);
    assert_eq!(s.error, None);
    assert_eq!(s.steps, 512);
    let samples = outcome.samples.unwrap();
    assert_eq!(samples.t.last(), Some(&s.t_final), "the last state is kept");
    let text = std::fs::read_to_string(dir.path().join("summary.json")).unwrap();
    assert!(text.contains("\"status\": \"interrupted\""), "{text}");
}

#[test]
fn a_stopped_sweep_runs_no_more_members() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../marsden-cli/tests/fixtures/pendulum_sweep.toml");
    let overrides = marsden_spec::Overrides {
        out: Some(dir.path().to_owned()),
        ..Default::default()
    };
    let spec = marsden_spec::load(&fixture, &overrides).unwrap();
    let sweep = spec.sweep.clone().unwrap();
    let options = SweepOptions {
        stop: Some(Arc::new(AtomicBool::new(true))),
        ..SweepOptions::default()
    };
    let rows = sweep::run_members(&spec, &sweep, &overrides, &options).unwrap();
    assert!(rows.iter().all(|r| r.status == RunStatus::Interrupted));
    assert!(rows.iter().all(|r| r.error.as_deref() == Some(NOT_RUN)));
}
