//! Ensembles: results in member order, independent of the number of threads, one
//! failing member reported without stopping the others.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use marsden::studies::ensemble::{self, Member, MemberFailure, MemberReport};
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, NewtonOptions, Problem, RunOptions, SolveOptions, TimeGrid};

type Outcome = Vec<Member<MemberReport, MemberFailure>>;

fn pendulums(count: usize, grid: TimeGrid) -> Vec<Problem<Pendulum>> {
    (0..count)
        .map(|k| {
            let q0 = 0.1 + 2.5 * k as f64 / count as f64;
            Problem::new(Pendulum::default(), Initial::velocity(&[q0], &[0.0]), grid).unwrap()
        })
        .collect()
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn ensemble_is_independent_of_thread_count() {
    let problems = pendulums(64, TimeGrid::new(0.0, 0.05, 400).unwrap());
    let options = SolveOptions {
        run: RunOptions { stride: 10 },
        ..SolveOptions::default()
    };
    let solve = || ensemble::solve(&problems, &Midpoint, &options);
    let one: Outcome = in_pool(1, solve);
    let two: Outcome = in_pool(2, solve);
    assert_eq!(
        one, two,
        "1 and 2 threads must give the same members, bit for bit"
    );
    for (k, member) in one.iter().enumerate() {
        assert_eq!(member.index, k);
        let report = member.result.as_ref().unwrap();
        assert_eq!(report.steps, 400);
        // 41 samples with stride 10 over 400 steps (the first and every 10th).
        assert_eq!(report.energy.samples, 41);
        assert!(
            report.energy.max_rel_error < 1e-2,
            "member {k}: {:?}",
            report.energy
        );
        // Each member is the run of its own problem alone.
        let alone = problems[k].solve(&Midpoint, &options).unwrap();
        assert_eq!(report.q, alone.q(alone.len() - 1));
    }
    // Members differ: they really ran their own initial conditions.
    assert_ne!(one[0].result, one[1].result);
}

#[test]
fn a_failing_member_does_not_stop_the_others() {
    // One Newton iteration per step: the pendulum at rest at the bottom needs none, the
    // swinging ones cannot converge in one and fail at their first step.
    let grid = TimeGrid::new(0.0, 0.05, 50).unwrap();
    let at_rest = Problem::new(Pendulum::default(), Initial::velocity(&[0.0], &[0.0]), grid);
    let mut problems = pendulums(3, grid);
    problems.insert(1, at_rest.unwrap());
    let options = SolveOptions {
        newton: NewtonOptions {
            max_iterations: 1,
            ..NewtonOptions::default()
        },
        ..SolveOptions::default()
    };
    let members = in_pool(2, || ensemble::solve(&problems, &Midpoint, &options));
    assert_eq!(members.len(), 4);
    let ok: Vec<bool> = members.iter().map(|m| m.result.is_ok()).collect();
    assert_eq!(ok, [false, true, false, false]);
    let failure = members[0].result.as_ref().unwrap_err();
    assert_eq!(failure.steps, 0);
    assert_eq!(failure.t, 0.0);
    assert!(failure.to_string().contains("after 0 steps"), "{failure}");
    assert_eq!(members[1].result.as_ref().unwrap().steps, 50);
}

#[test]
fn generic_members_keep_their_order_and_errors() {
    let members = in_pool(2, || {
        ensemble::run_indexed(1000, |k| if k % 7 == 3 { Err(k) } else { Ok(2 * k) })
    });
    for (k, m) in members.iter().enumerate() {
        assert_eq!(m.index, k);
        let expected = if k % 7 == 3 { Err(k) } else { Ok(2 * k) };
        assert_eq!(m.result, expected);
    }
}
