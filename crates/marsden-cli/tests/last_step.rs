//! A `t_end` that is not a whole number of steps: the run ends there exactly with one shorter,
//! still variational step, says so in `summary.json` and on the console, and the balances of a
//! forced run discretise that step with its own size.

use crate::util::{assert_rejected_with, column, number, run_ok};

/// Reference case R12 with a shorter last step: 100 midpoint steps of h = 0.1 and one of 0.05.
/// `E_{k+1} − E_k = −c (q_{k+1} − q_k)²/h_k` holds to round-off at every step only if the
/// balance takes the last step's own `h_k` (with `h` there the last defect would be of the
/// size of that step's work).
#[test]
fn r12_damped_oscillator_balance_holds_with_a_shorter_last_step() {
    let run = run_ok("r12_damped_last_step.toml", &[]);
    let s = run.summary();
    assert_eq!(number(&s, "steps"), 101.0);
    assert_eq!(number(&s, "final_state.t"), 10.05, "ends at t_end exactly");
    let last = number(&s, "last_step");
    assert!((last - 0.05).abs() < 1e-12, "last step {last}");
    let t = run.trajectory();
    let (time, q) = (column(&t, "t"), column(&t, "q_x"));
    assert_eq!(q.len(), 102);
    let c = 0.1;
    let closed_form: f64 = (time.windows(2).zip(q.windows(2)))
        .map(|(t, q)| -c * (q[1] - q[0]).powi(2) / (t[1] - t[0]))
        .sum();
    let work = number(&s, "energy_balance.total_work");
    assert!(
        (work - closed_form).abs() <= 1e-12,
        "total work {work:e} against −c Σ Δq²/h_k = {closed_form:e}"
    );
    let max_defect = number(&s, "energy_balance.max_defect");
    assert!(max_defect <= 1e-14, "max per-step defect {max_defect:e}");
    assert!(
        run.stdout.contains("the last one shorter, h = 0.05"),
        "{}",
        run.stdout
    );
}

/// A uniform run says nothing about a last step (the key is absent from `summary.json`).
#[test]
fn a_whole_number_of_steps_has_no_last_step_key() {
    let run = run_ok("r12_damped_midpoint.toml", &["--steps", "10"]);
    assert!(run.summary().get("last_step").is_none());
    assert!(!run.stdout.contains("shorter"), "{}", run.stdout);
}

/// A rigid body's LGVI is built for one `h`: a `t_end` off the grid is refused with the two
/// whole grids beside it, before anything is written.
#[test]
fn a_rigid_body_with_a_t_end_off_the_grid_is_refused_with_the_neighbours() {
    assert_rejected_with(
        "rigid_t_end_off_grid.toml",
        &[],
        &[
            "t_end = 1.05 is not a whole number of steps h = 0.1",
            "a rigid body",
            "takes no shorter last step",
            "use t_end = 1 or 1.1",
        ],
    );
}
