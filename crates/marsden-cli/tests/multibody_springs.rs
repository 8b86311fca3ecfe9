//! Springs and dampers between body points in problem files (`[[system.spring]]`,
//! `[[system.damper]]`): the spring dumbbell of `examples/spring_dumbbell.toml` keeps its total
//! angular momentum to round-off and reports the spring's energy in the energy it conserves; a
//! damper makes the run say that energy is not conserved, and the energy falls; every bad input
//! with its message.

use std::path::PathBuf;

use crate::util::{Run, marsden, number, repo_root};

fn dumbbell_text() -> String {
    let path: PathBuf = repo_root().join("examples").join("spring_dumbbell.toml");
    std::fs::read_to_string(path).unwrap()
}

fn run_text(text: &str, extra: &[&str]) -> (Run, tempfile::TempDir) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("springs.toml");
    std::fs::write(&path, text).unwrap();
    (marsden("run", &path, extra), dir)
}

/// The largest drift of the total angular momentum, relative to its largest component.
fn angular_momentum_drift(s: &serde_json::Value) -> f64 {
    let l = &s["multibody"]["angular_momentum"];
    let component = |what: &str, a: usize| l[what][a].as_f64().unwrap();
    let size = (0..3)
        .map(|a| component("initial", a).abs())
        .fold(0.0, f64::max);
    (0..3)
        .map(|a| component("max_abs_drift", a))
        .fold(0.0, f64::max)
        / size
}

