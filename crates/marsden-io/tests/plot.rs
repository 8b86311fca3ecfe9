//! Plot functions write decodable PNGs of the requested size, for ordinary and degenerate data,
//! using only the embedded font.

// Test helpers outside `#[test]` functions fail loudly too.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};

use marsden_io::plot::{FONT_FAMILY, plot_run};
use marsden_io::{
    Column, Error, PhaseCurve, PlotOptions, Series, Table, plot_constraint_residual,
    plot_energy_error, plot_momentum_drift, plot_phase_portrait,
};

/// Decodes a PNG fully and returns (width, height, RGB-ish bytes).
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes.len() > 5_000,
        "{} is only {} bytes",
        path.display(),
        bytes.len()
    );
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Asserts the image has the given size and is not blank (axes, text and lines drew).
fn check_png(path: &Path, w: u32, h: u32) {
    let (dw, dh, px) = decode(path);
    assert_eq!((dw, dh), (w, h));
    let dark = px.chunks(3).filter(|c| c.iter().all(|&v| v < 100)).count();
    assert!(dark > 2_000, "{}: only {dark} dark pixels", path.display());
}

/// Where images go: `MARSDEN_IO_PLOT_DIR` if set (to look at them), else a temp dir.
fn out_dir() -> (Option<tempfile::TempDir>, PathBuf) {
    match std::env::var_os("MARSDEN_IO_PLOT_DIR") {
        Some(d) => {
            std::fs::create_dir_all(&d).unwrap();
            (None, PathBuf::from(d))
        }
        None => {
            let t = tempfile::tempdir().unwrap();
            let p = t.path().to_path_buf();
            (Some(t), p)
        }
    }
}

/// A pendulum-like run: two coordinates, energy error ~1e-9 oscillating plus a spike,
/// a conserved momentum map at round-off level, and a positive constraint residual.
fn sample(n: usize) -> Table {
    let dt = 0.01;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * dt).collect();
    let qx: Vec<f64> = t.iter().map(|t| t.cos()).collect();
    let px: Vec<f64> = t.iter().map(|t| -t.sin()).collect();
    let qy: Vec<f64> = t.iter().map(|t| 0.5 * (2.0 * t).sin()).collect();
    let py: Vec<f64> = t.iter().map(|t| (2.0 * t).cos()).collect();
    let mut energy: Vec<f64> = t.iter().map(|t| 1.5 + 3e-9 * (7.0 * t).sin()).collect();
    energy[n / 2] += 4e-8;
    let j: Vec<f64> = (0..n)
        .map(|i| 2.0 + 1e-15 * ((i * 7919) % 13) as f64)
        .collect();
    let j2: Vec<f64> = (0..n)
        .map(|i| -1.0 + 1e-14 * (i as f64 / n as f64))
        .collect();
    let r: Vec<f64> = (0..n)
        .map(|i| {
            let f = i as f64 / n as f64;
            1e-14 * 10f64.powf(3.0 * f) * (1.0 + 0.5 * (i as f64 * 0.05).sin())
        })
        .collect();
    Table::new(vec![
        Column::new("t", t),
        Column::new("q_x", qx),
        Column::new("q_y", qy),
        Column::new("p_x", px),
        Column::new("p_y", py),
        Column::new("energy", energy),
        Column::new("J_rotation", j),
        Column::new("J_translation", j2),
        Column::new("constraint_residual", r),
    ])
    .unwrap()
}

#[test]
fn every_plot_of_a_run_is_a_png_of_the_right_size() {
    let (_keep, dir) = out_dir();
    let table = sample(5_000);
    let opts = PlotOptions::default();
    let reports = plot_run(&table, &dir, &opts).unwrap();
    let names: Vec<String> = reports
        .iter()
        .map(|r| r.path.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "phase_portrait.png",
            "time_series.png",
            "configuration.png",
            "energy_error.png",
            "momentum_drift.png",
            "constraint_residual.png"
        ]
    );
    for r in &reports {
        check_png(&r.path, opts.width, opts.height);
    }
    // 5000 > 4000 points: reduced, and the reports say so.
    assert!(
        reports[3].notes.iter().any(|n| n.contains("buckets")),
        "{:?}",
        reports[3].notes
    );
}

#[test]
fn long_runs_are_reduced_and_still_plot() {
    let (_keep, dir) = out_dir();
    let dir = dir.join("long");
    std::fs::create_dir_all(&dir).unwrap();
    let table = sample(400_000);
    let opts = PlotOptions {
        width: 800,
        height: 600,
        ..PlotOptions::default()
    };
    for r in plot_run(&table, &dir, &opts).unwrap() {
        check_png(&r.path, 800, 600);
    }
}

