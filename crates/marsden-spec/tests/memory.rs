//! Runs in memory, to files, and both: the same samples bit for bit, the same summaries.

use marsden_io::read_csv;
use marsden_spec::sweep::{self, SweepOptions};
use marsden_spec::{Controls, RunStatus, Samples, Store, execute};

use crate::load_example;

/// The columns of the trajectory file as the in-memory samples have them.
fn file_columns(samples: &Samples) -> Vec<(String, Vec<f64>)> {
    let named = |prefix: &str, columns: &[Vec<f64>]| {
        samples
            .coordinates
            .iter()
            .zip(columns)
            .map(|(c, v)| (format!("{prefix}_{c}"), v.clone()))
            .collect::<Vec<_>>()
    };
    let mut out = vec![("t".to_owned(), samples.t.clone())];
    out.extend(named("q", &samples.q));
    out.extend(named("p", &samples.p));
    out.push(("energy".to_owned(), samples.energy.clone()));
    for (name, j) in &samples.momenta {
        out.push((format!("J_{name}"), j.clone()));
    }
    if let Some(r) = &samples.constraint_residual {
        out.push(("constraint_residual".to_owned(), r.clone()));
    }
    for (i, lambda) in samples.lambda.iter().enumerate() {
        out.push((format!("lambda_{i}"), lambda.clone()));
    }
    if let Some(r) = &samples.constraint_velocity_residual {
        out.push(("constraint_velocity_residual".to_owned(), r.clone()));
    }
    out
}

#[test]
fn samples_in_memory_are_the_rows_of_the_file() {
    for name in [
        "cartesian_pendulum.toml",
        "kepler.toml",
        "double_pendulum.toml",
    ] {
        let dir = tempfile::tempdir().unwrap();
        let spec = load_example(name, dir.path(), Some(300));
        let both = execute(&spec, Store::FilesAndMemory, &Controls::none()).unwrap();
        let samples = both.samples.clone().unwrap();
        let table = read_csv(dir.path().join("trajectory.csv")).unwrap();
        let columns = file_columns(&samples);
        assert_eq!(table.names().count(), columns.len(), "{name}");
        for (column, values) in &columns {
            let written = table.values(column).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(written), bits(values), "{name}: {column}");
        }
        assert_eq!(samples.len() as u64, both.summary.output.rows, "{name}");
        assert!(samples.v.iter().all(|v| v.len() == samples.len()), "{name}");

        let memory = execute(&spec, Store::Memory, &Controls::none()).unwrap();
        assert_eq!(memory.samples.as_ref(), Some(&samples), "{name}");
        assert!(memory.dir.is_none() && memory.summary.output.files.is_empty());
        assert_eq!(memory.summary.output.format, "memory");
        assert_eq!(memory.summary.final_state.q, both.summary.final_state.q);
        assert_eq!(memory.summary.status, RunStatus::Completed);
    }
}

#[test]
fn memory_runs_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never");
    let spec = load_example("pendulum.toml", &out, Some(50));
    let outcome = execute(&spec, Store::Memory, &Controls::none()).unwrap();
    assert!(!out.exists());
    assert_eq!(
        outcome.samples.unwrap().len(),
        6,
        "every 10th of 50 steps, and the first"
    );
}

#[test]
fn velocities_follow_from_the_momenta() {
    let dir = tempfile::tempdir().unwrap();
    let spec = load_example("harmonic_oscillator.toml", dir.path(), Some(20));
    let samples = execute(&spec, Store::Memory, &Controls::none())
        .unwrap()
        .samples
        .unwrap();
    // L = ½ m v² − ½ k x², so v = p / m; the example has m = 1.
    for (v, p) in samples.v[0].iter().zip(&samples.p[0]) {
        assert!((v - p).abs() <= 1e-12 * p.abs().max(1.0), "{v} vs {p}");
    }
}

#[test]
fn sweep_members_run_without_writing() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../marsden-cli/tests/fixtures/pendulum_sweep.toml");
    let overrides = marsden_spec::Overrides {
        out: Some(dir.path().join("sweep")),
        ..Default::default()
    };
    let spec = marsden_spec::load(&fixture, &overrides).unwrap();
    let sweep = spec.sweep.clone().unwrap();
    let rows = sweep::run_members(&spec, &sweep, &overrides, &SweepOptions::default()).unwrap();
    assert_eq!(rows.len(), sweep.count());
    assert!(rows.iter().all(|r| r.status == RunStatus::Completed));
    assert!(!dir.path().join("sweep").exists());
}

/// Each member's in-memory outcome equals its row of `run_members` and the same member run
/// alone (bit for bit), whatever the number of threads.
#[test]
fn sweep_member_outcomes_match_the_rows_and_single_runs() {
    let fixture = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../marsden-cli/tests/fixtures/pendulum_sweep.toml");
    let overrides = marsden_spec::Overrides::default();
    let spec = marsden_spec::load(&fixture, &overrides).unwrap();
    let sweep = spec.sweep.clone().unwrap();
    let rows = sweep::run_members(&spec, &sweep, &overrides, &SweepOptions::default()).unwrap();
    let one_thread = SweepOptions {
        threads: Some(1),
        ..SweepOptions::default()
    };
    let outcomes = sweep::member_outcomes(&spec, &sweep, &overrides, &one_thread).unwrap();
    assert_eq!(outcomes.len(), rows.len());
    for (k, (outcome, row)) in outcomes.iter().zip(&rows).enumerate() {
        let outcome = outcome.as_ref().unwrap().as_ref().unwrap();
        let fin = &outcome.summary.final_state;
        assert_eq!(row.t_final.to_bits(), fin.t.to_bits(), "member {k}");
        assert_eq!(
            row.energy_max_rel_error,
            outcome.summary.energy.max_rel_error
        );
        let samples = outcome.samples.as_ref().unwrap();
        assert_eq!(samples.q[0].last().copied(), fin.q.first().copied());
        let alone =
            sweep::member_outcome(&spec, &overrides, k, &marsden_spec::Controls::none()).unwrap();
        assert_eq!(alone.samples.as_ref().unwrap(), samples, "member {k}");
    }
}
