//! Plots drawn by `marsden run` and `marsden plot`: which pictures a run gets, angles wrapped
//! and recorded, and inputs that once made the plotting loop for ever.

use std::time::{Duration, Instant};

use crate::util::{assert_rejected, fixture, marsden_in, run_ok};

fn pngs(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            name.ends_with(".png").then_some(name)
        })
        .collect();
    names.sort();
    names
}

/// Kepler's problem (coordinates x, y) gets its orbit drawn in the plane, beside the phase
/// portrait and the time series.
#[test]
fn a_planar_orbit_gets_a_configuration_plot() {
    let run = run_ok("kepler_symmetry.toml", &[]);
    let names = pngs(&run.out);
    for png in ["configuration.png", "time_series.png", "phase_portrait.png"] {
        assert!(names.contains(&png.to_owned()), "{names:?}");
    }
}

/// `angles = ["theta"]` is recorded in summary.json (so `marsden plot` wraps it too), and a
/// name that is not a coordinate is refused with a suggestion.
#[test]
fn declared_angles_are_checked_and_recorded() {
    let run = run_ok("pendulum_over_the_top.toml", &[]);
    let s = run.summary();
    assert_eq!(s["output"]["angles"][0], "theta");
    assert!(pngs(&run.out).contains(&"time_series.png".to_owned()));
    std::fs::remove_file(run.out.join("time_series.png")).unwrap();
    let out = marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    assert!(run.out.join("time_series.png").is_file());
    assert_rejected(
        "angles_unknown.toml",
        &[
            "`thetta` in `angles` is not a coordinate",
            "did you mean `theta`?",
        ],
    );
}

/// A trajectory spanning 0 … 1.7e308 once made the plotting search for axis ticks for ever.
#[test]
fn a_trajectory_near_the_largest_float_plots_in_bounded_time() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_marsden"))
        .args(["run", fixture("plot_huge_range.toml").to_str().unwrap()])
        .args(["--out", out.to_str().unwrap()])
        .current_dir(tmp.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("still plotting after 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success(), "{status}");
    assert!(out.join("summary.json").is_file());
}

/// `marsden plot` on a sweep's directory draws the sweep plot (it once failed with "a table
/// needs at least one column").
#[test]
fn plot_on_a_sweep_folder_draws_the_sweep() {
    let run = run_ok("pendulum_sweep.toml", &[]);
    assert!(run.out.join("sweep.csv").is_file());
    let out = marsden_in(run.tmp.path(), &["plot", run.out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(run.out.join("sweep.png").is_file());
}