#[test]
fn degenerate_data_plots_with_notes_instead_of_failing() {
    let (_keep, dir) = out_dir();
    let dir = dir.join("degenerate");
    std::fs::create_dir_all(&dir).unwrap();
    let opts = PlotOptions::default();
    let t: Vec<f64> = (0..100).map(f64::from).collect();
    let nan = vec![f64::NAN; 100];
    let zeros = vec![0.0; 100];
    let mut spiky = vec![1.0; 100];
    spiky[10] = f64::NAN;
    spiky[20] = f64::INFINITY;

    let r = plot_energy_error(dir.join("empty.png"), &[], &[], &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("no finite data")),
        "{:?}",
        r.notes
    );
    let r = plot_energy_error(dir.join("all_nan.png"), &t, &nan, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("no finite data")),
        "{:?}",
        r.notes
    );
    let r = plot_energy_error(dir.join("constant.png"), &t, &vec![3.0; 100], &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("constant")),
        "{:?}",
        r.notes
    );
    let r = plot_energy_error(dir.join("zero_energy.png"), &t, &zeros, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("E₀ = 0")),
        "{:?}",
        r.notes
    );
    let r = plot_energy_error(dir.join("gaps.png"), &t, &spiky, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("2 non-finite")),
        "{:?}",
        r.notes
    );
    let r = plot_momentum_drift(dir.join("no_maps.png"), &t, &[], &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("no momentum maps")),
        "{:?}",
        r.notes
    );
    let exact = Series {
        name: "J_exact",
        values: &zeros,
    };
    let r = plot_momentum_drift(dir.join("exact.png"), &t, &[exact], &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("constant")),
        "{:?}",
        r.notes
    );
    let r = plot_constraint_residual(dir.join("zero_res.png"), &t, &zeros, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("constant")),
        "{:?}",
        r.notes
    );
    let mut some_zero: Vec<f64> = t.iter().map(|t| 1e-12 * (t + 1.0).powi(2)).collect();
    some_zero[5] = 0.0;
    let r = plot_constraint_residual(dir.join("log_zero.png"), &t, &some_zero, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("1 exact zero")),
        "{:?}",
        r.notes
    );
    let signed: Vec<f64> = t.iter().map(|t| 1e-12 * t.sin()).collect();
    plot_constraint_residual(dir.join("signed_res.png"), &t, &signed, &opts).unwrap();
    let r = plot_phase_portrait(dir.join("no_coords.png"), &[], &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("no coordinates")),
        "{:?}",
        r.notes
    );
    let point = PhaseCurve {
        name: "x",
        q: &[1.0],
        p: &[2.0],
    };
    plot_phase_portrait(dir.join("one_point.png"), &[point], &opts).unwrap();
    let extreme = [f64::MAX, f64::MIN, 1e-320, -0.0, 5e-324];
    let t5 = [0.0, 1.0, 2.0, 3.0, 4.0];
    let r = plot_energy_error(dir.join("extreme.png"), &t5, &extreme, &opts).unwrap();
    assert!(!r.notes.is_empty());
    plot_constraint_residual(
        dir.join("tiny.png"),
        &t5,
        &[5e-324, 1e-320, 0.0, 1e-310, 5e-324],
        &opts,
    )
    .unwrap();
    let huge_t = [1e300, 1e300, 1e300];
    plot_energy_error(dir.join("huge_t.png"), &huge_t, &[1.0, 2.0, 3.0], &opts).unwrap();

    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let (w, h, _) = decode(&path);
        assert_eq!((w, h), (opts.width, opts.height), "{}", path.display());
    }
}

#[test]
fn smallest_images_with_many_notes_still_render() {
    let dir = tempfile::tempdir().unwrap();
    let opts = PlotOptions {
        width: 200,
        height: 200,
        ..PlotOptions::default()
    };
    let t: Vec<f64> = (0..10_000).map(f64::from).collect();
    let mut v: Vec<f64> = t.iter().map(|t| t.sin()).collect();
    v[5] = f64::NAN;
    let names: Vec<String> = (0..10).map(|i| format!("J_{i}")).collect();
    let maps: Vec<Series<'_>> = names
        .iter()
        .map(|n| Series {
            name: n,
            values: &v,
        })
        .collect();
    let r = plot_momentum_drift(dir.path().join("m.png"), &t, &maps, &opts).unwrap();
    // One per series, the bucketing, and the legend capped at 8 of the 10 maps.
    assert_eq!(r.notes.len(), 12, "{:?}", r.notes);
    assert_eq!(
        r.notes.last().map(String::as_str),
        Some("the legend names the first 8 of 10 curves")
    );
    assert_eq!(decode(&r.path).0, 200);
    let curves: Vec<PhaseCurve<'_>> = names
        .iter()
        .map(|n| PhaseCurve {
            name: n,
            q: &v,
            p: &t,
        })
        .collect();
    let r = plot_phase_portrait(dir.path().join("p.png"), &curves, &opts).unwrap();
    assert!(
        r.notes.iter().any(|n| n.contains("first 4 of 10")),
        "{:?}",
        r.notes
    );
}

