//! The tangent run of `[sensitivity]` under the caller's controls: the progress callback every
//! 256 steps and once at the end, and the stop flag, which ends the tangent run with the
//! Jacobians of the steps taken (R1: the Cayley matrix to the power of those steps).

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use marsden_spec::prepare;
use marsden_spec::sensitivity::compute_with;
use marsden_spec::{Controls, Progress, RunSpec};

use super::{OSCILLATOR, product};

#[test]
fn r1_stop_flag_set_from_the_progress_callback_ends_the_tangent_run_at_512_steps() {
    let text = OSCILLATOR.replace("steps = 200", "steps = 2000");
    let spec = RunSpec::from_toml_str(&text, "sensitivity.toml").unwrap_or_else(|d| panic!("{d}"));
    let start = prepare(&spec).unwrap_or_else(|d| panic!("{d}"));
    let asked = spec.sensitivity.as_ref().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let seen = RefCell::new(Vec::new());
    let request = |p: Progress| {
        seen.borrow_mut().push((p.step, p.total, p.done));
        if p.step >= 512 {
            stop.store(true, Ordering::Relaxed);
        }
    };
    let controls = Controls {
        progress: Some(&request),
        stop: Some(stop.clone()),
    };
    let found = compute_with(
        marsden_spec::engine_for(&spec).as_ref(),
        &spec,
        asked,
        &start,
        &controls,
    )
    .unwrap();
    assert_eq!(
        seen.into_inner(),
        [(256, 2000, false), (512, 2000, false), (512, 2000, true)]
    );
    let error = found.summary.error.as_deref().unwrap_or_default();
    assert!(error.contains("stopped after 512 of 2000 steps"), "{error}");
    assert_eq!(found.samples.len(), 513);
    let (t_last, _) = found.samples[512];
    assert!((t_last - 51.2).abs() < 1e-12, "last sample at t = {t_last}");
    let step = [
        [399.0 / 401.0, 40.0 / 401.0],
        [-40.0 / 401.0, 399.0 / 401.0],
    ];
    let mut want = [[1.0, 0.0], [0.0, 1.0]];
    for _ in 0..512 {
        want = product(&step, &want);
    }
    let got = &found.summary.final_jacobian;
    for i in 0..2 {
        for j in 0..2 {
            let error = (got[i][j] - want[i][j]).abs();
            assert!(
                error <= 1e-12,
                "entry ({i}, {j}): {} vs {}",
                got[i][j],
                want[i][j]
            );
        }
    }
}

/// The Jacobians are handed on as the tangent run reaches them, not kept: every stored step
/// reaches the sink once, in order of time, and the result holds none of them (a run of 10⁶
/// stored steps kept 366 MB before). The streamed values are those `compute_with` keeps, bit for
/// bit; a files-only run writes them and keeps nothing in memory.
#[test]
fn r1_jacobians_are_streamed_to_the_sink_not_kept() {
    use marsden_spec::sensitivity::compute_streamed;
    let spec =
        RunSpec::from_toml_str(OSCILLATOR, "sensitivity.toml").unwrap_or_else(|d| panic!("{d}"));
    let start = prepare(&spec).unwrap_or_else(|d| panic!("{d}"));
    let asked = spec.sensitivity.as_ref().unwrap();
    let mut streamed = Vec::new();
    let mut sink = |t: f64, jacobian: &[f64]| streamed.push((t, jacobian.to_vec()));
    let found = compute_streamed(
        marsden_spec::engine_for(&spec).as_ref(),
        &spec,
        asked,
        &start,
        &Controls::none(),
        &mut sink,
    )
    .unwrap();
    assert!(
        found.samples.is_empty(),
        "kept {} samples",
        found.samples.len()
    );
    let kept = compute_with(
        marsden_spec::engine_for(&spec).as_ref(),
        &spec,
        asked,
        &start,
        &Controls::none(),
    )
    .unwrap();
    assert_eq!(found.summary.samples, kept.samples.len());
    assert_eq!(streamed, kept.samples);
    assert!(streamed.windows(2).all(|w| w[0].0 < w[1].0));

    let dir = tempfile::tempdir().unwrap();
    let overrides = marsden_spec::Overrides {
        out: Some(dir.path().join("out")),
        ..marsden_spec::Overrides::default()
    };
    let text = format!("{OSCILLATOR}\n[output]\nformat = \"npy\"\nplots = false\n");
    let spec = marsden_spec::from_toml_str(&text, "sensitivity.toml", &overrides)
        .unwrap_or_else(|d| panic!("{d}"));
    let files =
        marsden_spec::execute(&spec, marsden_spec::Store::Files, &Controls::none()).unwrap();
    assert!(
        files.sensitivity.is_none(),
        "a files-only run keeps no Jacobians"
    );
    let written = marsden_io::read_npy(dir.path().join("out/sensitivity.npy")).unwrap();
    let flat: Vec<f64> = kept.samples.iter().flat_map(|(_, j)| j.clone()).collect();
    assert_eq!(written.data, flat);
}
