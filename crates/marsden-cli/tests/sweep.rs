//! End-to-end: `[sweep]` ensembles, `--shard i/n`, N-body initial data from a file, and the
//! bad input around them.

use crate::util::{SweepTable, assert_rejected_with, fixture, marsden, run_ok};

/// Eight pendulums released at rest from q₀ = 0.2 … 1.6: one row each, in order, with the
/// swept value; the midpoint rule's energy error is bounded and grows with the amplitude
/// (a larger swing sees a larger curvature of the potential at the same h).
#[test]
fn a_sweep_writes_one_row_per_member_in_order() {
    let run = run_ok("pendulum_sweep.toml", &["--threads", "2"]);
    let table = SweepTable::read(&run.out.join("sweep.csv"));
    let members = table.column("member");
    assert_eq!(members, (0..8).map(f64::from).collect::<Vec<_>>());
    let q0 = table.column("q[0]");
    for (k, q) in q0.iter().enumerate() {
        let expected = 0.2 + 0.2 * k as f64;
        assert!((q - expected).abs() < 1e-12, "member {k}: q0 {q}");
    }
    let steps = table.column("steps");
    assert!(steps.iter().all(|s| *s == 400.0), "{steps:?}");
    let energy = table.column("energy_max_rel_error");
    assert!(energy.iter().all(|e| *e > 0.0 && *e < 1e-2), "{energy:?}");
    assert!(energy[7] > energy[0], "{energy:?}");
    assert!(
        run.stdout.contains("sweep of q[0] over 8 members"),
        "{}",
        run.stdout
    );
}

/// The rows do not depend on the number of threads, and the shards of `--shard i/n` together
/// are the whole sweep, bit for bit.
#[test]
fn threads_and_shards_give_the_same_rows() {
    let one = run_ok("pendulum_sweep.toml", &["--threads", "1"]);
    let two = run_ok("pendulum_sweep.toml", &["--threads", "2"]);
    let read =
        |run: &crate::util::Run, file: &str| std::fs::read_to_string(run.out.join(file)).unwrap();
    assert_eq!(read(&one, "sweep.csv"), read(&two, "sweep.csv"));
    let whole = SweepTable::read(&one.out.join("sweep.csv"));
    let energy = whole.column("energy_max_rel_error");
    let mut seen = 0;
    for i in 0..3 {
        let shard = format!("{i}/3");
        let part = run_ok("pendulum_sweep.toml", &["--shard", &shard]);
        let table = SweepTable::read(&part.out.join(format!("sweep.shard-{i}-of-3.csv")));
        for (m, e) in table
            .column("member")
            .iter()
            .zip(table.column("energy_max_rel_error"))
        {
            let k = *m as usize;
            assert_eq!(k % 3, i, "shard {shard} ran member {k}");
            assert_eq!(e.to_bits(), energy[k].to_bits(), "member {k}");
            seen += 1;
        }
    }
    assert_eq!(seen, 8);
}

/// One member that cannot run (zero mass: a singular Legendre transform) is reported in its row; the others complete
/// and the exit status is 1.
#[test]
fn a_failing_member_is_reported_and_the_others_run() {
    let run = marsden("run", &fixture("pendulum_sweep_failing.toml"), &[]);
    assert_eq!(run.code, 1, "{}", run.stderr);
    let text = std::fs::read_to_string(run.out.join("sweep.csv")).unwrap();
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(rows.len(), 3, "{text}");
    assert!(rows[0].contains("completed"), "{text}");
    assert!(rows[1].contains("failed"), "{text}");
    assert!(rows[2].contains("completed"), "{text}");
    assert!(
        run.stderr.contains("1 of 3 members failed"),
        "{}",
        run.stderr
    );
}

#[test]
fn a_sweep_over_an_unknown_name_is_refused() {
    assert_rejected_with(
        "sweep_unknown_parameter.toml",
        &[],
        &["unknown parameter `lenght`", "parameters: m, l, g"],
    );
}

#[test]
fn an_empty_range_is_refused() {
    assert_rejected_with("sweep_empty_range.toml", &[], &["count"]);
}

#[test]
fn a_shard_outside_the_range_is_refused() {
    assert_rejected_with("../pendulum_sweep.toml", &["--shard", "3/3"], &["3/3"]);
    assert_rejected_with("../pendulum_sweep.toml", &["--shard", "1/0"], &["1/0"]);
}

#[test]
fn a_malformed_nbody_file_names_the_line() {
    assert_rejected_with(
        "nbody_malformed_file.toml",
        &[],
        &["three_bodies_malformed.txt", "line 4"],
    );
}

/// Initial data from a file: two planets on circular orbits (G M = 1, radii 1 and 2, speeds
/// 1 and 1/√2); Störmer–Verlet keeps the energy to O(h²) and the total linear momentum
/// (translation symmetry) to round-off.
#[test]
fn nbody_initial_data_come_from_the_file() {
    let run = run_ok("nbody_file.toml", &[]);
    let s = run.summary();
    let energy = crate::util::number(&s, "energy.max_rel_error");
    assert!(energy < 1e-4, "energy error {energy:e}");
    let traj = run.trajectory();
    // Body 2, the planet at radius 1 (period 2π), is at angle ≈ 20 rad at t = 20 (its
    // neighbour's pull and the star's recoil, mass ratio 1e-3, shift it slightly).
    let x2 = *crate::util::column(&traj, "q_x2").last().unwrap();
    let y2 = *crate::util::column(&traj, "q_y2").last().unwrap();
    let angle = y2.atan2(x2) - (20.0 - 6.0 * std::f64::consts::PI);
    assert!(angle.abs() < 0.05, "angle off by {angle}");
    assert!(((x2 * x2 + y2 * y2).sqrt() - 1.0).abs() < 0.01, "radius");
}
