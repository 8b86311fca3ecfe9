//! End-to-end: what a sweep's table keeps — grids of two axes, the final state and momentum
//! maps of every member, the energy balance (not an energy error) of forced members, the
//! `.npy` table — and the sweep plot.

use crate::util::{SweepTable, marsden};

/// Writes `text` as a problem file in a fresh directory and runs it.
fn run_text(text: &str, extra: &[&str]) -> (tempfile::TempDir, crate::util::Run) {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("problem.toml");
    std::fs::write(&file, text).unwrap();
    let run = marsden("run", &file, extra);
    (dir, run)
}

const PENDULUM: &str = r#"
[system]
builtin = "pendulum"
parameters = { l = 1.0 }

[initial]
q = [0.5]
v = [0.0]

[integrator]
h = 0.05
steps = 200

[output]
plots = false
"#;

/// A grid of l × q[0]: every combination, the last axis fastest; each member's final state
/// equals (bit for bit) that member in a one-axis sweep over l at the same q[0].
#[test]
fn a_grid_of_two_axes_is_every_combination_with_its_final_state() {
    let grid = format!(
        "{PENDULUM}\n[sweep]\nparameter = \"l\"\nvalues = [0.5, 1.0, 2.0]\n\n[sweep.and]\n\
         initial = \"q[0]\"\nvalues = [0.2, 0.4]\n"
    );
    let (_d, run) = run_text(&grid, &["--threads", "2"]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.stdout.contains("l × q[0]"), "{}", run.stdout);
    let table = SweepTable::read(&run.out.join("sweep.csv"));
    assert_eq!(table.column("l"), [0.5, 0.5, 1.0, 1.0, 2.0, 2.0]);
    assert_eq!(table.column("q[0]"), [0.2, 0.4, 0.2, 0.4, 0.2, 0.4]);
    let one_axis = format!(
        "{}\n[sweep]\nparameter = \"l\"\nvalues = [0.5, 1.0, 2.0]\n",
        PENDULUM.replace("q = [0.5]", "q = [0.4]")
    );
    let (_e, line) = run_text(&one_axis, &[]);
    assert_eq!(line.code, 0, "{}", line.stderr);
    let line = SweepTable::read(&line.out.join("sweep.csv"));
    let grid_q: Vec<f64> = table
        .column("q_theta")
        .into_iter()
        .skip(1)
        .step_by(2)
        .collect();
    let grid_p: Vec<f64> = table
        .column("p_theta")
        .into_iter()
        .skip(1)
        .step_by(2)
        .collect();
    assert_eq!(grid_q, line.column("q_theta"));
    assert_eq!(grid_p, line.column("p_theta"));
    // The final state is a state, not a copy of the start: a short pendulum swings faster.
    assert!(grid_q.windows(2).all(|w| w[0] != w[1]), "{grid_q:?}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(run.out.join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["members"], 6);
    assert_eq!(summary["swept_columns"], serde_json::json!(["l", "q[0]"]));
}

/// Kepler with the rotation symmetry over a sweep of p_y: each row's J_Lz is the initial
/// angular momentum x·p_y − y·p_x = 0.4·p_y (closed form), and its drift is at round-off
/// (discrete Noether, MW01 Thm 1.3.3).
#[test]
fn each_member_keeps_its_momentum_map() {
    let text = std::fs::read_to_string(crate::util::fixture("kepler_symmetry.toml")).unwrap();
    let text = text
        .replace("steps = 3000", "steps = 600")
        .replace("plots = true", "plots = false")
        + "\n[sweep]\ninitial = \"p[1]\"\nvalues = [1.6, 1.8, 2.0]\n";
    let (_d, run) = run_text(&text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = SweepTable::read(&run.out.join("sweep.csv"));
    for (j, py) in table.column("J_Lz").iter().zip([1.6, 1.8, 2.0]) {
        assert!((j - 0.4 * py).abs() <= 1e-15, "J_Lz {j} for p_y {py}");
    }
    for drift in table.column("J_Lz_drift") {
        assert!(drift <= 1e-13, "drift {drift}");
    }
}

/// Reference case R12 swept over the damping c: a forced member's row has the discrete energy
/// balance (E_N − E_0 − total work at round-off), no energy error.
#[test]
fn a_forced_sweep_reports_the_energy_balance() {
    let text = std::fs::read_to_string(crate::util::fixture("r12_damped_midpoint.toml")).unwrap();
    let text = text.replace("steps = 1000", "steps = 200")
        + "\n[sweep]\nparameter = \"c\"\nvalues = [0.05, 0.1, 0.2]\n";
    let (_d, run) = run_text(&text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    let table = SweepTable::read(&run.out.join("sweep.csv"));
    assert!(
        !table.header.iter().any(|h| h.starts_with("energy")),
        "{:?}",
        table.header
    );
    let work = table.column("balance_total_work");
    assert!(
        work.iter().all(|w| *w < 0.0),
        "damping removes energy: {work:?}"
    );
    assert!(
        work.windows(2).all(|w| w[1] < w[0]),
        "more damping, more work: {work:?}"
    );
    for d in table.column("balance_total_defect") {
        assert!(d.abs() <= 1e-12, "total defect {d}");
    }
    for d in table.column("balance_max_defect") {
        assert!(d <= 1e-14, "max defect {d}");
    }
    assert!(run.stdout.contains("max defect"), "{}", run.stdout);
}

/// `format = "npy"`: the table is `sweep.npy` (members × columns, named in summary.json), with
/// the same numbers as the CSV; `marsden plot` draws the sweep plot from it.
#[test]
fn an_npy_sweep_writes_the_same_table_and_plots() {
    let sweep = "\n[sweep]\nparameter = \"l\"\nvalues = [0.5, 1.0, 2.0]\n";
    let csv = format!("{PENDULUM}{sweep}");
    let npy = csv.replace("plots = false", "plots = false\nformat = \"npy\"");
    let (_d, a) = run_text(&csv, &[]);
    let (_e, b) = run_text(&npy, &[]);
    assert_eq!(b.code, 0, "{}", b.stderr);
    assert!(!b.out.join("sweep.csv").exists());
    let array = marsden_io::read_npy(b.out.join("sweep.npy")).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(b.out.join("summary.json")).unwrap())
            .unwrap();
    let names: Vec<&str> = summary["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(array.shape, [3, names.len() as u64]);
    let table = SweepTable::read(&a.out.join("sweep.csv"));
    let width = names.len();
    for (j, name) in names.iter().enumerate().filter(|(_, n)| **n != "status") {
        let from_npy: Vec<u64> = (0..3)
            .map(|i| array.data[i * width + j].to_bits())
            .collect();
        let from_csv: Vec<u64> = table.column(name).iter().map(|x| x.to_bits()).collect();
        assert_eq!(from_npy, from_csv, "column {name}");
    }
    let plot = crate::util::marsden_in(b.out.as_path(), &["plot", "."]);
    assert!(
        plot.status.success(),
        "{}",
        String::from_utf8_lossy(&plot.stderr)
    );
    assert!(b.out.join("sweep.png").exists());
}

/// A sweep with plots on draws `sweep.png` itself.
#[test]
fn a_sweep_with_plots_draws_the_sweep_plot() {
    let text = format!(
        "{}\n[sweep]\nparameter = \"l\"\nvalues = [0.5, 1.0]\n",
        PENDULUM.replace("plots = false", "plots = true")
    );
    let (_d, run) = run_text(&text, &[]);
    assert_eq!(run.code, 0, "{}", run.stderr);
    assert!(run.out.join("sweep.png").exists(), "{}", run.stdout);
    assert!(run.stdout.contains("sweep.png"), "{}", run.stdout);
}

#[test]
fn a_value_swept_twice_is_refused() {
    let text = format!(
        "{PENDULUM}\n[sweep]\nparameter = \"l\"\nvalues = [0.5]\n\n[sweep.and]\n\
         parameter = \"l\"\nvalues = [1.0]\n"
    );
    rejected(&text, &["`l` is swept twice", "^"]);
}

#[test]
fn a_grid_beyond_the_member_limit_is_refused() {
    let text = format!(
        "{PENDULUM}\n[sweep]\nparameter = \"l\"\nrange = {{ start = 0.5, stop = 2.0, count = 10000 }}\n\n\
         [sweep.and]\ninitial = \"q[0]\"\nrange = {{ start = 0.1, stop = 1.0, count = 10000 }}\n"
    );
    rejected(&text, &["more than the limit of 1e7 sweep members"]);
}

/// Runs `text`, asserting exit status 2, each fragment in the message and nothing written.
fn rejected(text: &str, fragments: &[&str]) {
    let (_d, run) = run_text(text, &[]);
    assert_eq!(run.code, 2, "{}", run.stderr);
    for f in fragments {
        assert!(
            run.stderr.contains(f),
            "message lacks {f:?}:\n{}",
            run.stderr
        );
    }
    assert!(!run.out.exists(), "nothing may be written for a bad file");
}