#[test]
fn bad_input_is_a_typed_error() {
    let dir = tempfile::tempdir().unwrap();
    let opts = PlotOptions::default();
    let e = plot_energy_error(dir.path().join("e.png"), &[0.0, 1.0], &[1.0], &opts).unwrap_err();
    assert!(matches!(e, Error::PlotInput { .. }));
    assert!(
        e.to_string().contains("e.png") && e.to_string().contains("`energy` has 1"),
        "{e}"
    );
    let tiny = PlotOptions {
        width: 10,
        ..PlotOptions::default()
    };
    let e = plot_energy_error(dir.path().join("s.png"), &[0.0], &[1.0], &tiny).unwrap_err();
    assert!(matches!(e, Error::PlotInput { .. }), "{e}");
    let curve = PhaseCurve {
        name: "x",
        q: &[1.0, 2.0],
        p: &[1.0],
    };
    assert!(plot_phase_portrait(dir.path().join("p.png"), &[curve], &opts).is_err());
    // Unwritable destination: an I/O error naming the path.
    let e =
        plot_energy_error(dir.path().join("missing/dir/e.png"), &[0.0], &[1.0], &opts).unwrap_err();
    assert!(
        matches!(e, Error::Io { .. }) && e.to_string().contains("missing/dir/e.png"),
        "{e}"
    );
    let no_t = Table::new(vec![Column::new("energy", vec![1.0])]).unwrap();
    assert!(matches!(
        plot_run(&no_t, dir.path(), &opts),
        Err(Error::PlotInput { .. })
    ));
}

/// The font family plots use is ours, not a system family name, so a working plot proves the
/// embedded font was used (plotters is built without system-font lookup).
#[test]
fn only_the_embedded_font_family_is_used() {
    assert!(!["sans-serif", "serif", "monospace", "DejaVu Sans"].contains(&FONT_FAMILY));
}

/// Renders in a child process whose environment is empty (no HOME, no fontconfig, no
/// XDG dirs): plots must not need anything from the machine.
#[test]
fn plots_render_with_an_empty_environment() {
    if std::env::var_os("MARSDEN_IO_CHILD").is_some() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "child_renders_a_plot",
            "--ignored",
            "--nocapture",
        ])
        .env_clear()
        .env("MARSDEN_IO_CHILD_DIR", dir.path())
        .env("FONTCONFIG_FILE", "/nonexistent")
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{log}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(log.contains("1 passed"), "{log}");
    check_png(&dir.path().join("child.png"), 600, 400);
}

#[test]
#[ignore = "run by plots_render_with_an_empty_environment in a clean child process"]
fn child_renders_a_plot() {
    assert!(std::env::var_os("HOME").is_none());
    let dir = PathBuf::from(std::env::var_os("MARSDEN_IO_CHILD_DIR").unwrap());
    let t: Vec<f64> = (0..50).map(f64::from).collect();
    let e: Vec<f64> = t.iter().map(|t| 1.0 + 1e-10 * t.sin()).collect();
    let opts = PlotOptions {
        width: 600,
        height: 400,
        ..PlotOptions::default()
    };
    plot_energy_error(dir.join("child.png"), &t, &e, &opts).unwrap();
}

/// A trajectory spanning 0 … 1.7e308 (a free particle with an absurd step) draws in bounded
/// time: axes whose span overflows are not handed to the drawing library.
#[test]
fn huge_ranges_draw_in_bounded_time() {
    let (_keep, dir) = out_dir();
    let start = std::time::Instant::now();
    for (t, q) in [
        ([0.0, 1.7e158], [0.0, 1.7e308]),
        ([0.0, 1.7e308], [-1.7e308, 1.7e308]),
    ] {
        let table = Table::new(vec![
            Column::new("t", t.to_vec()),
            Column::new("q_x", q.to_vec()),
            Column::new("p_x", vec![1e150, 1e150]),
            Column::new("energy", vec![5e299, 5e299]),
        ])
        .unwrap();
        let reports = plot_run(&table, &dir, &PlotOptions::default()).unwrap();
        let notes: Vec<&String> = reports.iter().flat_map(|r| &r.notes).collect();
        assert!(
            notes.iter().any(|n| n.contains("too large to draw")),
            "{notes:?}"
        );
    }
    assert!(start.elapsed().as_secs() < 20, "{:?}", start.elapsed());
}

