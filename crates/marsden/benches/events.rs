//! The cost of watching a run for events (`marsden::run::events`): the pendulum's midpoint run
//! of 1000 steps (h = 0.05, θ₀ = 1.5) alone, with an observer that does nothing, with an event
//! detector on θ (falling through zero, recorded, declared not to read `v`: one evaluation of g
//! per step, the velocities only at the 6 steps where it fires) and with one on θ̇ (which reads
//! `v`: one inverse Legendre transform per step as well). The budget: the detector adds at most
//! 5 % to the run.
//!
//! Measured 2026-11-29 (shared 2-core machine under load, the two builds run in turn, medians
//! of 3 runs; instructions per step from callgrind, the machine has no hardware counters):
//!
//! | run | before (c1ec769) | after (022d3b6) | instructions/step (after) |
//! |---|---|---|---|
//! | plain | 85.7 µs | 87.4 µs | 1 066.6 |
//! | empty observer | 90.4 µs (+6 %) | 93.7 µs (+7 %) | 1 214.7 (+14 %) |
//! | detector on θ | 115.7 µs (+35 %; 1 514.5 instr., +42 %) | 108.6 µs (**+24 %**) | 1 418.6 (+33 %) |
//! | detector on θ̇ | – | 113.2 µs (+30 %) | 1 496.4 (+40 %) |
//!
//! Over the 5 % budget still: half of what is left is the run loop's cost of showing every
//! step to an observer (the empty observer's +14 % in instructions), the rest the detector's
//! own ≈ 200 instructions per step (the evaluation of g, two copies of the state, the sign
//! test), down from 300.
//!
//! 2026-11-29, 05cd011 (the every-step path steps by `Integrator::step`, small functions
//! inlined across crates), instructions per step (callgrind, 12 runs less 2, over 10 000
//! steps): plain 1 048.9, empty observer 1 157.7 (+10.4 %), detector on θ 1 361.5 (+29.8 %),
//! on θ̇ 1 440.3 (+37.3 %); the budget is still not met (BENCHMARKS.md, "Events and
//! checkpoints").
//!
//! 2026-11-30: the detector no longer needs the every-step path (it watches the steps inside
//! the stretches the run loop hands the stepper, `Observer::watch_steps`), so `with_event` runs
//! in one stretch like `plain`; the file runs' figures before and after are in BENCHMARKS.md
//! ("Events and checkpoints").
//!
//! `cargo bench -p marsden --bench events`

use divan::Bencher;
use marsden::run::events::{Direction, Event, EventDetector};
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, Problem, SolveOptions, TimeGrid};

fn main() {
    divan::main();
}

/// Steps of each run.
const RUN: usize = 1000;

fn problem() -> Option<Problem<Pendulum>> {
    let grid = TimeGrid::new(0.0, 0.05, RUN).ok()?;
    Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), grid).ok()
}

/// Only the first and last states stored, so the run loop's own work dominates.
fn options() -> SolveOptions {
    let mut options = SolveOptions::default();
    options.run.stride = usize::MAX;
    options
}

/// The run without a detector.
#[divan::bench]
fn plain(bencher: Bencher) {
    let Some(problem) = problem() else { return };
    let options = options();
    bencher.bench_local(|| divan::black_box(problem.solve(&Midpoint, &options)));
}

/// The same run, every step shown to an observer that does nothing (what any every-step
/// observer costs the loop).
#[divan::bench]
fn empty_observer(bencher: Bencher) {
    let Some(problem) = problem() else { return };
    let options = options();
    bencher.bench_local(|| {
        let mut observer = |_: &marsden::StepView<'_>| std::ops::ControlFlow::Continue(());
        divan::black_box(problem.solve_with(&Midpoint, &options, &mut observer))
    });
}

/// The same run with the event detector on θ, declared not to read `v`
/// ([`Event::without_velocity`]): one evaluation of g per step.
#[divan::bench]
fn with_event(bencher: Bencher) {
    let Some(problem) = problem() else { return };
    let options = options();
    let theta = |_t: f64, q: &[f64], _v: &[f64], _p: &[f64]| q[0];
    let events = vec![Event::record(theta, Direction::Down).without_velocity()];
    let Ok(mut detector) = EventDetector::new(problem.lagrangian(), events) else {
        return;
    };
    bencher.bench_local(|| {
        divan::black_box(problem.solve_with(&Midpoint, &options, &mut detector)).is_ok()
    });
}

/// The same run with an event on θ̇ (the turning points, falling through zero: 6 of them):
/// one evaluation of g and one inverse Legendre transform per step.
#[divan::bench]
fn with_velocity_event(bencher: Bencher) {
    let Some(problem) = problem() else { return };
    let options = options();
    let theta_dot = |_t: f64, _q: &[f64], v: &[f64], _p: &[f64]| v[0];
    let events = vec![Event::record(theta_dot, Direction::Down)];
    let Ok(mut detector) = EventDetector::new(problem.lagrangian(), events) else {
        return;
    };
    bencher.bench_local(|| {
        divan::black_box(problem.solve_with(&Midpoint, &options, &mut detector)).is_ok()
    });
}
