//! End-to-end: forces written in the momenta `p_<coordinate>` (`f_H`) run as `f_L = f_H ∘ FL`
//! ([MW01] §3.1), and the misuses are refused with a pointed message.

use crate::util::{assert_close, assert_rejected, column, marsden, run_ok};

/// For `L = ½ m ẋ² − ½ k x²`, `FL(x, ẋ) = m ẋ`, so the damping `−c p_x / m` is the damping
/// `−c ẋ`: the two runs (midpoint, 1500 steps, m = 2) agree to round-off (1e-14) at every stored
/// row, positions and momenta.
#[test]
fn momentum_damping_equals_velocity_damping_r12_oscillator() {
    let p = run_ok("damped_force_p.toml", &[]);
    let v = run_ok("damped_force_v.toml", &[]);
    assert_eq!(p.summary()["status"], "completed");
    let (tp, tv) = (p.trajectory(), v.trajectory());
    for name in ["q_x", "p_x"] {
        let (a, b) = (column(&tp, name), column(&tv, name));
        assert_eq!(a.len(), b.len());
        assert!(a.len() > 100);
        for (x, y) in a.iter().zip(b) {
            assert_close(*x, *y, 1e-14, name);
        }
    }
    // The damping acted: the amplitude A(t) = A₀ exp(−c t / 2m), A₀ = √(1 + m v₀²/k) ≈ 1.06,
    // is 0.13 over the last 10 rows (t ≥ 28).
    let x = column(&tp, "q_x");
    let tail = &x[x.len() - 10..];
    assert!(tail.iter().all(|x| x.abs() < 0.15), "{tail:?}");
}

#[test]
fn a_force_reads_momenta_of_existing_coordinates_only() {
    assert_rejected(
        "force_unknown_momentum.toml",
        &["[system] forces[0]", "p_y", "p_x", "^"],
    );
}

#[test]
fn forces_use_velocities_or_momenta_not_both() {
    assert_rejected(
        "force_velocity_and_momentum.toml",
        &[
            "both the velocity `y_dot` and the momentum `p_x`",
            "forces[1]",
            "^",
        ],
    );
}

/// The damped oscillator `L = ½ m ẋ² − ½ k x²` with its damping written as `force`, and
/// `[sensitivity] parameters = ["c", "m"]`.
fn damped(force: &str, c: f64) -> String {
    format!(
        "[system]\ncoordinates = [\"x\"]\nparameters = {{ m = 2.0, k = 4.0, c = {c} }}\n\
         lagrangian = \"0.5*m*x_dot^2 - 0.5*k*x^2\"\nforces = [\"{force}\"]\n\
         [initial]\nq = [1.0]\nv = [0.5]\n\
         [integrator]\nmethod = \"midpoint\"\nh = 0.02\nsteps = 1500\ntolerance = 1e-14\n\
         [sensitivity]\nparameters = [\"c\", \"m\"]\n[output]\nevery = 100\nplots = false\n"
    )
}

/// Runs `text` and returns its summary.
fn summary_of(text: &str) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("damped.toml");
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    run.summary()
}

/// `∂(x_N, p_N)/∂(c, m)` from the summary (rows x, p; columns c, m).
fn final_jacobian(summary: &serde_json::Value) -> Vec<Vec<f64>> {
    let rows = summary["sensitivity"]["final"].as_array().unwrap();
    (rows.iter())
        .map(|r| {
            (r.as_array().unwrap().iter())
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect()
}

/// Parameter sensitivities through a force written in the momenta (they were once refused):
/// `−c p_x/m` is `−c ẋ` because `FL = m ẋ`, so the derivatives with respect to `c` and `m`
/// must be those of the velocity form. Through `m` this holds only if the momenta inside the
/// force are the parametric Lagrangian's (`∂p/∂m = ẋ` cancels the `1/m`): a model that froze
/// `p` at the file's `m` would give another `∂/∂m`. Both Jacobians agree to 1e-11, and the
/// column of `c` matches central differences of whole runs (c ± 1e-5) to 1e-7.
#[test]
fn parameter_sensitivities_through_a_momentum_force_equal_the_velocity_forms() {
    let momentum = final_jacobian(&summary_of(&damped("-c*p_x/m", 0.3)));
    let velocity = final_jacobian(&summary_of(&damped("-c*x_dot", 0.3)));
    assert_eq!(momentum.len(), 2);
    for (a, b) in momentum.iter().flatten().zip(velocity.iter().flatten()) {
        assert_close(*a, *b, 1e-11, "∂(x, p)/∂(c, m)");
    }
    assert!(
        momentum.iter().flatten().all(|x| x.abs() > 1e-3),
        "{momentum:?}"
    );
    let delta = 1e-5;
    let final_state = |c: f64| {
        let s = summary_of(&damped("-c*p_x/m", c));
        let state = &s["final_state"];
        [
            state["q"][0].as_f64().unwrap(),
            state["p"][0].as_f64().unwrap(),
        ]
    };
    let (up, down) = (final_state(0.3 + delta), final_state(0.3 - delta));
    for row in 0..2 {
        let difference = (up[row] - down[row]) / (2.0 * delta);
        assert_close(momentum[row][0], difference, 1e-7, "∂/∂c by differences");
    }
}
