//! Adjoint gradients against tangent runs: `dΛ/dx₀ = Σ_k ℓ_kᵀ S_k` computed backwards with
//! checkpoints agrees with the forward sensitivities to 1e-10, whatever the checkpoint spacing.

use super::common::{integrator, relative_distance, state};
use crate::common::tight;
use marsden::discrete::rules::Galerkin;
use marsden::sensitivity::{
    AdjointOptions, SensitiveStep, TangentOptions, adjoint, adjoint_watched, tangent,
};
use marsden::systems::{DampedDrivenPendulum, Kepler};
use marsden::{Integrator, Midpoint, Rule, State, Termination, TimeGrid};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// The loss cotangent of sample k: ℓ_k = Σ_i w_{ik} x_i²/2 on every 7th step (∇ℓ_k = w ∘ x_k).
fn cotangent(k: usize, x: &State, out: &mut [f64]) {
    if k.is_multiple_of(7) {
        let n = x.q.len();
        for (i, o) in out.iter_mut().enumerate() {
            let w = 1.0 + 0.1 * (i as f64) + 0.01 * ((k / 7) % 5) as f64;
            let xi = if i < n { x.q[i] } else { x.p[i - n] };
            *o += w * xi;
        }
    }
}

/// `Σ_k ∇ℓ_kᵀ S_k` from a tangent run that keeps every state.
fn forward_gradient<D: SensitiveStep>(stepper: &mut D, start: &State, grid: &TimeGrid) -> Vec<f64> {
    let run = tangent(stepper, start.clone(), grid, &TangentOptions { every: 1 }).unwrap();
    let (m, cols) = (2 * run.n, run.columns);
    let mut g = vec![0.0; cols];
    let mut cot = vec![0.0; m];
    for sample in &run.samples {
        cot.fill(0.0);
        cotangent(sample.step, &sample.state, &mut cot);
        for (c, gc) in g.iter_mut().enumerate() {
            *gc += (0..m)
                .map(|r| cot[r] * sample.jacobian[r * cols + c])
                .sum::<f64>();
        }
    }
    g
}

fn check_against_forward<D: SensitiveStep + Clone>(
    name: &str,
    make: impl Fn() -> D,
    start: &State,
    grid: &TimeGrid,
) {
    let forward = forward_gradient(&mut make(), start, grid);
    for every in [0, 1, 10, 64, grid.steps + 5] {
        let options = AdjointOptions {
            checkpoint_every: every,
        };
        let reverse = adjoint(&mut make(), start.clone(), grid, cotangent, &options).unwrap();
        let d = relative_distance(&reverse.gradient, &forward);
        println!(
            "{name}, checkpoint every {every}: {} checkpoints, segments of {}, relative distance {d:.2e}",
            reverse.checkpoints, reverse.segment
        );
        assert!(d <= 1e-10, "{name}, every {every}: relative distance {d:e}");
    }
}

/// Kepler e = 0.6, gauss-3, h = 0.01, 1000 steps: adjoint = forward to 1e-10 for several
/// checkpoint spacings (√K by default, every state, a few, a single segment).
#[test]
fn adjoint_equals_forward_kepler_gauss3() {
    let (q, p) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    check_against_forward(
        "kepler / gauss-3",
        || integrator(Galerkin::gauss(3).unwrap().discretize(Kepler::default())),
        &state(&q, &p),
        &grid,
    );
}

/// With discrete forces (damped driven pendulum, midpoint): adjoint = forward to 1e-10.
#[test]
fn adjoint_equals_forward_forced_pendulum() {
    let sys = DampedDrivenPendulum::default();
    let grid = TimeGrid::new(0.0, 0.05, 500).unwrap();
    check_against_forward(
        "damped driven pendulum / midpoint",
        || {
            Integrator::new(Midpoint.discretize(sys))
                .with_force(Midpoint.discretize_force(sys, 1))
                .with_options(tight())
                .unwrap()
        },
        &state(&[0.5], &[0.1]),
        &grid,
    );
}

/// Memory: the default schedule of 10⁵ steps holds ⌈K/m⌉ = 316 checkpoints (m = ⌈√K⌉ = 317) and one segment of m
/// states and Jacobians, not K.
#[test]
fn adjoint_memory_is_sqrt_k() {
    let (q, p) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 0.01, 100_000).unwrap();
    let mut vi = integrator(Midpoint.discretize(Kepler::default()));
    let g = adjoint(
        &mut vi,
        state(&q, &p),
        &grid,
        |k, x, out| {
            if k == 100_000 {
                out[0] += x.q[0];
            }
        },
        &AdjointOptions::default(),
    )
    .unwrap();
    assert_eq!(
        (g.checkpoints, g.segment),
        (100_000usize.div_ceil(317), 317)
    );
    assert!(g.gradient.iter().all(|x| x.is_finite()));
}

/// A stop flag set from the watcher ends the adjoint at once, in either sweep: it says so
/// ([`Termination::Stopped`] with the steps of work shown last), gives no gradient, and the
/// watcher saw every step of work up to there (`1 … K` forwards, `K + 1 … 2K` backwards); a
/// stop during the forward sweep leaves the state of a plain run of that many steps. A watcher
/// that never stops sees `1 … 2K` and changes nothing in the gradient.
#[test]
fn stop_flag_set_from_the_watcher_ends_the_adjoint_in_either_sweep() {
    let (q, p) = Kepler::pericentre(0.6);
    let start = state(&q, &p);
    let grid = TimeGrid::new(0.0, 0.01, 100).unwrap();
    let options = AdjointOptions::default();
    let make = || integrator(Midpoint.discretize(Kepler::default()));
    let run = |stop_at: usize| {
        let stop = AtomicBool::new(false);
        let mut seen = Vec::new();
        let watch = |k: usize| {
            seen.push(k);
            if k == stop_at {
                stop.store(true, Ordering::Relaxed);
            }
            match stop.load(Ordering::Relaxed) {
                true => ControlFlow::Break(()),
                false => ControlFlow::Continue(()),
            }
        };
        let g = adjoint_watched(
            &mut make(),
            start.clone(),
            &grid,
            cotangent,
            &options,
            watch,
        );
        (g.unwrap(), seen)
    };

    let (forward_stop, seen) = run(37);
    assert_eq!(forward_stop.termination, Termination::Stopped { steps: 37 });
    assert!(forward_stop.gradient.is_empty());
    assert_eq!(seen, (1..=37).collect::<Vec<_>>());
    let mut plain = start.clone();
    make().advance(&mut plain, grid.h, 37).unwrap();
    assert_eq!(forward_stop.state, plain);

    let (reverse_stop, seen) = run(150);
    assert_eq!(
        reverse_stop.termination,
        Termination::Stopped { steps: 150 }
    );
    assert!(reverse_stop.gradient.is_empty());
    assert_eq!(seen, (1..=150).collect::<Vec<_>>());

    let (whole, seen) = run(usize::MAX);
    let unwatched = adjoint(&mut make(), start, &grid, cotangent, &options).unwrap();
    assert_eq!(whole.termination, Termination::Completed);
    assert_eq!(seen, (1..=200).collect::<Vec<_>>());
    assert_eq!(whole, unwatched);
    assert_eq!(whole.gradient.len(), 4);
}
