//! Output directories that are safe: a sanitised default name, a lock against a second run,
//! a summary that is whole or absent.

use std::path::PathBuf;

use marsden_spec::output;
use marsden_spec::{Controls, ErrorKind, Overrides, RunSpec, Store, execute, from_toml_str};

fn named(name: &str) -> String {
    format!(
        "[system]\nname = {name:?}\ncoordinates = [\"x\"]\nlagrangian = \"0.5*x_dot^2\"\n\
         [initial]\nq = [0]\nv = [1]\n[integrator]\nh = 0.1\nsteps = 3\n[output]\nplots = false\n"
    )
}

#[test]
fn name_cannot_steer_the_default_directory_out_of_out() {
    for (name, dir) in [
        ("../escaped", "out/.._escaped"),
        ("..", "out/run"),
        (".", "out/run"),
        ("/etc/x", "out/_etc_x"),
        ("pendulum", "out/pendulum"),
    ] {
        let spec = RunSpec::from_toml_str(&named(name), "p.toml").unwrap();
        assert_eq!(spec.output.dir, PathBuf::from(dir), "{name}");
    }
}

#[test]
fn second_run_into_a_locked_directory_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let overrides = Overrides {
        out: Some(dir.path().to_owned()),
        ..Overrides::default()
    };
    let spec = from_toml_str(&named("a"), "p.toml", &overrides).unwrap();
    let held = output::lock(dir.path()).unwrap();
    let err = execute(&spec, Store::Files, &Controls::none()).unwrap_err();
    assert_eq!(err.kind, ErrorKind::BadInput);
    assert!(err.to_string().contains("another run is writing"), "{err}");
    assert!(!dir.path().join(output::SUMMARY_JSON).exists());
    drop(held);
    let outcome = execute(&spec, Store::Files, &Controls::none()).unwrap();
    assert_eq!(outcome.summary.output.rows, 4);
    // The lock is gone after the run, and no temporary summary is left.
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, [output::SUMMARY_JSON, output::TRAJECTORY_CSV]);
}

/// A sweep locks its own files: the same sweep into a locked directory is refused and writes
/// nothing; another shard of it may write beside it.
#[test]
fn a_sweep_into_a_locked_directory_is_refused() {
    use marsden_spec::sweep::Shard;
    use marsden_spec::sweep::{self, SweepOptions};
    let dir = tempfile::tempdir().unwrap();
    let overrides = Overrides {
        out: Some(dir.path().to_owned()),
        ..Overrides::default()
    };
    let text = named("s") + "[sweep]\ninitial = \"v[0]\"\nvalues = [1.0, 2.0]\n";
    let spec = from_toml_str(&text, "p.toml", &overrides).unwrap();
    let sweep_spec = spec.sweep.clone().unwrap();
    let held = output::lock_named(dir.path(), ".marsden.lock").unwrap();
    let whole = SweepOptions::default();
    let err = sweep::execute(&spec, &sweep_spec, &overrides, &whole).unwrap_err();
    assert_eq!(err.kind, ErrorKind::BadInput);
    assert!(err.to_string().contains("another run is writing"), "{err}");
    assert!(!dir.path().join("sweep.csv").exists());
    let shard = SweepOptions {
        shard: Shard { index: 1, count: 2 },
        ..SweepOptions::default()
    };
    let outcome = sweep::execute(&spec, &sweep_spec, &overrides, &shard).unwrap();
    assert_eq!(outcome.members_run, 1);
    drop(held);
    let outcome = sweep::execute(&spec, &sweep_spec, &overrides, &whole).unwrap();
    assert_eq!(outcome.members_run, 2);
    assert!(!dir.path().join(".marsden.lock").exists());
}
