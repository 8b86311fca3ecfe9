//! Rigid bodies from problem files (`[system] rigid_body`): the free rigid body of reference
//! case R19 (energy, Casimir and spatial momentum to round-off; orders 2 and 4 against the exact
//! solution of Euler's equations in Jacobi elliptic functions), the heavy top of R20 (the
//! vertical momentum and the spin to round-off, the energy error of order 2), the same bits as
//! the core's Rust interface, and every bad input with its message.

use std::path::PathBuf;

use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::{Lgvi, LgviOptions};
use marsden::lie::potential::UniformGravity;
use marsden::lie::so3::{self, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::numerics::dense::max_or_nan;
use marsden::special::euler_top::EulerTop;
use serde_json::Value;

use crate::util::{Run, marsden, number, repo_root};

/// R19's body and initial momentum.
const R19_MOMENTS: [f64; 3] = [2.0, 1.0, 2.0 / 3.0];

fn r19_pi0() -> [f64; 3] {
    [1.1_f64.cos(), 0.0, 1.1_f64.sin()]
}

/// Writes `text` as a problem file and runs `marsden run` on it with `extra` arguments.
fn run_text(text: &str, extra: &[&str]) -> (Run, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("body.toml");
    std::fs::write(&path, text).unwrap();
    (marsden("run", &path, extra), dir)
}

fn example(name: &str) -> PathBuf {
    repo_root().join("examples").join(name)
}

/// R19 as a file: `J = diag(2, 1, 2/3)`, `Π₀ = (cos 1.1, 0, sin 1.1)`, `R₀ = I`.
fn r19_file(method: &str, h: f64, t_end: f64) -> String {
    let [p1, p2, p3] = r19_pi0();
    format!(
        "[system]\nrigid_body = {{ inertia = [2.0, 1.0, {j3:?}] }}\n\
         [initial]\nPi = [{p1:?}, {p2:?}, {p3:?}]\n\
         [integrator]\nmethod = \"{method}\"\nh = {h:?}\nt_end = {t_end:?}\ntolerance = 1e-14\n\
         [output]\nevery = 1000000\nplots = false\n",
        j3 = R19_MOMENTS[2]
    )
}

fn final_pi(summary: &Value) -> [f64; 3] {
    let pi = summary["rigid_body"]["final_body_momentum"]
        .as_array()
        .unwrap();
    [0, 1, 2].map(|i| pi[i].as_f64().unwrap())
}

/// Slope of `log e` against `log h` (least squares).
fn slope(hs: &[f64], errors: &[f64]) -> f64 {
    let x: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx) * (a - mx)).sum();
    sxy / sxx
}

#[test]
fn r19_free_rigid_body_keeps_energy_casimir_and_spatial_momentum_to_round_off() {
    let run = marsden(
        "run",
        &example("free_rigid_body.toml"),
        &["--steps", "4000"],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["status"], "completed");
    assert_eq!(s["system"], "rigid_body");
    let energy = number(&s, "energy.max_rel_error");
    assert!(energy <= 1e-13, "energy {energy:e}");
    let casimir = number(&s, "rigid_body.casimir.max_abs_drift");
    assert!(casimir <= 1e-13, "casimir {casimir:e}");
    assert!(number(&s, "rigid_body.orthogonality_defect") <= 1e-13);
    for axis in ["L_x", "L_y", "L_z"] {
        let drift = number(&s, &format!("momenta.{axis}.max_abs_drift"));
        assert!(drift <= 1e-13, "{axis}: {drift:e}");
        assert_eq!(s["momenta"][axis]["symmetry"], true);
    }
    let table = run.trajectory();
    for c in ["R11", "R33", "Pi1", "Pi3", "energy", "J_L_z"] {
        assert!(table.values(c).is_some(), "no column {c}");
    }
    for png in ["axis_tip.png", "body_momentum.png", "energy_error.png"] {
        assert!(run.out.join(png).exists(), "{png} not drawn");
    }
}

/// The error of the final `Π` against the exact Euler top at `t = 8`, for each `h`.
fn errors_against_exact(method: &str, hs: &[f64]) -> Vec<f64> {
    let t_end = 8.0;
    let exact = EulerTop::new(R19_MOMENTS, r19_pi0())
        .unwrap()
        .momentum(t_end)
        .unwrap();
    hs.iter()
        .map(|&h| {
            let (run, _dir) = run_text(&r19_file(method, h, t_end), &[]);
            assert_eq!(run.code, 0, "{method}, h = {h}: {}", run.stderr);
            let s = run.summary();
            assert!((number(&s, "t_final") - t_end).abs() < 1e-9);
            let pi = final_pi(&s);
            (0..3)
                .map(|k| (pi[k] - exact[k]).abs())
                .fold(0.0, max_or_nan)
        })
        .collect()
}