fn names_of(reports: &[marsden_io::PlotReport]) -> Vec<String> {
    reports
        .iter()
        .map(|r| r.path.file_name().unwrap().to_string_lossy().into_owned())
        .collect()
}

/// N-body orbits are drawn in the plane where the bodies spread (here x–y; z ≡ 0), and a
/// coordinate that never moves (z₁ ≡ 0) gets no phase-portrait panel: it is named in a note.
#[test]
fn nbody_orbits_in_their_plane_and_constant_coordinates_skipped() {
    let (_keep, dir) = out_dir();
    let dir = dir.join("nbody");
    std::fs::create_dir_all(&dir).unwrap();
    let n = 500;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.02).collect();
    let mut cols = vec![Column::new("t", t.clone())];
    for (k, r) in [(1, 1.0), (2, 2.5)] {
        let w = 1.0 / r;
        cols.push(Column::new(
            format!("q_x{k}"),
            t.iter().map(|t| r * (w * t).cos()).collect(),
        ));
        cols.push(Column::new(
            format!("q_y{k}"),
            t.iter().map(|t| r * (w * t).sin()).collect(),
        ));
        cols.push(Column::new(format!("q_z{k}"), vec![0.0; n]));
        cols.push(Column::new(
            format!("p_x{k}"),
            t.iter().map(|t| -(w * t).sin()).collect(),
        ));
        cols.push(Column::new(
            format!("p_y{k}"),
            t.iter().map(|t| (w * t).cos()).collect(),
        ));
        cols.push(Column::new(format!("p_z{k}"), vec![0.0; n]));
    }
    let table = Table::new(cols).unwrap();
    let reports = plot_run(&table, &dir, &PlotOptions::default()).unwrap();
    assert!(names_of(&reports).contains(&"configuration.png".to_owned()));
    let phase = &reports[0];
    assert!(
        phase
            .notes
            .iter()
            .any(|n| n.contains("constant throughout: z1, z2")),
        "{:?}",
        phase.notes
    );
    for r in &reports {
        check_png(&r.path, 1200, 800);
    }
}

/// A pendulum going over the top: θ grows by 2π per turn; declared an angle, it is drawn in
/// (−π, π] (the axis says "mod 2π") and the plots still render.
#[test]
fn declared_angles_are_wrapped() {
    let (_keep, dir) = out_dir();
    let dir = dir.join("angles");
    std::fs::create_dir_all(&dir).unwrap();
    let n = 2000;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 0.01).collect();
    let theta: Vec<f64> = t.iter().map(|t| -3.0 * t).collect();
    let table = Table::new(vec![
        Column::new("t", t),
        Column::new("q_theta", theta),
        Column::new("p_theta", vec![-3.0; n]),
        Column::new("energy", vec![4.5; n]),
    ])
    .unwrap();
    let opts = PlotOptions {
        angles: vec!["theta".to_owned()],
        ..PlotOptions::default()
    };
    let reports = plot_run(&table, &dir, &opts).unwrap();
    assert_eq!(
        names_of(&reports),
        ["phase_portrait.png", "time_series.png", "energy_error.png"]
    );
    for r in &reports {
        check_png(&r.path, 1200, 800);
    }
    assert!(opts.is_angle("q_theta") && !opts.is_angle("p_theta"));
}

/// A long run read back through the bounded sketch keeps its energy spike, and the plots say
/// from how many rows they were drawn.
#[test]
fn long_runs_are_read_back_through_a_bounded_sketch() {
    let (_keep, dir) = out_dir();
    let dir = dir.join("sketch");
    std::fs::create_dir_all(&dir).unwrap();
    let table = sample(300_000);
    let csv = dir.join("trajectory.csv");
    marsden_io::write_csv(&csv, &table).unwrap();
    let sketch = marsden_io::read_csv_thinned(&csv, &["energy", "J_rotation"], 1 << 20).unwrap();
    assert_eq!(sketch.rows_read, 300_000);
    assert!(sketch.table.n_rows() < 30_000, "{}", sketch.table.n_rows());
    let e = sketch.table.values("energy").unwrap();
    let full = table.values("energy").unwrap();
    let max = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!(max(e), max(full), "the spike survives");
    let opts = PlotOptions {
        note: sketch.note(),
        ..PlotOptions::default()
    };
    let reports = plot_run(&sketch.table, &dir, &opts).unwrap();
    assert!(
        reports
            .iter()
            .all(|r| r.notes.iter().any(|n| n.contains("of 300000 rows")))
    );
}
