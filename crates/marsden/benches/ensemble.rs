//! An ensemble of 10⁴ pendulums: the same members on 1 and on 2 threads.
//!
//! `cargo bench -p marsden --bench ensemble`. Each iteration solves 10⁴ pendulums (initial
//! angles spread over 0.1 … 2.6 rad) for 100 midpoint steps each, storing only the first and
//! last states, with per-member energy diagnostics; the speed-up is the ratio of the two
//! medians (goal ≥ 1.8 on 2 cores). The results are checked identical before timing. Divan
//! times all 1-thread samples before the 2-thread ones, so on a machine whose load changes the
//! ratio drifts; `cargo run --release -p marsden --example ensemble_speedup` measures the same
//! ensemble in interleaved pairs and reports the median pair ratio.

use divan::Bencher;
use marsden::studies::ensemble;
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, Problem, RunOptions, SolveOptions, TimeGrid};

const MEMBERS: usize = 10_000;
const STEPS: usize = 100;

fn main() {
    divan::main();
}

fn problems() -> Vec<Problem<Pendulum>> {
    let Ok(grid) = TimeGrid::new(0.0, 0.05, STEPS) else {
        return Vec::new();
    };
    (0..MEMBERS)
        .filter_map(|k| {
            let q0 = 0.1 + 2.5 * k as f64 / MEMBERS as f64;
            Problem::new(Pendulum::default(), Initial::velocity(&[q0], &[0.0]), grid).ok()
        })
        .collect()
}

fn options() -> SolveOptions {
    SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    }
}

#[divan::bench(args = [1, 2], sample_count = 10)]
fn pendulums(bencher: Bencher, threads: usize) {
    let problems = problems();
    let options = options();
    let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(threads).build() else {
        return;
    };
    let Ok(serial) = rayon::ThreadPoolBuilder::new().num_threads(1).build() else {
        return;
    };
    let reference = serial.install(|| ensemble::solve(&problems, &Midpoint, &options));
    let here = pool.install(|| ensemble::solve(&problems, &Midpoint, &options));
    assert!(here == reference, "{threads} threads changed the results");
    bencher.bench_local(|| pool.install(|| ensemble::solve(&problems, &Midpoint, &options)));
}
