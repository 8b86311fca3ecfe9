//! `[[events]]` and `[output] observables` end to end: crossing times against closed forms
//! (R7, R10), the order of their error, a run stopped by an event, observables against the
//! same expressions computed from the stored columns, and every bad input refused.

use std::path::PathBuf;

use crate::util::{Run, column, marsden, number};
use marsden::special::elliptic::ellip_k;
use marsden_io::Table;

/// Writes `text` to `name` in a directory of its own (kept alive by the returned guard).
fn problem(name: &str, text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// `marsden run` on `text`, asserting exit status 0.
fn run_text(text: &str) -> Run {
    let (_dir, path) = problem("problem.toml", text);
    let run = marsden("run", &path, &["--no-progress"]);
    assert_eq!(run.code, 0, "stderr:\n{}\n{text}", run.stderr);
    run
}

fn events(run: &Run) -> Table {
    marsden_io::read_csv(run.out.join("events.csv")).unwrap()
}

/// The pendulum `L = ½θ̇² + cos θ` released from rest at θ₀ = 1.5, every zero of θ recorded,
/// with the midpoint rule at step `h` up to t = 22 (three periods).
fn pendulum(h: f64) -> String {
    format!(
        "[system]
coordinates = [\"theta\"]
parameters = {{ m = 1.0, l = 1.0, g = 1.0 }}
lagrangian = \"0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)\"
[initial]
q = [1.5]
v = [0.0]
[integrator]
method = \"midpoint\"
h = {h}
t_end = 22.0
tolerance = 1e-14
[[events]]
name = \"bottom\"
when = \"theta\"
direction = \"both\"
[output]
every = 100
plots = false
"
    )
}

/// R7: the pendulum's period from rest at θ₀ is T = 4K(k²), k = sin(θ₀/2) (`ω = √(g/l) = 1`);
/// θ = 0 at t = T/4 + jT/2. The crossing times located in a midpoint run differ from these by
/// the method's phase error, O(h²): the largest error over six crossings, at h = 0.04, 0.02,
/// 0.01, 0.005, falls with a fitted log–log slope of 2 ± 0.2.
#[test]
fn r07_pendulum_crossing_times_converge_at_order_two_for_midpoint() {
    let period = 4.0 * ellip_k((0.75f64).sin().powi(2)).unwrap();
    let steps = [0.04, 0.02, 0.01, 0.005];
    let mut errors = Vec::new();
    for h in steps {
        let run = run_text(&pendulum(h));
        let table = events(&run);
        let t = column(&table, "t");
        assert_eq!(t.len(), 6, "h = {h}: crossings {t:?}");
        assert_eq!(number(&run.summary(), "events.bottom"), 6.0);
        let error = (t.iter().enumerate())
            .map(|(j, t)| (t - (0.25 + 0.5 * j as f64) * period).abs())
            .fold(0.0, marsden::numerics::dense::max_or_nan);
        errors.push(error);
    }
    let order = slope(&steps, &errors);
    assert!(
        (order - 2.0).abs() <= 0.2,
        "order {order}, errors {errors:?}"
    );
    // The phase error of midpoint, not the location, dominates: at h = 0.005 it is small.
    assert!(errors[3] < 1e-4, "{errors:?}");
}

/// R7's turning points, with events that read the velocity: `θ̇` directly and through an
/// observable `w = "theta_dot"`. Released from rest at θ₀ = 1.5, θ̇ = 0 at t = jT/2
/// (T = 4K(k²), k = sin(θ₀/2)): six of them up to t = 22. The detector computes the velocities
/// at every step only for events whose `when` reads them, itself or through an observable; a
/// wrong reading would show `when` NaN and fail the run. At h = 0.01 the midpoint's phase
/// error keeps each located time within h/10 of the closed form (the order is fitted in the
/// core's tests), and both events find the same times.
#[test]
fn r07_turning_point_events_read_the_velocity_directly_and_through_an_observable() {
    let period = 4.0 * ellip_k((0.75f64).sin().powi(2)).unwrap();
    let text = pendulum(0.01).replace(
        "[[events]]
name = \"bottom\"
when = \"theta\"",
        "[[events]]
name = \"turn\"
when = \"theta_dot\"
[[events]]
name = \"turn_w\"
when = \"w\"",
    ) + "observables = { w = \"theta_dot\" }\n";
    let run = run_text(&text);
    assert_eq!(number(&run.summary(), "events.turn"), 6.0);
    assert_eq!(number(&run.summary(), "events.turn_w"), 6.0);
    let table = events(&run);
    let (event, t) = (column(&table, "event"), column(&table, "t"));
    for which in [0.0, 1.0] {
        let times: Vec<f64> = (t.iter().zip(event))
            .filter(|(_, e)| **e == which)
            .map(|(t, _)| *t)
            .collect();
        assert_eq!(times.len(), 6, "{times:?}");
        for (j, t) in times.iter().enumerate() {
            let exact = (j + 1) as f64 * period / 2.0;
            assert!(
                (t - exact).abs() < 1e-3,
                "event {which}: t = {t}, jT/2 = {exact}"
            );
        }
    }
}

/// Least-squares slope of `log e` against `log h`.
fn slope(h: &[f64], e: &[f64]) -> f64 {
    let x: Vec<f64> = h.iter().map(|h| h.ln()).collect();
    let y: Vec<f64> = e.iter().map(|e| e.ln()).collect();
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// R10: Kepler with e = 0.6 from the pericentre, period 2π. `r ṙ = x ẋ + y ẏ` rises through
/// zero at each pericentre: the stop event ends the run at the first one after the start
/// (t = 2π), at the pericentre (0.4, 0). The midpoint's error after one period at
/// h = 2π/1000 is 2.1e-2 in the state (R10, item 4), so about 5e-4 at h = 1e-3 (order 2),
/// which at the pericentre speed 2 is 3e-4 in time.
#[test]
fn r10_a_stop_event_ends_a_kepler_orbit_at_its_first_pericentre() {
    let text = "[system]
builtin = \"kepler\"
parameters = { mu = 1.0 }
[initial]
q = [0.4, 0.0]
p = [0.0, 2.0]
[integrator]
method = \"midpoint\"
h = 0.001
steps = 20000
tolerance = 1e-14
[[events]]
name = \"pericentre\"
when = \"x*x_dot + y*y_dot\"
direction = \"up\"
action = \"stop\"
[output]
plots = false
every = 50
";
    let run = run_text(text);
    let s = run.summary();
    assert_eq!(s["status"], "stopped by event pericentre", "{s}");
    assert_eq!(s["events"]["pericentre"], 1);
    assert!(
        run.stdout.contains("stopped     by event pericentre"),
        "{}",
        run.stdout
    );
    let table = events(&run);
    let t = column(&table, "t")[0];
    let two_pi = std::f64::consts::TAU;
    assert!((t - two_pi).abs() < 3e-4, "t = {t}, 2π = {two_pi}");
    // The run ends with the step the event lies in.
    let steps = number(&s, "steps");
    assert_eq!(steps, (t / 0.001).ceil(), "t = {t}");
    let (x, y) = (column(&table, "q_x")[0], column(&table, "q_y")[0]);
    assert!((x - 0.4).abs() < 1e-5 && y.abs() < 1e-3, "({x}, {y})");
    // The last row of the trajectory is the end of that step.
    let trajectory = run.trajectory();
    let last = *column(&trajectory, "t").last().unwrap();
    assert!(last >= t && last - t < 0.001, "{last} vs {t}");
}

/// Observables are columns after the state, equal to the same expressions computed from the
/// stored `q` and `p` columns (the velocity `θ̇ = p/(m l²)`), and the Hamiltonian observable
/// equals the run's own energy column `⟨p, v⟩ − L`.
#[test]
fn observables_are_the_same_expressions_of_the_stored_columns() {
    let text = "[system]
coordinates = [\"theta\"]
parameters = { m = 2.0, l = 0.5, g = 9.81 }
lagrangian = \"0.5*m*l^2*theta_dot^2 + m*g*l*cos(theta)\"
[initial]
q = [1.0]
v = [0.5]
[integrator]
h = 0.01
steps = 500
[output]
plots = true
observables = { x = \"l*sin(theta)\", w = \"theta_dot\", H = \"0.5*p_theta^2/(m*l^2) - m*g*l*cos(theta)\" }
";
    let run = run_text(text);
    let s = run.summary();
    let columns: Vec<&str> = (s["output"]["columns"].as_array().unwrap().iter())
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(
        columns,
        ["t", "q_theta", "p_theta", "energy", "x", "w", "H"]
    );
    let table = run.trajectory();
    let (q, p, e) = (
        column(&table, "q_theta"),
        column(&table, "p_theta"),
        column(&table, "energy"),
    );
    let (m, l, g) = (2.0f64, 0.5f64, 9.81f64);
    for (k, &q) in q.iter().enumerate() {
        let x = l * q.sin();
        assert!((column(&table, "x")[k] - x).abs() <= 1e-15, "row {k}");
        let w = p[k] / (m * l * l);
        assert!((column(&table, "w")[k] - w).abs() <= 1e-14 * w.abs().max(1.0));
        let h = 0.5 * p[k] * p[k] / (m * l * l) - m * g * l * q.cos();
        assert!((column(&table, "H")[k] - h).abs() <= 1e-13 * h.abs().max(1.0));
        assert!((column(&table, "H")[k] - e[k]).abs() <= 1e-13 * h.abs().max(1.0));
    }
    assert!(run.out.join("observables.png").exists());
}

/// The Hénon–Heiles section example: about 2000 crossings of x = 0 upward, all on x = 0 to
/// the root finder's tolerance (Brent stops within 4ε·t in time, so |x| ≤ 4ε·t·|ẋ| with
/// ẋ = p_x), with x rising; the section is drawn.
#[test]
fn the_henon_heiles_section_example_records_its_crossings() {
    let path = crate::util::repo_root().join("examples/henon_heiles_section.toml");
    let run = marsden("run", &path, &["--no-progress"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = events(&run);
    let (t, x, px) = (
        column(&table, "t"),
        column(&table, "q_x"),
        column(&table, "p_x"),
    );
    assert!((1900..2200).contains(&x.len()), "{} crossings", x.len());
    for k in 0..x.len() {
        let bound = 4.0 * f64::EPSILON * t[k] * px[k];
        assert!(x[k].abs() <= bound, "x = {} at t = {}", x[k], t[k]);
    }
    assert!(px.iter().all(|p| *p > 0.0));
    assert!(run.out.join("section.png").exists());
    let files = run.summary()["output"]["files"].to_string();
    assert!(
        files.contains("events.csv") && files.contains("section.png"),
        "{files}"
    );
}

/// With `format = "npy"` the records go to `events.npy` (a `records × (2 + 2n)` array, its
/// columns in `summary.json`): the same numbers, bit for bit, as `events.csv` of the same run in
/// CSV; the section is drawn from them.
#[test]
fn with_npy_output_the_records_are_events_npy_with_the_csv_numbers() {
    let path = crate::util::repo_root().join("examples/henon_heiles_section.toml");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("steps = 260000", "steps = 40000");
    let csv = run_text(&text);
    let npy = run_text(&text.replace("[output]\n", "[output]\nformat = \"npy\"\n"));
    let array = marsden_io::read_npy(npy.out.join("events.npy")).unwrap();
    let table = events(&csv);
    let names = npy.summary()["output"]["event_columns"].clone();
    let names: Vec<String> = serde_json::from_value(names).unwrap();
    assert_eq!(names, ["event", "t", "q_x", "q_y", "p_x", "p_y"]);
    assert_eq!(array.shape, [table.n_rows() as u64, 6]);
    assert!(table.n_rows() > 100, "{} records", table.n_rows());
    for (j, name) in names.iter().enumerate() {
        let from_csv = column(&table, name);
        let from_npy: Vec<f64> = (0..table.n_rows()).map(|i| array.data[6 * i + j]).collect();
        assert_eq!(from_csv, from_npy.as_slice(), "{name}");
    }
    assert!(!npy.out.join("events.csv").exists());
    assert!(npy.out.join("section.png").exists());
    let files = npy.summary()["output"]["files"].to_string();
    assert!(files.contains("events.npy"), "{files}");
}

const HEAD: &str = "[system]
coordinates = [\"x\"]
parameters = { k = 1.0 }
lagrangian = \"0.5*x_dot^2 - 0.5*k*x^2\"
[initial]
q = [1.0]
v = [0.0]
[integrator]
h = 0.1
steps = 10
";

/// Each bad input: exit status 2, the message with a caret under the value at fault, nothing
/// written.
#[test]
fn bad_events_and_observables_exit_2_with_a_caret_and_write_nothing() {
    let cases = [
        (
            "[[events]]\nname = \"e\"\nwhen = \"x - zz\"\n",
            "in [[events]] `e` when: unknown name `zz`",
            "zz",
        ),
        (
            "[[events]]\nname = \"e\"\nwhen = \"x\"\ndirection = \"sideways\"\n",
            "unknown direction `sideways`",
            "\"sideways\"",
        ),
        (
            "[[events]]\nname = \"e\"\nwhen = \"x\"\naction = \"pause\"\n",
            "unknown action `pause`",
            "\"pause\"",
        ),
        (
            "[[events]]\nname = \"e\"\nwhen = \"x\"\ncount = 0\n",
            "`count` must be at least 1 (got 0)",
            "0",
        ),
        (
            "[output]\nobservables = { r = \"x*w\" }\n",
            "in [output] observables.r: unknown name `w`",
            "w",
        ),
        (
            "[output]\nobservables = { x = \"2*x\" }\n",
            "the observable `x` shadows the coordinate `x`",
            "x",
        ),
    ];
    for (tail, message, underlined) in cases {
        let (_dir, path) = problem("bad.toml", &format!("{HEAD}{tail}"));
        let run = marsden("run", &path, &["--no-progress"]);
        assert_eq!(run.code, 2, "{tail}: {}", run.stderr);
        assert!(run.stderr.starts_with("error: "), "{}", run.stderr);
        assert!(run.stderr.contains(message), "{tail}: {}", run.stderr);
        let lines: Vec<&str> = run.stderr.lines().collect();
        let caret = lines.iter().position(|l| l.contains('^')).unwrap();
        let (source, marks) = (lines[caret - 1], lines[caret]);
        let start = marks.find('^').unwrap();
        let width = marks.matches('^').count();
        assert_eq!(&source[start..start + width], underlined, "{}", run.stderr);
        assert!(!run.out.exists(), "{tail}: something was written");
        assert!(run.stdout.is_empty());
    }
}
