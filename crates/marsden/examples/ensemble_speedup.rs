//! The speed-up of an ensemble on 2 threads over 1, measured in interleaved pairs.
//!
//! ```sh
//! cargo run --release -p marsden --features tools --example ensemble_speedup [PAIRS]
//! ```
//!
//! The ensemble is that of `benches/ensemble.rs`: 10⁴ pendulums (initial angles 0.1 … 2.6 rad),
//! 100 midpoint steps each, first and last states stored, energy diagnostics per member. The
//! divan bench times all 1-thread samples, then all 2-thread samples; on a shared machine whose
//! load changes over seconds, the two blocks can see different loads, and the ratio of their
//! medians drifts with it. Here each pair runs the 1-thread and the 2-thread ensemble back to
//! back, so both see the same load; the speed-up quoted is the median of the pair ratios
//! (and, for reference, the ratio of the fastest runs). `PAIRS` defaults to 21. The results
//! of both pools are checked identical.

use std::time::Instant;

use marsden::studies::ensemble::{self, Member, MemberFailure, MemberReport};
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, Problem, RunOptions, SolveOptions, TimeGrid};

const MEMBERS: usize = 10_000;
const STEPS: usize = 100;

type Results = Vec<Member<MemberReport, MemberFailure>>;

fn problems() -> Result<Vec<Problem<Pendulum>>, marsden::Error> {
    let grid = TimeGrid::new(0.0, 0.05, STEPS)?;
    (0..MEMBERS)
        .map(|k| {
            let q0 = 0.1 + 2.5 * k as f64 / MEMBERS as f64;
            Problem::new(Pendulum::default(), Initial::velocity(&[q0], &[0.0]), grid)
        })
        .collect()
}

/// Milliseconds of one ensemble on `pool`, and its results.
fn timed(pool: &rayon::ThreadPool, problems: &[Problem<Pendulum>]) -> (f64, Results) {
    let options = SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..SolveOptions::default()
    };
    let start = Instant::now();
    let results = pool.install(|| ensemble::solve(problems, &Midpoint, &options));
    (start.elapsed().as_secs_f64() * 1e3, results)
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let pairs: usize = match std::env::args().nth(1) {
        Some(arg) => arg.parse()?,
        None => 21,
    };
    if pairs == 0 {
        return Err("PAIRS must be at least 1".into());
    }
    let problems = problems()?;
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let two = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    // Warm-up, and the identity of the results.
    let (_, a) = timed(&one, &problems);
    let (_, b) = timed(&two, &problems);
    if a != b {
        return Err("the 2-thread ensemble differs from the 1-thread one".into());
    }
    let (mut t1, mut t2, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..pairs {
        let (x, _) = timed(&one, &problems);
        let (y, _) = timed(&two, &problems);
        t1.push(x);
        t2.push(y);
        ratios.push(x / y);
    }
    let fastest = |t: &[f64]| t.iter().copied().fold(f64::INFINITY, f64::min);
    let (f1, f2) = (fastest(&t1), fastest(&t2));
    println!("{MEMBERS} pendulums x {STEPS} midpoint steps, {pairs} interleaved pairs");
    println!(
        "1 thread : median {:.1} ms, fastest {f1:.1} ms",
        median(&mut t1)
    );
    println!(
        "2 threads: median {:.1} ms, fastest {f2:.1} ms",
        median(&mut t2)
    );
    println!(
        "speed-up : median of pair ratios {:.2}, fastest/fastest {:.2}",
        median(&mut ratios),
        f1 / f2
    );
    Ok(())
}
