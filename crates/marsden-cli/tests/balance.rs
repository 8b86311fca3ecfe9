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

/// R12's balance for a Lagrangian depending on `t`: `E_{k+1} − E_k = W_k − ∂L_d/∂t₀`. For
/// `L = ½ẋ² − ½x² + a t x` (a potential quadratic in x plus a term bilinear in (t, x)) the
/// midpoint rule's balance is exact: every per-step defect is round-off, and the energy column
/// changes by the time work `−Σ h ∂L/∂t = −Σ h a x̄_k` (no forces: no work), which is checked
/// against that closed form on the stored trajectory.
#[test]
fn r12_time_dependent_bilinear_potential_balance_holds_to_round_off() {
    let run = run_ok("ramp_by_lagrangian.toml", &[]);
    let s = run.summary();
    assert_eq!(s["energy_not_conserved"], "the Lagrangian depends on t");
    assert!(s["energy"]["max_rel_error"].is_null());
    let t = run.trajectory();
    let (q, e) = (column(&t, "q_x"), column(&t, "energy"));
    assert_eq!(q.len(), 201);
    let (a, h) = (0.05, 0.1);
    let closed_form: f64 = q.windows(2).map(|w| -h * a * 0.5 * (w[0] + w[1])).sum();
    let time_work = number(&s, "energy_balance.total_time_work");
    assert!(
        (time_work - closed_form).abs() <= 1e-13,
        "time work {time_work:e} against −h a Σ x̄ = {closed_form:e}"
    );
    assert!(
        time_work.abs() > 1e-2,
        "the ramp changes the energy: {time_work:e}"
    );
    assert_eq!(number(&s, "energy_balance.total_work"), 0.0);
    let unaccounted = e[200] - e[0] - time_work;
    assert!(
        unaccounted.abs() <= 1e-13,
        "E_N − E_0 − W_t = {unaccounted:e}"
    );
    let max_defect = number(&s, "energy_balance.max_defect");
    assert!(max_defect <= 1e-14, "max per-step defect {max_defect:e}");
    assert!(
        run.stdout.contains("balance (the Lagrangian depends on t)")
            && run.stdout.contains("by the time dependence"),
        "{}",
        run.stdout
    );
}

/// The drive `x F cos(w t)` in L is not bilinear in (t, x): the midpoint balance's per-step
/// defect is the midpoint quadrature error of `dV` along the step in (t, x), `O(h³)` — halving
/// `h` divides the largest by 8 (a wrong sign of the `∂L_d/∂t₀` term leaves an `O(h)` defect,
/// ratio 2). The summary's parts add up: change = work + time work + defect.
#[test]
fn time_dependent_lagrangian_balance_defect_is_third_order() {
    let coarse = run_ok("driven_by_lagrangian.toml", &[]).summary();
    let fine = run_ok(
        "driven_by_lagrangian.toml",
        &["--h", "0.01", "--steps", "4000"],
    )
    .summary();
    assert_eq!(
        coarse["energy_not_conserved"],
        "the Lagrangian depends on t"
    );
    let defect = |s: &serde_json::Value| number(s, "energy_balance.max_defect");
    let ratio = defect(&coarse) / defect(&fine);
    assert!(
        (7.0..9.0).contains(&ratio),
        "defect ratio {ratio} (expected 8)"
    );
    let time_work = number(&coarse, "energy_balance.total_time_work");
    let change = number(&coarse, "energy_balance.energy_change");
    let total = number(&coarse, "energy_balance.total_defect");
    assert_eq!(number(&coarse, "energy_balance.total_work"), 0.0);
    assert!(
        time_work.abs() > 1e-2,
        "the drive changes the energy: {time_work:e}"
    );
    assert!((change - time_work - total).abs() <= 1e-13 * change.abs().max(1.0));
    assert!(
        total.abs() <= 1e-3 * time_work.abs(),
        "unaccounted {total:e} of {time_work:e}"
    );
}

/// An autonomous forced run has no time work in its balance (the field is absent).
#[test]
fn autonomous_balances_have_no_time_work() {
    let s = run_ok("r12_damped_midpoint.toml", &["--quiet"]).summary();
    assert!(s["energy_balance"].is_object());
    assert!(s["energy_balance"].get("total_time_work").is_none());
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

/// A forced run with a method with internal stages has no energy balance (its discrete forces
/// act on stage points): `summary.json` says so in `energy_balance_not_available`, and a
/// two-point method's summary has no such field.
#[test]
fn multi_stage_forced_runs_say_why_there_is_no_balance() {
    let s = run_ok("damped_gauss2.toml", &["--quiet"]).summary();
    assert_eq!(s["energy_not_conserved"], "forces act");
    assert!(s["energy_balance"].is_null());
    let why = s["energy_balance_not_available"].as_str().unwrap();
    assert!(why.contains("internal stages"), "{why}");
    let two_point = run_ok("r12_damped_midpoint.toml", &["--quiet"]).summary();
    assert!(two_point.get("energy_balance_not_available").is_none());
}
