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

/// `marsden plot DIR` draws again every picture `marsden run` drew: for a run with events and
/// observables (the Poincaré section and the observables, also from `.npy`), a rigid body (its
/// attitude and body momentum) and a multibody system (`bodies.png`) — each deleted, then
/// redrawn byte for byte (the same data through the same plotting code) and listed.
#[test]
fn plot_redraws_every_picture_the_run_drew() {
    let root = crate::util::repo_root().join("examples");
    let cases = [
        ("henon_heiles_section.toml", "csv", 20_000),
        ("henon_heiles_section.toml", "npy", 20_000),
        ("free_rigid_body.toml", "csv", 500),
        ("spring_dumbbell.toml", "csv", 500),
    ];
    for (example, format, steps) in cases {
        let tmp = tempfile::tempdir().unwrap();
        let text = std::fs::read_to_string(root.join(example)).unwrap();
        let text = match format {
            "npy" => text.replace("[output]", "[output]\nformat = \"npy\""),
            _ => text,
        };
        let file = tmp.path().join(example);
        std::fs::write(&file, text).unwrap();
        let steps = steps.to_string();
        let out = tmp.path().join("out");
        let run = marsden_in(
            tmp.path(),
            &[
                "run",
                file.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--steps",
                &steps,
            ],
        );
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let drawn = pngs(&out);
        let before: Vec<Vec<u8>> = drawn
            .iter()
            .map(|n| std::fs::read(out.join(n)).unwrap())
            .collect();
        for name in &drawn {
            std::fs::remove_file(out.join(name)).unwrap();
        }
        let plot = marsden_in(tmp.path(), &["plot", out.to_str().unwrap()]);
        let stdout = String::from_utf8_lossy(&plot.stdout);
        assert!(
            plot.status.success(),
            "{}",
            String::from_utf8_lossy(&plot.stderr)
        );
        assert_eq!(pngs(&out), drawn, "{example} ({format}): {stdout}");
        for (name, bytes) in drawn.iter().zip(&before) {
            assert!(
                stdout.contains(name.as_str()),
                "{name} not listed: {stdout}"
            );
            assert_eq!(
                &std::fs::read(out.join(name)).unwrap(),
                bytes,
                "{example}: {name}"
            );
        }
    }
}