#[test]
fn r19_orders_two_and_four_against_the_exact_solution_of_euler_equations() {
    let hs = [0.1, 0.05, 0.025];
    let second = errors_against_exact("trapezoid", &hs);
    let p2 = slope(&hs, &second);
    assert!(
        (p2 - 2.0).abs() < 0.15,
        "trapezoid: order {p2}, errors {second:?}"
    );
    let hs4 = [0.2, 0.1, 0.05];
    let fourth = errors_against_exact("triple-jump-4(trapezoid)", &hs4);
    let p4 = slope(&hs4, &fourth);
    assert!(
        (p4 - 4.0).abs() < 0.3,
        "triple jump: order {p4}, errors {fourth:?}"
    );
}

#[test]
fn r20_heavy_top_keeps_the_vertical_momentum_and_the_spin_and_its_energy_error_is_of_order_two() {
    let mut energy = Vec::new();
    for h in ["0.002", "0.001"] {
        let run = marsden(
            "run",
            &example("heavy_top.toml"),
            &["--h", h, "--steps", "4000"],
        );
        assert_eq!(run.code, 0, "{}", run.stderr);
        let s = run.summary();
        let lz = number(&s, "momenta.L_z.max_abs_drift") / number(&s, "momenta.L_z.initial");
        let spin = number(&s, "momenta.Pi_z.max_abs_drift") / number(&s, "momenta.Pi_z.initial");
        assert!(lz <= 1e-13 && spin <= 1e-13, "L_z {lz:e}, Π3 {spin:e}");
        assert_eq!(s["momenta"]["L_z"]["symmetry"], true);
        assert_eq!(s["momenta"]["Pi_z"]["symmetry"], true);
        assert!(number(&s, "rigid_body.orthogonality_defect") <= 1e-13);
        energy.push(number(&s, "energy.max_rel_error"));
    }
    // Bounded and second order: the largest error over the same time span, h halved.
    let ratio = energy[0] / energy[1];
    assert!((3.0..5.0).contains(&ratio), "energy errors {energy:?}");
    assert!(energy[1] < 1e-8, "{energy:?}");
}

