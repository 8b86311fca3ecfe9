//! End-to-end: `[system] hamiltonian = "…"` runs through `L = ⟨p, v⟩ − H` (every method), and
//! the misuses are refused with a pointed message.

use crate::util::{assert_rejected, number, run_ok};

fn final_state(s: &serde_json::Value) -> Vec<f64> {
    let part = |k: &str| -> Vec<f64> {
        s["final_state"][k]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    [part("q"), part("p")].concat()
}

/// The pendulum given by `H = ½p² − w2 cos θ` and by `L = ½θ̇² + w2 cos θ` is the same
/// problem: the discrete Hamiltonian map of the same `L_d` ([MW01] Thm 2.6.2), so the gauss-2
/// runs end in the same state to 1e-12 after 2000 steps.
#[test]
fn pendulum_hamiltonian_and_lagrangian_give_the_same_map_gauss2() {
    let h = run_ok("pendulum_h_gauss-2.toml", &[]).summary();
    let l = run_ok("pendulum_l_gauss-2.toml", &[]).summary();
    assert_eq!(h["status"], "completed");
    assert_eq!(h["system"], "hamiltonian");
    for (a, b) in final_state(&h).iter().zip(final_state(&l)) {
        assert!((a - b).abs() <= 1e-12, "final state {a} against {b}");
    }
}

/// Midpoint on the Hamiltonian completes, its energy error bounded (symplectic: no drift over
/// 2000 steps of h = 0.05) and equal to the Lagrangian run's.
#[test]
fn pendulum_hamiltonian_midpoint_keeps_the_energy_bounded() {
    let run = run_ok("pendulum_h_midpoint.toml", &[]);
    let h = run.summary();
    let l = run_ok("pendulum_l_midpoint.toml", &[]).summary();
    assert_eq!(h["status"], "completed");
    let (eh, el) = (
        number(&h, "energy.max_rel_error"),
        number(&l, "energy.max_rel_error"),
    );
    assert!(eh < 5e-3, "max |ΔE/E0| = {eh:e}");
    assert!(
        (eh - el).abs() <= 1e-9,
        "{eh:e} against the Lagrangian's {el:e}"
    );
    // E = H at the initial state: ½·0² − cos 1.5.
    assert!((number(&h, "energy.initial") + 1.5_f64.cos()).abs() <= 1e-14);
}

#[test]
fn a_hamiltonian_not_regular_in_p_is_refused() {
    assert_rejected(
        "hamiltonian_not_regular.toml",
        &["the Hamiltonian is not regular", "∂²H/∂p²"],
    );
    assert_rejected(
        "hamiltonian_without_momenta.toml",
        &["the Hamiltonian is not regular", "p_<coordinate>", "^"],
    );
}

#[test]
fn a_hamiltonian_uses_momenta_not_velocities_and_comes_alone() {
    assert_rejected("hamiltonian_velocity_name.toml", &["theta_dot", "p_theta"]);
    assert_rejected(
        "hamiltonian_and_lagrangian.toml",
        &["give either `hamiltonian` or `lagrangian`/`builtin`, not both"],
    );
}

/// R12's balance for a Hamiltonian depending on `t`: `H = ½p² + ½x² − a t x` is the Legendre
/// transform of the ramp `L = ½ẋ² − ½x² + a t x`, so the run reports the same balance as the
/// time-dependent `L` (not an energy error): the time work equals its closed form
/// `−Σ h a x̄_k` on the stored trajectory to 1e-13, every per-step defect is round-off
/// (midpoint, potential quadratic in x plus bilinear in (t, x)), and the final state is the
/// `L` file's to 1e-12 (the same map, MW01 Thm 2.6.2).
#[test]
fn r12_time_dependent_hamiltonian_reports_the_energy_balance() {
    let run = run_ok("ramp_by_hamiltonian.toml", &[]);
    let s = run.summary();
    assert_eq!(s["energy_not_conserved"], "the Hamiltonian depends on t");
    assert!(s["energy"]["max_rel_error"].is_null(), "{s:#}");
    let t = run.trajectory();
    let (q, e) = (
        crate::util::column(&t, "q_x"),
        crate::util::column(&t, "energy"),
    );
    assert_eq!(q.len(), 201);
    let (a, h) = (0.05, 0.1);
    let closed_form: f64 = q.windows(2).map(|w| -h * a * 0.5 * (w[0] + w[1])).sum();
    let time_work = number(&s, "energy_balance.total_time_work");
    assert!(
        (time_work - closed_form).abs() <= 1e-13,
        "time work {time_work:e} against −h a Σ x̄ = {closed_form:e}"
    );
    assert!(time_work.abs() > 1e-2, "{time_work:e}");
    assert_eq!(number(&s, "energy_balance.total_work"), 0.0);
    let unaccounted = e[200] - e[0] - time_work;
    assert!(
        unaccounted.abs() <= 1e-13,
        "E_N − E_0 − W_t = {unaccounted:e}"
    );
    let max_defect = number(&s, "energy_balance.max_defect");
    assert!(max_defect <= 1e-14, "max per-step defect {max_defect:e}");
    assert!(
        run.stdout
            .contains("balance (the Hamiltonian depends on t)"),
        "{}",
        run.stdout
    );
    let l = run_ok("ramp_by_lagrangian.toml", &["--quiet"]).summary();
    for (x, y) in final_state(&s).iter().zip(final_state(&l)) {
        assert!((x - y).abs() <= 1e-12, "final state {x} against {y}");
    }
}

/// An autonomous Hamiltonian still reports its energy error, not a balance.
#[test]
fn an_autonomous_hamiltonian_reports_its_energy_error() {
    let s = run_ok("pendulum_h_midpoint.toml", &["--quiet"]).summary();
    assert!(s["energy_not_conserved"].is_null(), "{s:#}");
    assert!(s["energy_balance"].is_null(), "{s:#}");
    assert!(number(&s, "energy.max_rel_error").is_finite());
}

/// `H` and the `L` derived from it by hand, run by gauss-2 from the same `p₀`: the final
/// states, and what `marsden check` says about the path the run takes.
fn same_map(hamiltonian: &str, lagrangian: &str, parameters: &str, tol: f64) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let file = |key: &str, text: &str| {
        let path = tmp.path().join(format!("{key}.toml"));
        let body = format!(
            "[system]\ncoordinates = [\"x\", \"y\"]\nparameters = {{ {parameters} }}\n\
             {key} = \"{text}\"\n[initial]\nq = [1.0, 0.0]\np = [0.0, 1.1]\n\
             [integrator]\nmethod = \"gauss-2\"\nh = 0.01\nsteps = 2000\n\
             [output]\nevery = 100\nplots = false\n"
        );
        std::fs::write(&path, body).unwrap();
        path
    };
    let h_file = file("hamiltonian", hamiltonian);
    let h = crate::util::marsden("run", &h_file, &[]);
    let l = crate::util::marsden("run", &file("lagrangian", lagrangian), &[]);
    assert_eq!(h.code, 0, "{}", h.stderr);
    assert_eq!(l.code, 0, "{}", l.stderr);
    for (a, b) in final_state(&h.summary())
        .iter()
        .zip(final_state(&l.summary()))
    {
        assert!((a - b).abs() <= tol, "final state {a} against {b}");
    }
    crate::util::marsden("check", &h_file, &[]).stdout
}

