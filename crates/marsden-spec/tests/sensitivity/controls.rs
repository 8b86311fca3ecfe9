//! The tangent run of `[sensitivity]` under the caller's controls: the progress callback every
//! 256 steps and once at the end, and the stop flag, which ends the tangent run with the
//! Jacobians of the steps taken (R1: the Cayley matrix to the power of those steps).

use std::cell::RefCell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use marsden_spec::run::sensitivity::compute_with;
use marsden_spec::run::start::prepare;
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
    let found = compute_with(&spec, asked, &start, &controls).unwrap();
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