/// The dumbbell: the energy the run reports at the start is the kinetic energy of the file's
/// velocities plus the spring's `½k(‖d‖ − ℓ₀)² = ½·50·0.2² = 1`, worked by hand:
/// `½(0.0125) + ½(0.03·0.25 + 0.04·4) + ½·0.5·0.04 + ½(0.01 + 0.015·2.25) + 1 = 1.121875`.
/// It is conserved to a bounded error; the angular momentum about the origin to round-off
/// ([MW01] §3.2, discrete Noether).
#[test]
fn spring_dumbbell_conserves_angular_momentum_and_the_energy_with_the_spring() {
    let (run, _dir) = run_text(&dumbbell_text(), &["--steps", "2000"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert!(s["energy_not_conserved"].is_null());
    let e0 = number(&s, "energy.initial");
    assert!((e0 - 1.121875).abs() < 1e-14, "initial energy {e0}");
    let error = number(&s, "energy.max_rel_error");
    assert!(error < 1e-3, "energy error {error:e}");
    let drift = angular_momentum_drift(&s);
    assert!(drift < 1e-12, "angular momentum drift {drift:e}");
}

/// A damper between the same bodies: the run says the energy is not conserved and why, the
/// angular momentum is still conserved (the damper acts along its line), the energy column
/// falls, and the energy balance accounts for the fall: `E_N − E_0 = W + D` with `W` the
/// dampers' work (negative) and the unaccounted `D` a method error, smaller by about 4 when `h`
/// halves (order 2 over a fixed time).
#[test]
fn a_damper_makes_energy_not_conserved_and_the_energy_fall() {
    let text = dumbbell_text().replace(
        "[initial.a]",
        "[[system.damper]]\nbodies = [\"a\", \"b\"]\nat = [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]]\n\
         coefficient = 2.0\n\n[initial.a]",
    );
    let (run, _dir) = run_text(&text, &["--steps", "2000"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(s["energy_not_conserved"], "dampers act");
    assert!(s["energy"]["max_rel_error"].is_null());
    assert!(
        run.stdout.contains("balance (dampers act)"),
        "{}",
        run.stdout
    );
    let balance = |s: &serde_json::Value, key: &str| s["energy_balance"][key].as_f64().unwrap();
    let (work, change, defect) = (
        balance(&s, "total_work"),
        balance(&s, "energy_change"),
        balance(&s, "total_defect"),
    );
    assert!(work < -0.1, "the dampers take energy out: {work}");
    assert!(
        (change - work - defect).abs() < 1e-12,
        "{change} {work} {defect}"
    );
    assert!(defect.abs() < 1e-2 * work.abs(), "{defect} of {work}");
    assert_eq!(s["energy_balance"]["steps"], 2000);
    // The same time with h/2: the unaccounted part falls by about 4.
    let finer = text.replace("h = 0.005", "h = 0.0025");
    let (run2, _dir2) = run_text(&finer, &["--steps", "4000"]);
    assert_eq!(run2.code, 0, "{}", run2.stderr);
    let ratio = defect / balance(&run2.summary(), "total_defect");
    println!("dampers: work {work:.6}, unaccounted {defect:.3e}, ratio at h/2 {ratio:.3}");
    assert!((3.0..5.0).contains(&ratio), "defect ratio {ratio}");
    let drift = angular_momentum_drift(&s);
    assert!(drift < 1e-12, "angular momentum drift {drift:e}");
    let energy = run.trajectory().values("energy").unwrap().to_vec();
    let (first, last) = (energy[0], energy[energy.len() - 1]);
    assert!(last < 0.5 * first, "energy {first} → {last}");
}

/// Runs `text` and checks exit 2 with every fragment in the message.
fn refused(text: &str, fragments: &[&str]) {
    let (run, _dir) = run_text(text, &[]);
    assert_eq!(run.code, 2, "exit code; stderr:\n{}", run.stderr);
    for f in fragments {
        assert!(
            run.stderr.contains(f),
            "message lacks {f:?}:\n{}",
            run.stderr
        );
    }
}

#[test]
fn bad_springs_and_dampers_are_refused_with_their_messages() {
    let base = dumbbell_text();
    let damper = "[[system.damper]]\nbodies = [\"a\", \"b\"]\nat = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]\n\
                  coefficient = 1.0\n\n[initial.a]";
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            base.replace("bodies = [\"a\", \"b\"]", "bodies = [\"a\", \"c\"]"),
            vec!["spring #1 names an unknown body `c`", "\"a\", \"b\"", "^"],
        ),
        (
            base.replace(
                "at = [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]]",
                "at = [[0.1, 0.0, 0.0]]",
            ),
            vec!["`at` must be two vectors of three numbers", "^"],
        ),
        (
            base.replace("stiffness = 50.0", "stiffness = -50.0"),
            vec![
                "the stiffness of a spring must be zero or positive, not -50",
                "^",
            ],
        ),
        (
            base.replace("rest_length = 1.0", "rest_length = -1.0"),
            vec!["the rest_length of a spring must be zero or positive, not -1"],
        ),
        (
            base.replace("stiffness = 50.0\n", ""),
            vec!["spring #1 has no `stiffness`"],
        ),
        (
            base.replace("stiffness = 50.0", "stiffness = 50.0\nstifness = 1.0"),
            vec!["stifness", "^"],
        ),
        (
            base.replace("[initial.a]", &damper.replace("1.0\n", "-1.0\n")),
            vec![
                "the coefficient of a damper must be zero or positive, not -1",
                "^",
            ],
        ),
        (
            base.replace("[initial.a]", &damper.replace("\"b\"", "\"ground\", \"x\"")),
            vec!["`bodies` names 3 sides; a damper joins two"],
        ),
        (
            base.replace("[initial.a]", &damper.replace("coefficient", "coeff")),
            vec!["coeff", "^"],
        ),
        (
            base.replace("bodies = [\"a\", \"b\"]", "bodies = [\"a\", \"a\"]"),
            vec!["a spring joins two different bodies"],
        ),
    ];
    for (text, fragments) in cases {
        refused(&text, &fragments);
    }
}

#[test]
fn a_spring_without_bodies_is_refused() {
    let text = "[system]\n[[system.spring]]\nbodies = [\"ground\", \"a\"]\n\
                at = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]\nstiffness = 1.0\n\
                [integrator]\nmethod = \"trapezoid\"\nh = 0.01\nsteps = 10\n";
    refused(text, &["need bodies: the file has no [[system.body]]"]);
}

const SPRING: &str = "[[system.spring]]
name = \"link\"
bodies = [\"a\", \"b\"]
at = [[0.1, 0.0, 0.0], [-0.1, 0.0, 0.0]]
stiffness = 50.0
rest_length = 1.0
";

/// The dumbbell's spring written instead as `potential = "…"` over the bodies' entries,
/// `U = ½k(‖p_b − p_a‖ − ℓ₀)²` with `p = x + R X` spelled out in `a_x`, `a_R11`, …: the bodies'
/// moments and forces then come from automatic differentiation of the expression, the
/// spring's from its closed form, and the two runs agree to round-off over 2000 steps (every
/// column of every row, 1e-9), energies included.
#[test]
fn a_potential_over_the_bodies_entries_moves_them_as_the_spring_does() {
    let base = dumbbell_text()
        .replace("t_end = 20.0", "steps = 2000")
        .replace("every = 10", "every = 1\nplots = false");
    assert!(base.contains(SPRING));
    let written = base.replace(SPRING, "").replace(
        "name = \"spring_dumbbell\"\n",
        "name = \"spring_dumbbell\"\nparameters = { k = 50.0, l0 = 1.0 }\n\
         potential = \"0.5*k*(sqrt((b_x - 0.1*b_R11 - a_x - 0.1*a_R11)^2 \
         + (b_y - 0.1*b_R21 - a_y - 0.1*a_R21)^2 + (b_z - 0.1*b_R31 - a_z - 0.1*a_R31)^2) - l0)^2\"\n",
    );
    let (spring, _d1) = run_text(&base, &[]);
    let (potential, _d2) = run_text(&written, &[]);
    assert_eq!(
        (spring.code, potential.code),
        (0, 0),
        "{}{}",
        spring.stderr,
        potential.stderr
    );
    let (a, b) = (spring.trajectory(), potential.trajectory());
    let names: Vec<String> = a.names().map(str::to_owned).collect();
    assert_eq!(names, b.names().map(str::to_owned).collect::<Vec<_>>());
    let mut worst: f64 = 0.0;
    for name in &names {
        let (x, y) = (a.values(name).unwrap(), b.values(name).unwrap());
        for (u, v) in x.iter().zip(y) {
            worst = worst.max((u - v).abs());
        }
    }
    println!("spring against the written potential: max difference {worst:.2e}");
    assert!(worst <= 1e-9, "{worst:e}");
    let e0 = number(&potential.summary(), "energy.initial");
    assert!((e0 - 1.121875).abs() < 1e-12, "E0 = {e0}");
    let bad = written.replace("- l0)^2\"", "- l0)^2 + t\"");
    let (run, _d3) = run_text(&bad, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    assert!(run.stderr.contains("unknown name `t`"), "{}", run.stderr);
    assert!(run.stderr.contains("not `t`"), "{}", run.stderr);
}
