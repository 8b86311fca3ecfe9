//! End-to-end: forced and time-dependent runs report their discrete energy balance, not an
//! "energy error" (`summary.json` `energy_balance`, the console's energy line).

use crate::util::{column, number, run_ok};

/// Reference case R12 through the command: the damped oscillator by the midpoint rule keeps
/// `E_{k+1} − E_k = W_k = −c (q_{k+1} − q_k)²/h` to round-off. The work is checked against the
/// closed form computed from the stored trajectory, and `E_N − E_0 − Σ W_k` against the
/// trajectory's own energy column.
#[test]
fn r12_damped_oscillator_balance_holds_to_round_off() {
    let run = run_ok("r12_damped_midpoint.toml", &[]);
    let s = run.summary();
    let t = run.trajectory();
    let (q, e) = (column(&t, "q_x"), column(&t, "energy"));
    assert_eq!(q.len(), 1001);
    let (c, h) = (0.1, 0.1);
    let closed_form: f64 = q.windows(2).map(|w| -c * (w[1] - w[0]).powi(2) / h).sum();
    let work = number(&s, "energy_balance.total_work");
    assert!(
        (work - closed_form).abs() <= 1e-12,
        "total work {work:e} against −c Σ Δq²/h = {closed_form:e}"
    );
    let unaccounted = e[1000] - e[0] - work;
    assert!(
        unaccounted.abs() <= 1e-12,
        "E_N − E_0 − W = {unaccounted:e}"
    );
    let max_defect = number(&s, "energy_balance.max_defect");
    assert!(max_defect <= 1e-14, "max per-step defect {max_defect:e}");
    assert_eq!(number(&s, "energy_balance.steps"), 1000.0);
    assert!(work < -0.1, "the damping removes energy: W = {work}");
    // No energy error where energy is not conserved, and the console says why.
    assert_eq!(s["energy_not_conserved"], "forces act");
    assert!(s["energy"]["max_rel_error"].is_null());
    assert!(
        run.stdout.contains("balance (forces act)"),
        "{}",
        run.stdout
    );
    assert!(!run.stdout.contains("max |ΔE/E0|"), "{}", run.stdout);
}

/// The driven pendulum: the per-step defect of the midpoint balance is
/// `(1/24) D³V(q̄)[Δq, Δq, Δq] + O(h⁵)` (`marsden::analysis::diagnostics::energy_balance`), so
/// it is not round-off for `V = −w2 cos θ` but falls like `h³`: halving `h` divides it by 8.
#[test]
fn driven_pendulum_balance_defect_is_third_order() {
    let coarse = run_ok("driven_pendulum.toml", &[]).summary();
    let fine = run_ok("driven_pendulum.toml", &["--h", "0.01", "--steps", "4000"]).summary();
    let defect = |s: &serde_json::Value| number(s, "energy_balance.max_defect");
    let ratio = defect(&coarse) / defect(&fine);
    assert!(
        (7.0..9.0).contains(&ratio),
        "defect ratio {ratio} (expected 8)"
    );
    let work = number(&coarse, "energy_balance.total_work");
    let change = number(&coarse, "energy_balance.energy_change");
    let total = number(&coarse, "energy_balance.total_defect");
    assert!(work.abs() > 1e-2, "the drive does work: {work:e}");
    assert!((change - work - total).abs() <= 1e-13 * change.abs().max(1.0));
    assert!(
        total.abs() <= 1e-3 * work.abs(),
        "unaccounted {total:e} of {work:e}"
    );
}

/// A Lagrangian depending on `t` conserves no energy: no error is reported, and the reason is.
#[test]
fn time_dependent_lagrangian_reports_no_energy_error() {
    let run = run_ok("driven_by_lagrangian.toml", &[]);
    let s = run.summary();
    assert_eq!(s["energy_not_conserved"], "the Lagrangian depends on t");
    assert!(s["energy"]["max_rel_error"].is_null());
    assert!(s["energy_balance"].is_null());
    assert!(
        run.stdout
            .contains("not conserved (the Lagrangian depends on t)")
    );
}

/// A conservative run keeps its energy error and has no balance.
#[test]
fn conservative_runs_keep_their_energy_error() {
    let s = run_ok("r1_expression.toml", &[]).summary();
    assert!(s["energy_not_conserved"].is_null());
    assert!(s["energy_balance"].is_null());
    assert!(number(&s, "energy.max_abs_error") <= 1e-13);
}

/// The energy plot of a forced run shows the balance, not an energy error.
#[test]
fn forced_runs_plot_the_energy_balance() {
    let file = crate::util::repo_root().join("examples/damped_oscillator.toml");
    let run = crate::util::marsden("run", &file, &["--steps", "200"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.out.join("energy_balance.png").is_file());
    assert!(!run.out.join("energy_error.png").exists());
    let files = run.summary()["output"]["files"].to_string();
    assert!(files.contains("energy_balance.png"), "{files}");
    assert!(!files.contains("energy_error.png"), "{files}");
    // `marsden plot` on the folder redraws the rest and still draws no energy error.
    let before = std::fs::read(run.out.join("energy_balance.png")).unwrap();
    let plot = crate::util::marsden_in(&run.out, &["plot", "."]);
    assert!(
        plot.status.success(),
        "{}",
        String::from_utf8_lossy(&plot.stderr)
    );
    assert!(!run.out.join("energy_error.png").exists());
    assert_eq!(
        std::fs::read(run.out.join("energy_balance.png")).unwrap(),
        before
    );
}