#[test]
fn a_symmetry_the_body_does_not_have_is_monitored_and_said() {
    // The heavy top is not symmetric about the horizontal axis x of space.
    let text = std::fs::read_to_string(example("heavy_top.toml"))
        .unwrap()
        .replace(
            "rotation = \"z\"                               # about",
            "rotation = \"x\" # about",
        );
    let (run, _dir) = run_text(&text, &["--steps", "100"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(
        run.stderr
            .contains("\"L_x\" is not a symmetry of the rigid body"),
        "{}",
        run.stderr
    );
    assert_eq!(run.summary()["momenta"]["L_x"]["symmetry"], false);
}

#[test]
fn the_file_gives_the_same_bits_as_the_rust_interface() {
    let steps = 3000;
    let run = marsden(
        "run",
        &example("heavy_top.toml"),
        &["--steps", &steps.to_string()],
    );
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    let body = RigidBody::fixed_point(Inertia::principal([5.0, 5.0, 1.0]).unwrap());
    let system = RigidSystem::new(vec![body], UniformGravity::top(20.0));
    let r0 = so3::from_rotation_vector(&Vec3::new(0.05, 0.0, 0.0));
    let pi0 = Vec3::new(0.0, 0.0, 50.0);
    let state = RigidState::new(&system, 0.0, &[BodyInitial::rotating(&r0, &pi0)]).unwrap();
    let mut lgvi = Lgvi::new(system, state, 0.001, LgviOptions::default()).unwrap();
    for _ in 0..steps {
        lgvi.step().unwrap();
    }
    let rows = &s["rigid_body"]["final_attitude"];
    for (k, expected) in lgvi.state().rotations.iter().enumerate() {
        let got = rows[k / 3][k % 3].as_f64().unwrap();
        assert_eq!(
            got.to_bits(),
            expected.to_bits(),
            "R entry {k}: {got} vs {expected}"
        );
    }
    for (k, expected) in lgvi.state().momenta.iter().enumerate() {
        assert_eq!(final_pi(&s)[k].to_bits(), expected.to_bits(), "Π_{k}");
    }
}

#[test]
fn a_body_with_a_mass_moves_its_centre_by_its_forces() {
    // A free body falling under gravity: x(t) = x0 + v0 t − g t²/2 exactly for the Verlet
    // translation, whatever the rotation.
    let text = "[system]\nrigid_body = { inertia = [1.0, 2.0, 2.5], mass = 2.0 }\n\
                parameters = { g = 9.81 }\npotential = \"2*g*z\"\n\
                [[system.symmetry]]\ntranslation = \"x\"\n\
                [initial]\nq = [0.0, 0.0, 10.0]\nv = [1.0, 0.0, 0.0]\nOmega = [0.3, 2.0, 0.1]\n\
                [integrator]\nh = 0.01\nsteps = 100\n[output]\nplots = false\n";
    let (run, _dir) = run_text(text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = run.trajectory();
    let (t, z, x) = (
        table.values("t").unwrap(),
        table.values("q_z").unwrap(),
        table.values("q_x").unwrap(),
    );
    let k = t.len() - 1;
    assert!(
        (z[k] - (10.0 - 0.5 * 9.81 * t[k] * t[k])).abs() < 1e-10,
        "z = {}",
        z[k]
    );
    assert!((x[k] - t[k]).abs() < 1e-12, "x = {}", x[k]);
    let s = run.summary();
    assert!(number(&s, "momenta.P_x.max_abs_drift") <= 1e-14);
    assert!(number(&s, "energy.max_rel_error") < 1e-10);
}

/// A rigid file with `replace` applied to its heavy-top text, and the fragments its refusal
/// must contain (exit 2, nothing written).
fn assert_refused(edit: (&str, &str), fragments: &[&str]) {
    let text = std::fs::read_to_string(example("heavy_top.toml")).unwrap();
    assert!(text.contains(edit.0), "the example lacks {:?}", edit.0);
    let (run, _dir) = run_text(&text.replace(edit.0, edit.1), &[]);
    assert_eq!(run.code, 2, "{edit:?}: {}", run.stderr);
    for f in fragments {
        assert!(
            run.stderr.contains(f),
            "{edit:?}: lacks {f:?}:\n{}",
            run.stderr
        );
    }
    assert!(run.stderr.contains('^'), "no caret: {}", run.stderr);
    assert!(!run.out.exists(), "{edit:?}: something was written");
}

#[test]
fn bad_rigid_bodies_are_refused_with_a_caret() {
    assert_refused(
        ("inertia = [5.0, 5.0, 1.0]", "inertia = [5.0, -5.0, 1.0]"),
        &["invalid inertia", "not positive definite"],
    );
    assert_refused(
        (
            "inertia = [5.0, 5.0, 1.0]",
            "inertia = [[5, 1, 0], [0, 5, 0], [0, 0, 1]]",
        ),
        &["invalid inertia", "not symmetric"],
    );
    assert_refused(
        ("inertia = [5.0, 5.0, 1.0]", "inertia = [5.0, 5.0]"),
        &["three principal moments or a 3×3 matrix"],
    );
    assert_refused(
        ("potential = \"mgl*R33\"", "potential = \"mgl*R34\""),
        &["in [system] potential: unknown name `R34`", "R33"],
    );
    assert_refused(
        ("potential = \"mgl*R33\"", "potential = \"mgl*z\""),
        &["names `z`, the centre of mass, but the body has no `mass`"],
    );
    assert_refused(
        ("method = \"trapezoid\"", "method = \"gauss-2\""),
        &[
            "the method `gauss-2` has no rigid-body version",
            "triple-jump-4(trapezoid)",
        ],
    );
    assert_refused(
        (
            "rotation_vector = [0.05, 0.0, 0.0]",
            "R = [[1, 0, 0], [0, 1, 0.001], [0, 0, 1]]",
        ),
        &["not a rotation", "orthonormal"],
    );
    assert_refused(
        (
            "rotation_vector = [0.05, 0.0, 0.0]",
            "rotation_vector = [0.05, 0.0, 0.0]\nquaternion = [1, 0, 0, 0]",
        ),
        &["give the initial attitude once"],
    );
    assert_refused(
        (
            "Omega = [0.0, 0.0, 50.0]",
            "Omega = [0.0, 0.0, 50.0]\nPi = [0, 0, 50]",
        ),
        &["give either `Omega` or `Pi`"],
    );
    assert_refused(
        ("Omega = [0.0, 0.0, 50.0]", "Omega = [0.0, 50.0]"),
        &["initial.Omega has 2 values"],
    );
    assert_refused(
        ("rotation = \"z\"", "rotation = \"w\""),
        &["unknown axis `w`"],
    );
    assert_refused(
        (
            "potential = \"mgl*R33\"",
            "potential = \"mgl*R33\"\nforces = [\"0\", \"0\", \"-1\"]",
        ),
        &["`forces` act on the centre of mass of a body with a `mass`"],
    );
    assert_refused(
        (
            "potential = \"mgl*R33\"",
            "potential = \"mgl*R33\"\ncoordinates = [\"a\"]",
        ),
        &["`coordinates` cannot be used with a rigid body"],
    );
    assert_refused(
        ("[output]", "[sensitivity]\ninitial = true\n[output]"),
        &["[sensitivity] is not available for a rigid body"],
    );
}

#[test]
fn rigid_keys_without_a_rigid_body_are_refused() {
    let text = std::fs::read_to_string(example("pendulum.toml"))
        .unwrap()
        .replace("v = [0.0]", "v = [0.0]\nOmega = [1.0, 0.0, 0.0]");
    let (run, _dir) = run_text(&text, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(
        run.stderr.contains("`Omega` applies to a rigid body"),
        "{}",
        run.stderr
    );
}

#[test]
fn a_torque_about_the_symmetry_axis_raises_the_spin_linearly() {
    // J₁ = J₂: Euler's third equation is J₃Ω̇₃ = τ₃, so Π₃(t) = Π₃(0) + τ₃ t; the step keeps
    // the discrete Noether balance of the body rotation about e₃ exactly: Π₃ grows by hτ₃ per
    // step to round-off (a wrong sign of the torque would make it fall).
    let text = "[system]\nrigid_body = { inertia = [3.0, 3.0, 1.0] }\n\
                torques = [\"0\", \"0\", \"0.25\"]\n\
                [initial]\nOmega = [0.4, -0.7, 2.0]\n\
                [integrator]\nh = 0.01\nsteps = 400\n[output]\nplots = false\n";
    let (run, _dir) = run_text(text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = run.trajectory();
    let (t, pi3) = (table.values("t").unwrap(), table.values("Pi3").unwrap());
    for k in 0..t.len() {
        let expected = 2.0 + 0.25 * t[k];
        assert!(
            (pi3[k] - expected).abs() < 1e-12,
            "t = {}: {} vs {expected}",
            t[k],
            pi3[k]
        );
    }
    let s = run.summary();
    assert_eq!(s["energy_not_conserved"], "torques or forces act");
    assert!(s["energy"]["max_rel_error"].is_null());
}

#[test]
fn the_catalog_heavy_top_is_the_written_one_bit_for_bit() {
    let written = marsden("run", &example("heavy_top.toml"), &["--steps", "500"]);
    let text = "[system]\nbuiltin = \"heavy_top\"\n\
                [[system.symmetry]]\nrotation = \"z\"\n\
                [initial]\nrotation_vector = [0.05, 0.0, 0.0]\nOmega = [0.0, 0.0, 50.0]\n\
                [integrator]\nh = 0.001\nsteps = 500\n[output]\nplots = false\n";
    let (builtin, _dir) = run_text(text, &[]);
    assert_eq!(builtin.code, 0, "{}", builtin.stderr);
    let (a, b) = (written.summary(), builtin.summary());
    assert_eq!(
        a["rigid_body"]["final_attitude"],
        b["rigid_body"]["final_attitude"]
    );
    assert_eq!(
        a["rigid_body"]["final_body_momentum"],
        b["rigid_body"]["final_body_momentum"]
    );
    // A parameter of the entry is overridden; one it does not have is an expression constant.
    let (light, _dir) = run_text(
        &text.replace(
            "builtin = \"heavy_top\"",
            "builtin = \"heavy_top\"\nparameters = { mgl = 0.0 }",
        ),
        &[],
    );
    assert_eq!(light.code, 0, "{}", light.stderr);
    // Without gravity the top spins steadily: Π does not change.
    let pi = final_pi(&light.summary());
    assert!(
        pi[0].abs() < 1e-12 && pi[1].abs() < 1e-12 && (pi[2] - 50.0).abs() < 1e-12,
        "{pi:?}"
    );
    let (both, _dir) = run_text(
        &text.replace(
            "builtin = \"heavy_top\"",
            "builtin = \"heavy_top\"\npotential = \"R33\"",
        ),
        &[],
    );
    assert_eq!(both.code, 2);
    assert!(
        both.stderr
            .contains("`potential` is given by `builtin = \"heavy_top\"`"),
        "{}",
        both.stderr
    );
}

#[test]
fn marsden_systems_lists_the_rigid_bodies() {
    let out = crate::util::marsden_in(&repo_root(), &["systems", "heavy_top"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(
        text.contains("potential    mgl*R33") && text.contains("J3 = 1"),
        "{text}"
    );
    let all = crate::util::marsden_in(&repo_root(), &["systems"]);
    let text = String::from_utf8(all.stdout).unwrap();
    assert!(
        text.contains("free_rigid_body  —") && text.contains("heavy_top  —"),
        "{text}"
    );
}
