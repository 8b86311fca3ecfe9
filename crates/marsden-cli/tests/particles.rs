//! Particles among jointed bodies (`[[system.particle]]`), from `examples/pendulum_with_bob.toml`:
//! a rod hinged at its top with a point mass on a ball joint at its tip, against its reduced
//! pendulum `L = ½(1/12 + 1/4 + 0.5)θ̇² + (0.5 + 0.5)·9.81·cos θ` written as an expression
//! and integrated at a tiny step: order 2, the joints closed, the bob where the rod's tip is;
//! its columns (no attitude), the summary, and every bad input with its message.

use std::path::PathBuf;

use crate::util::{Run, column, marsden, number, repo_root};

fn example() -> PathBuf {
    repo_root().join("examples").join("pendulum_with_bob.toml")
}

fn run_text(text: &str, extra: &[&str]) -> (Run, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bob.toml");
    std::fs::write(&path, text).unwrap();
    (marsden("run", &path, extra), dir)
}

const T_END: f64 = 1.0;

/// The reduced pendulum's angle at `T_END` (gauss-4, 2000 steps).
fn reduced_angle() -> f64 {
    let text = format!(
        "[system]\ncoordinates = [\"theta\"]\n\
         lagrangian = \"0.5*(1/12 + 1/4 + 0.5)*theta_dot^2 + (0.5 + 0.5)*9.81*cos(theta)\"\n\
         [initial]\nq = [0.8]\nv = [-0.6]\n\
         [integrator]\nmethod = \"gauss-4\"\nh = {h:?}\nsteps = 2000\ntolerance = 1e-15\n\
         [output]\nevery = 2000\nplots = false\n",
        h = T_END / 2000.0
    );
    let (run, _dir) = run_text(&text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    run.summary()["final_state"]["q"][0].as_f64().unwrap()
}

#[test]
fn rod_with_a_particle_bob_is_second_order_against_its_reduced_pendulum() {
    let reference = reduced_angle();
    let text = std::fs::read_to_string(example())
        .unwrap()
        .replace(
            "method = \"trapezoid\"",
            "method = \"trapezoid\"\ntolerance = 1e-14",
        )
        .replace("every = 10", "every = 1\nplots = false");
    let hs = [0.02, 0.01, 0.005];
    let mut errors = Vec::new();
    for h in hs {
        let steps = ((T_END / h).round() as usize).to_string();
        let (run, _dir) = run_text(&text, &["--h", &h.to_string(), "--steps", &steps]);
        assert_eq!(run.code, 0, "h = {h}: {}", run.stderr);
        let s = run.summary();
        assert!(number(&s, "multibody.max_joint_residual") <= 1e-13);
        assert_eq!(
            (
                s["multibody"]["bodies"].as_u64(),
                s["multibody"]["particles"].as_u64()
            ),
            (Some(1), Some(1))
        );
        assert!(s["multibody"]["final_attitudes"]["bob"].is_null());
        let r = &s["multibody"]["final_attitudes"]["rod"];
        let angle = r[0][2].as_f64().unwrap().atan2(r[0][0].as_f64().unwrap());
        // The bob hangs at the rod's tip: its angle from its own columns is the rod's.
        let table = run.trajectory();
        let (x, z) = (column(&table, "bob_x"), column(&table, "bob_z"));
        let last = x.len() - 1;
        assert!(((-x[last]).atan2(-z[last]) - angle).abs() < 1e-12);
        errors.push((angle - reference).abs());
    }
    let order = (errors[0] / errors[2]).log2() / 2.0;
    println!("rod with a bob: order {order:.3}, errors {errors:?}");
    assert!(
        (order - 2.0).abs() < 0.1,
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn a_particle_has_position_and_momentum_columns_only() {
    let run = marsden("run", &example(), &["--steps", "50"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let names: Vec<String> = run.trajectory().names().map(str::to_owned).collect();
    for c in [
        "rod_R11",
        "rod_Pi2",
        "rod_x",
        "bob_x",
        "bob_z",
        "bob_p_x",
        "bob_p_z",
        "lambda_ball_2",
    ] {
        assert!(names.iter().any(|n| n == c), "{c} missing: {names:?}");
    }
    assert!(
        !names
            .iter()
            .any(|n| n.starts_with("bob_R") || n.starts_with("bob_Pi"))
    );
    assert!(
        run.stdout.contains("1 body and 1 particle"),
        "{}",
        run.stdout
    );
    assert!(run.out.join("bodies.png").exists());
}

#[test]
fn joints_and_data_a_particle_cannot_take_are_refused() {
    let base = std::fs::read_to_string(example()).unwrap();
    let cases: [(String, &[&str]); 5] = [
        (
            base.replace("kind = \"spherical\"", "kind = \"fixed\""),
            &["a fixed joint cannot hold particle `bob`", "^"],
        ),
        (
            base.replace(
                "at = [[0.0, 0.0, -0.5], [0.0, 0.0, 0.0]]",
                "at = [[0.0, 0.0, -0.5], [0.0, 0.0, 0.1]]",
            ),
            &["acts on particle `bob` at its position", "^"],
        ),
        (
            base.replace(
                "[initial.bob]\n",
                "[initial.bob]\nOmega = [0.0, 1.0, 0.0]\n",
            ),
            &[
                "particle `bob` has no attitude: `Omega` cannot be given",
                "^",
            ],
        ),
        (
            base.replace("name = \"bob\"\nmass = 0.5", "name = \"bob\""),
            &["particle `bob` has no `mass`"],
        ),
        (
            base.replace("name = \"bob\"\nmass = 0.5", "name = \"rod\"\nmass = 0.5"),
            &["two bodies or particles are named `rod`"],
        ),
    ];
    for (text, fragments) in cases {
        let (run, _dir) = run_text(&text, &[]);
        assert_eq!(run.code, 2, "{fragments:?}: {}", run.stderr);
        for f in fragments {
            assert!(run.stderr.contains(f), "{f:?} not in:\n{}", run.stderr);
        }
    }
}
