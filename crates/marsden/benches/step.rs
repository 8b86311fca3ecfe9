//! One step of each rule on the pendulum, the double pendulum and Kepler (issue "Core").
//!
//! `cargo bench -p marsden --bench step`; `scripts/bench.sh` runs it next to `verlet.c` and
//! prints the ratios. Each iteration is one call of `Integrator::step` on a running trajectory
//! (Newton tolerance 1e-12, the default), so predictor and convergence behave as in a real run.

use divan::Bencher;
use marsden::systems::{DoublePendulum, Kepler, Pendulum};
use marsden::{
    DiscreteAction, GeneralizedMidpoint, Integrator, Midpoint, Rule, State, SymmetrizedMidpoint,
    Trapezoid,
};

// Shows allocations per step in divan's output (the steps allocate nothing).
#[global_allocator]
static ALLOC: divan::AllocProfiler = divan::AllocProfiler::system();

fn main() {
    divan::main();
}

/// Steps timed together in one sample. Divan sizes samples by itself, and when an early
/// iteration is slow (a cold cache) it settles on one step per sample: each ~300 ns sample then
/// carries the timer's 20 ns precision and its overhead, and the double pendulum's median came
/// out at 430–520 ns in runs where 64 steps per sample give 270 ns. Fixed for every step row.
const STEPS_PER_SAMPLE: u32 = 64;

fn bench_steps<A: DiscreteAction>(bencher: Bencher, action: A, start: State, h: f64) {
    let mut integrator = Integrator::new(action);
    let mut state = start;
    // Warm the predictor's history so each timed step is a steady-state step.
    for _ in 0..8 {
        if integrator.step(&mut state, h).is_err() {
            return;
        }
    }
    bencher.bench_local(|| {
        let _ = divan::black_box(integrator.step(&mut state, h));
    });
}

fn pendulum() -> State {
    State {
        t: 0.0,
        q: vec![1.5],
        p: vec![0.0],
    }
}

fn double_pendulum() -> State {
    State {
        t: 0.0,
        q: vec![1.0, 0.5],
        p: vec![0.0, 0.0],
    }
}

fn kepler() -> State {
    let (q, p) = Kepler::pericentre(0.6);
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

macro_rules! rules {
    ($name:ident, $system:expr, $start:expr, $h:expr) => {
        mod $name {
            use super::*;

            #[divan::bench(sample_size = STEPS_PER_SAMPLE)]
            fn midpoint(b: Bencher) {
                bench_steps(b, Midpoint.discretize($system), $start, $h);
            }

            #[divan::bench(sample_size = STEPS_PER_SAMPLE)]
            fn trapezoid(b: Bencher) {
                bench_steps(b, Trapezoid.discretize($system), $start, $h);
            }

            #[divan::bench(sample_size = STEPS_PER_SAMPLE)]
            fn alpha_quarter(b: Bencher) {
                bench_steps(
                    b,
                    GeneralizedMidpoint { alpha: 0.25 }.discretize($system),
                    $start,
                    $h,
                );
            }

            #[divan::bench(sample_size = STEPS_PER_SAMPLE)]
            fn symmetrized_quarter(b: Bencher) {
                bench_steps(
                    b,
                    SymmetrizedMidpoint { alpha: 0.25 }.discretize($system),
                    $start,
                    $h,
                );
            }
        }
    };
}

rules!(pendulum_h005, Pendulum::default(), pendulum(), 0.05);
rules!(
    double_pendulum_h001,
    DoublePendulum::default(),
    double_pendulum(),
    0.01
);
rules!(kepler_h001, Kepler::default(), kepler(), 0.01);

/// Steps per iteration of the run benchmarks; `scripts/bench_table.py` divides by it.
const RUN: usize = 1000;

/// `RUN` steps per iteration by [`Integrator::advance`]: the bare loop that `verlet.c` times
/// (for explicit steps one loop, no per-step dispatch; otherwise repeated steps).
fn bench_run<A: DiscreteAction>(bencher: Bencher, action: A, start: State, h: f64) {
    let mut integrator = Integrator::new(action);
    let mut state = start;
    if integrator.advance(&mut state, h, 8).is_err() {
        return;
    }
    bencher.bench_local(|| {
        let _ = divan::black_box(integrator.advance(&mut state, h, RUN));
    });
}

/// Runs of 1000 steps (per-step time = median / 1000).
macro_rules! runs {
    ($name:ident, $system:expr, $start:expr, $h:expr) => {
        mod $name {
            use super::*;

            #[divan::bench]
            fn trapezoid(b: Bencher) {
                bench_run(b, Trapezoid.discretize($system), $start, $h);
            }

            #[divan::bench]
            fn midpoint(b: Bencher) {
                bench_run(b, Midpoint.discretize($system), $start, $h);
            }
        }
    };
}

runs!(pendulum_h005_run1000, Pendulum::default(), pendulum(), 0.05);
runs!(kepler_h001_run1000, Kepler::default(), kepler(), 0.01);