/// A separable `H = ½ pᵀ K p + V` with coupled momenta (`K = [[1/m, 0.3], [0.3, 1/m]]`, m = 2)
/// runs as its closed-form Lagrangian `L = ½ vᵀ K⁻¹ v − V` (`K⁻¹ = [[3.125, −1.875], [−1.875,
/// 3.125]]`, derived by hand): the same map ([MW01] Thm 2.6.2) to 1e-12 after 2000 gauss-2
/// steps, and `check` says it takes the separable path.
#[test]
fn a_separable_hamiltonian_with_coupled_momenta_runs_as_its_closed_form_lagrangian() {
    let said = same_map(
        "0.5*(p_x^2 + p_y^2)/m + 0.3*p_x*p_y + 0.5*(x^2 + y^2) + 0.1*x^4",
        "0.5*(3.125*x_dot^2 - 3.75*x_dot*y_dot + 3.125*y_dot^2) - 0.5*(x^2 + y^2) - 0.1*x^4",
        "m = 2.0",
        1e-12,
    );
    assert!(
        said.contains("separable: run as L = ½vᵀK⁻¹v − V(q)"),
        "{said}"
    );
}

/// A Hamiltonian whose kinetic part depends on `q` (`H = p_x²/(2(1 + x²)) + …`) is not
/// separable: it runs through `L = ⟨p, v⟩ − H` at `∂H/∂p = v`, and still gives the map of its
/// Lagrangian `L = ½(1 + x²)ẋ² + …` to 1e-11.
#[test]
fn a_hamiltonian_whose_mass_depends_on_q_takes_the_general_path() {
    let said = same_map(
        "p_x^2/(2*(1 + x^2)) + 0.5*p_y^2 + 0.5*(x^2 + y^2)",
        "0.5*(1 + x^2)*x_dot^2 + 0.5*y_dot^2 - 0.5*(x^2 + y^2)",
        "m = 1.0",
        1e-11,
    );
    assert!(
        said.contains("run as L = ⟨p, v⟩ − H at ∂H/∂p = v"),
        "{said}"
    );
}
