//! End-to-end: `[analysis] every_step` makes the summary's maxima see every step, and without
//! it the console says over how many stored samples they were taken.

use crate::util::{fixture, marsden, number, run_ok};

/// Runs the fixture's text with `edit` applied, from a temporary file.
fn run_edited(edit: impl Fn(&str) -> String) -> crate::util::Run {
    let text = std::fs::read_to_string(fixture("pendulum_every_step.toml")).unwrap();
    let tmp = tempfile::tempdir().unwrap();
    let file = tmp.path().join("pendulum.toml");
    std::fs::write(&file, edit(&text)).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    run
}

/// The pendulum (h = 0.05, 10⁵ steps, θ₀ = 1.5): storing every 25000th step, the stored rows
/// miss the largest energy error; with `every_step` the maximum equals the one of the run that
/// stores every step (max |ΔE/E₀| ≈ 1.27e-3), and so does the momentum-free summary's count.
#[test]
fn maxima_over_every_step_match_a_run_storing_every_step() {
    let monitored = run_ok("pendulum_every_step.toml", &[]);
    let all = run_edited(|t| t.replace("every = 25000", "every = 1"));
    let sparse = run_edited(|t| t.replace("every_step = true", "every_step = false"));
    let max = |r: &crate::util::Run| number(&r.summary(), "energy.max_rel_error");
    let (m, a, s) = (max(&monitored), max(&all), max(&sparse));
    assert_eq!(m, a, "every-step monitors against every stored step");
    assert!((m - 1.27e-3).abs() < 0.01e-3, "max |ΔE/E0| = {m:e}");
    assert!(s < 0.9 * m, "the 5 stored samples miss the maximum: {s:e}");
    assert_eq!(number(&monitored.summary(), "energy.samples"), 100001.0);
    assert_eq!(monitored.trajectory().n_rows(), 5);
    assert!(
        !monitored.stdout.contains("stored samples"),
        "{}",
        monitored.stdout
    );
    assert!(
        sparse.stdout.contains("(over 5 stored samples)"),
        "{}",
        sparse.stdout
    );
}

/// A misspelt key of `[analysis]` is named, with the table, a suggestion and the valid keys.
#[test]
fn unknown_analysis_key_is_named() {
    crate::util::assert_rejected(
        "analysis_unknown_key.toml",
        &["unknown key `everystep` in [analysis]", "every_step"],
    );
}
