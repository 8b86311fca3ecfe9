//! `[output] times`: the states at chosen times in `samples.csv` (R7's pendulum against its
//! closed form, at the method's order; grid times exactly the trajectory's rows), observables
//! at the samples, `.npy`, a run that stops before the last time, and bad lists refused with a
//! caret.

use std::path::{Path, PathBuf};

use marsden::special::pendulum::Pendulum as ExactPendulum;

use crate::util::{column, marsden, number};

/// The pendulum `L = ½θ̇² + cos θ` released from θ₀ = 1.5 at rest (R7's system), midpoint
/// rule, with `output` appended to its `[output]` table.
fn pendulum(h: &str, t_end: &str, output: &str) -> String {
    format!(
        "[system]\ncoordinates = [\"theta\"]\nlagrangian = \"0.5*theta_dot^2 + cos(theta)\"\n\
         [initial]\nq = [1.5]\nv = [0.0]\n\
         [integrator]\nmethod = \"midpoint\"\nh = {h}\nt_end = {t_end}\ntolerance = 1e-14\n\
         [output]\nplots = false\n{output}\n"
    )
}

/// `text` written as `name` in a fresh directory (kept alive by the returned guard).
fn file(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn read_samples(out: &Path) -> marsden_io::Table {
    marsden_io::read_csv(out.join("samples.csv")).unwrap()
}

/// R7's system through the file: samples at π, 5.55 and 11.1 (between grid points for every
/// h below) follow the closed-form θ(t), θ̇(t) with errors converging at the midpoint rule's
/// order 2 (h = 1/32 … 1/128, fitted slope 2 ± 0.2); t = 0 and t = 2 (grid times: multiples of
/// a power of two) are the trajectory's own rows, bit for bit; the summary counts five of five.
#[test]
fn r07_samples_follow_the_closed_form_at_order_two_and_grid_times_are_rows() {
    let exact = ExactPendulum::new(1.5, 0.0, 1.0).unwrap();
    let steps: [f64; 3] = [1.0 / 32.0, 1.0 / 64.0, 1.0 / 128.0];
    let mut errors = Vec::new();
    for &h in &steps {
        let text = pendulum(&h.to_string(), "12", "times = [0, 2, \"pi\", 5.55, 11.1]");
        let (_dir, path) = file("pendulum.toml", &text);
        let run = marsden("run", &path, &[]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        let s = run.summary();
        assert_eq!(number(&s, "samples.requested"), 5.0);
        assert_eq!(number(&s, "samples.taken"), 5.0);
        assert!(
            run.stdout.contains("5 requested time(s) sampled"),
            "{}",
            run.stdout
        );
        let samples = read_samples(&run.out);
        let (t, q, p) = (
            column(&samples, "t"),
            column(&samples, "q_theta"),
            column(&samples, "p_theta"),
        );
        assert_eq!(t, [0.0, 2.0, std::f64::consts::PI, 5.55, 11.1]);
        let trajectory = run.trajectory();
        let (tt, tq, tp) = (
            column(&trajectory, "t"),
            column(&trajectory, "q_theta"),
            column(&trajectory, "p_theta"),
        );
        for (j, grid_time) in [(0, 0.0), (1, 2.0)] {
            let k = (grid_time / h) as usize;
            assert_eq!(tt[k], grid_time);
            assert_eq!(
                (q[j].to_bits(), p[j].to_bits()),
                (tq[k].to_bits(), tp[k].to_bits())
            );
        }
        let worst = [2, 3, 4]
            .iter()
            .map(|&j| {
                let (theta, theta_dot) = exact.state(t[j]).unwrap();
                (q[j] - theta).abs().max((p[j] - theta_dot).abs())
            })
            .fold(0.0, marsden::numerics::dense::max_or_nan);
        assert!(worst < 0.2 * h, "h = {h}: error {worst:.3e}");
        errors.push(worst);
    }
    let x: Vec<f64> = steps.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let slope = marsden::analysis::diagnostics::least_squares_slope(&x, &y);
    assert!(
        (slope - 2.0).abs() < 0.2,
        "order {slope} (errors {errors:?})"
    );
}

/// The observables are columns of the samples, evaluated at the sampled state: the energy
/// `½θ̇² − cos θ` of each row from its own `q`, `p` (unit mass: θ̇ = p), to round-off.
#[test]
fn observables_are_evaluated_at_the_samples() {
    let output = "times = [0.7, 1.9, 3.3]\nobservables = { E = \"0.5*theta_dot^2 - cos(theta)\" }";
    let (_dir, path) = file("pendulum.toml", &pendulum("0.05", "4", output));
    let run = marsden("run", &path, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let samples = read_samples(&run.out);
    let names: Vec<&str> = samples.columns().iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["t", "q_theta", "p_theta", "E"]);
    let (q, p, e) = (
        column(&samples, "q_theta"),
        column(&samples, "p_theta"),
        column(&samples, "E"),
    );
    for j in 0..3 {
        let expected = 0.5 * p[j] * p[j] - q[j].cos();
        assert!(
            (e[j] - expected).abs() < 1e-15,
            "E = {} against {expected}",
            e[j]
        );
        // The energy is conserved to the run's O(h²) error: about 1e-3 here.
        assert!((e[j] + 1.5f64.cos()).abs() < 5e-3, "E = {}", e[j]);
    }
    let s = run.summary();
    let columns = s["output"]["sample_columns"].as_array().unwrap();
    assert_eq!(columns.len(), 4);
}

/// With `format = "npy"` the samples are `samples.npy`, a 2 × 3 matrix (`t, q_θ, p_θ`), the same
/// numbers as the CSV of the same run.
#[test]
fn npy_samples_are_the_csv_samples() {
    let csv = pendulum("0.05", "4", "times = [0.7, 3.3]");
    let npy = pendulum("0.05", "4", "times = [0.7, 3.3]\nformat = \"npy\"");
    let (_a, csv_path) = file("csv.toml", &csv);
    let (_b, npy_path) = file("npy.toml", &npy);
    let (csv_run, npy_run) = (
        marsden("run", &csv_path, &[]),
        marsden("run", &npy_path, &[]),
    );
    assert_eq!(npy_run.code, 0, "{}", npy_run.stderr);
    let files = npy_run.summary()["output"]["files"].to_string();
    assert!(files.contains("samples.npy"), "{files}");
    let columns = ["t", "q_theta", "p_theta"].map(str::to_owned);
    let layout = marsden_io::Layout::new(vec![marsden_io::Group::vector("samples", columns)]);
    let from_npy = marsden_io::read_npy_dir(&npy_run.out, &layout.unwrap()).unwrap();
    let from_csv = read_samples(&csv_run.out);
    for name in ["t", "q_theta", "p_theta"] {
        assert_eq!(column(&from_npy, name), column(&from_csv, name), "{name}");
    }
}

/// `exact_times = true` with gauss-2: the samples at π and 5.55 are, to the bit, the last rows
/// of the same file run to `t_end = "pi"` and `t_end = 5.55` (whose last steps are the shorter
/// ones the samples were reached by), the trajectory is byte for byte the one without
/// `exact_times`, and the summary and the console say how the times were reached.
#[test]
fn exact_times_are_the_ends_of_runs_stopping_there() {
    let gauss = |t_end: &str, output: &str| {
        pendulum("0.1", t_end, output).replace("\"midpoint\"", "\"gauss-2\"")
    };
    let run_of = |text: String| {
        let (dir, path) = file("pendulum.toml", &text);
        let run = marsden("run", &path, &[]);
        assert_eq!(run.code, 0, "{}", run.stderr);
        (dir, run)
    };
    let (_d1, exact) = run_of(gauss("12", "times = [\"pi\", 5.55]\nexact_times = true"));
    let (_d2, read) = run_of(gauss("12", "times = [\"pi\", 5.55]"));
    let s = exact.summary();
    assert_eq!(s["samples"]["reached_by"], "step");
    assert_eq!(read.summary()["samples"]["reached_by"], "interpolant");
    assert!(
        exact
            .stdout
            .contains("2 requested time(s) sampled by steps of their own size"),
        "{}",
        exact.stdout
    );
    let trajectory =
        |run: &crate::util::Run| std::fs::read(run.out.join("trajectory.csv")).unwrap();
    assert_eq!(
        trajectory(&exact),
        trajectory(&read),
        "the run is unchanged"
    );
    let samples = read_samples(&exact.out);
    let interpolated = read_samples(&read.out);
    for (row, t_end) in ["pi", "5.55"].into_iter().enumerate() {
        let (_d, ended) = run_of(gauss(&format!("\"{t_end}\""), ""));
        let last = marsden_io::read_csv(ended.out.join("trajectory.csv")).unwrap();
        let end = column(&last, "t").len() - 1;
        for name in ["t", "q_theta", "p_theta"] {
            let stored = column(&last, name);
            assert_eq!(
                column(&samples, name)[row],
                stored[end],
                "{name} at t = {t_end}"
            );
        }
        let off = (column(&interpolated, "p_theta")[row] - column(&samples, "p_theta")[row]).abs();
        assert!(
            off > 0.0 && off < 1e-3,
            "the interpolant's momentum differs a little: {off:e}"
        );
    }
}

/// A run stopped by an event at T/4 ≈ 1.825 reaches one of the times 1, 2, 3: the summary and
/// the console say one of three, and `samples.csv` has one row.
#[test]
fn a_run_that_stops_early_says_how_many_times_it_reached() {
    let text = pendulum("0.05", "4", "times = [1, 2, 3]")
        + "[[events]]\nname = \"bottom\"\nwhen = \"theta\"\ndirection = \"down\"\naction = \"stop\"\n";
    let (_dir, path) = file("pendulum.toml", &text);
    let run = marsden("run", &path, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let s = run.summary();
    assert_eq!(number(&s, "samples.taken"), 1.0);
    assert_eq!(number(&s, "samples.requested"), 3.0);
    assert!(
        run.stdout.contains("1 of 3 requested times sampled"),
        "{}",
        run.stdout
    );
    assert_eq!(column(&read_samples(&run.out), "t"), [1.0]);
}

/// Bad lists and systems without an interpolant: exit 2, the reason, a caret on the value, and
/// nothing written.
#[test]
fn bad_times_are_refused_with_a_caret() {
    let rigid = "[system]\nrigid_body = { inertia = [2.0, 1.0, 0.5] }\n\
        [initial]\nPi = [0.1, 1.0, 0.1]\n\
        [integrator]\nmethod = \"trapezoid\"\nh = 0.01\nsteps = 10\n[output]\ntimes = [0.05]\n";
    let cases = [
        (
            pendulum("0.05", "4", "times = [1, 0.5]"),
            "the time 0.5 is not after the one before it, 1",
            "[1, 0.5]",
        ),
        (
            pendulum("0.05", "4", "times = [0, \"2*pi\"]"),
            "the time 6.283185307179586 is outside the run, from t0 = 0 to 4",
            "[0, \"2*pi\"]",
        ),
        (
            pendulum("0.05", "4", "times = [1, \"t\"]"),
            "not a constant expression",
            "\"t\"",
        ),
        (
            rigid.to_owned(),
            "`times` cannot be sampled for a rigid body",
            "[0.05]",
        ),
        (
            pendulum("0.05", "4", "exact_times = true"),
            "`exact_times = true` needs the times to reach: `times` is not given",
            "true",
        ),
    ];
    for (text, message, written) in cases {
        let (_dir, path) = file("bad.toml", &text);
        let run = marsden("run", &path, &[]);
        assert_eq!(run.code, 2, "{message}: {}", run.stderr);
        assert!(run.stderr.contains(message), "{message}: {}", run.stderr);
        assert!(run.stderr.contains(written), "{}", run.stderr);
        assert!(run.stderr.contains('^'), "a caret: {}", run.stderr);
        assert!(!run.out.exists(), "nothing written");
    }
}
