//! The cost of watching a run for events (`marsden::run::events`): the pendulum's midpoint run
//! of 1000 steps (h = 0.05, θ₀ = 1.5) alone and with an event detector on θ (falling through
//! zero, recorded: it fires 6 times in the run, otherwise one evaluation of g and one inverse
//! Legendre transform per step). The budget: the detector adds at most 5 % to the run.
//!
//! Measured once (shared 2-core machine, medians): plain 85.6 µs, empty observer 89.1 µs
//! (+4 %), detector 109.5 µs (+28 %): over the 5 % budget, to be brought down.
//!
//! `flock /work/release.lock cargo bench -p marsden --bench events`

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
