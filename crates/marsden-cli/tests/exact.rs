//! End-to-end: `[integrator] method = "exact"`, the exact discrete Lagrangian `L_d^E` by
//! shooting ([MW01] §1.6), and its refusals.

use crate::util::{assert_close, assert_rejected, marsden, number, repo_root};

/// R3 through the problem file: the oscillator m = k = 1 from (1, 0) with `L_d^E` and h = 0.5
/// follows the exact flow, `(q, p)(500) = (cos 500, −sin 500)` to 1e-12 after 1000 steps.
#[test]
fn r3_exact_method_reproduces_the_exact_flow_of_the_oscillator() {
    let run = marsden(
        "run",
        &repo_root().join("examples/exact_oscillator.toml"),
        &[],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    assert_eq!(s["method"], "exact");
    assert!(s["order"].is_null(), "order: {}", s["order"]);
    assert_eq!(number(&s, "final_state.t"), 500.0);
    let q = s["final_state"]["q"][0].as_f64().unwrap();
    let p = s["final_state"]["p"][0].as_f64().unwrap();
    assert_close(q, 500.0_f64.cos(), 1e-12, "q(500)");
    assert_close(p, -500.0_f64.sin(), 1e-12, "p(500)");
    // The exact flow conserves the energy ½(q² + p²) = ½ at every stored row.
    assert!(number(&s, "energy.max_rel_error") <= 1e-12);
    assert!(
        run.stdout.contains("exact (the exact flow, by shooting)"),
        "{}",
        run.stdout
    );
}

#[test]
fn exact_is_refused_with_constraints_and_forces() {
    assert_rejected(
        "exact_with_constraints.toml",
        &[
            "the method `exact` cannot be used with constraints",
            "shoots",
            "^",
        ],
    );
    assert_rejected(
        "exact_with_forces.toml",
        &[
            "the method `exact` cannot be used with forces",
            "f_d^±",
            "^",
        ],
    );
}
