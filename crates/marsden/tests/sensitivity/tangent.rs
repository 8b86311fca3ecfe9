//! Tangent maps against closed forms and structure: the midpoint oscillator's one-step matrix
//! (R1), the damped oscillator's (R12, discrete Lagrange–d'Alembert), and the symplecticity of
//! the `(q₀, p₀)` block over 10⁴ steps (Kepler, double pendulum; R17's certificate over a run).

use super::common::{integrator, state};
use crate::common::{assert_close, tight};
use marsden::analysis::certificate::symplectic_defect;
use marsden::discrete::rules::Galerkin;
use marsden::sensitivity::{
    TangentCheckpoint, TangentOptions, TangentSample, tangent, tangent_continued, tangent_watched,
};
use marsden::systems::{DampedOscillator, DoublePendulum, HarmonicOscillator, Kepler};
use marsden::{Integrator, Midpoint, Rule, Termination, TimeGrid, Trapezoid};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};

/// R1: the tangent map of one midpoint step of `q̈ = −q` with h = 0.1 is the Cayley matrix
/// [[399, 40], [−40, 399]]/401, and of ten steps its tenth power.
#[test]
fn r1_tangent_map_is_the_cayley_matrix_to_1e14() {
    let grid = TimeGrid::new(0.0, 0.1, 1).unwrap();
    let mut vi = integrator(Midpoint.discretize(HarmonicOscillator::default()));
    let t = tangent(
        &mut vi,
        state(&[0.3], &[-0.7]),
        &grid,
        &TangentOptions::default(),
    )
    .unwrap();
    let exact = [399.0 / 401.0, 40.0 / 401.0, -40.0 / 401.0, 399.0 / 401.0];
    for (k, e) in exact.iter().enumerate() {
        assert_close(
            t.jacobian[k],
            *e,
            1e-14,
            &format!("M[{}][{}]", k / 2, k % 2),
        );
    }
    // Ten steps: M¹⁰ (rotation by 10θ with cos θ = 399/401).
    let grid = TimeGrid::new(0.0, 0.1, 10).unwrap();
    let mut vi = integrator(Midpoint.discretize(HarmonicOscillator::default()));
    let t = tangent(
        &mut vi,
        state(&[1.0], &[0.0]),
        &grid,
        &TangentOptions { every: 5 },
    )
    .unwrap();
    let theta = (399.0f64 / 401.0).acos() * 10.0;
    let (c, s) = (theta.cos(), theta.sin());
    for (k, e) in [c, s, -s, c].iter().enumerate() {
        assert_close(
            t.jacobian[k],
            *e,
            1e-14,
            &format!("M¹⁰[{}][{}]", k / 2, k % 2),
        );
    }
    assert_eq!(
        t.samples.iter().map(|s| s.step).collect::<Vec<_>>(),
        [0, 5, 10]
    );
}

/// R12: the damped oscillator (m = k = 1, c = 0.1) with midpoint L_d and midpoint forces has the
/// one-step matrix [[401, 40], [−40, 397]]/403; the forced tangent map reproduces it.
#[test]
fn r12_forced_tangent_map_is_401_40_minus40_397_over_403() {
    let osc = DampedOscillator::default();
    let mut vi = Integrator::new(Midpoint.discretize(osc))
        .with_force(Midpoint.discretize_force(osc, 1))
        .with_options(tight())
        .unwrap();
    let grid = TimeGrid::new(0.0, 0.1, 1).unwrap();
    let t = tangent(
        &mut vi,
        state(&[0.4], &[0.2]),
        &grid,
        &TangentOptions::default(),
    )
    .unwrap();
    let exact = [401.0, 40.0, -40.0, 397.0];
    for (k, e) in exact.iter().enumerate() {
        assert_close(
            t.jacobian[k],
            e / 403.0,
            1e-14,
            &format!("M[{}][{}]", k / 2, k % 2),
        );
    }
}

/// The `(q₀, p₀)` block `M` of a conservative run of 10⁴ steps satisfies `MᵀJM = J` to 1e-10
/// relative to `‖M‖²` (the product of 10⁴ symplectic step Jacobians, R17).
#[test]
fn tangent_map_of_10k_steps_is_symplectic_kepler_and_double_pendulum() {
    let (q, p) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 0.01, 10_000).unwrap();
    let mut vi = integrator(Trapezoid.discretize(Kepler::default()));
    let t = tangent(&mut vi, state(&q, &p), &grid, &TangentOptions::default()).unwrap();
    let (abs, rel) = symplectic_defect(&t.state_block(), 2);
    // The shear of Kepler orbits makes M grow linearly in t; the rounding of MᵀJM is then
    // about ε‖M‖², so the absolute defect is that of the entries' size, not of the map.
    let size = t.state_block().iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    println!(
        "kepler / trapezoid, 10⁴ steps: max |M_ij| = {size:.2e}, |MᵀJM − J| = {abs:.2e}, \
         relative {rel:.2e}"
    );
    assert!(rel <= 1e-10, "kepler: relative defect {rel:e}");

    let grid = TimeGrid::new(0.0, 0.01, 10_000).unwrap();
    let mut vi = integrator(
        Galerkin::gauss(2)
            .unwrap()
            .discretize(DoublePendulum::default()),
    );
    let t = tangent(
        &mut vi,
        state(&[1.0, -0.5], &[0.3, 0.2]),
        &grid,
        &TangentOptions::default(),
    )
    .unwrap();
    let (abs, rel) = symplectic_defect(&t.state_block(), 2);
    println!("double pendulum / gauss-2, 10⁴ steps: |MᵀJM − J| = {abs:.2e}, relative {rel:.2e}");
    assert!(rel <= 1e-10, "double pendulum: relative defect {rel:e}");
}

/// A stop flag set from the watcher after 37 of 100 steps ends the tangent run there: it says
/// so ([`Termination::Stopped`]), keeps the state and Jacobian of step 37 — those of a 37-step
/// run, bit for bit — and keeps step 37 as its last sample.
#[test]
fn stop_flag_set_from_the_watcher_ends_the_tangent_run_with_the_steps_done() {
    let (q, p) = Kepler::pericentre(0.6);
    let start = state(&q, &p);
    let options = TangentOptions { every: 10 };
    let stop = AtomicBool::new(false);
    let mut seen = Vec::new();
    let watch = |k: usize| {
        seen.push(k);
        if k == 37 {
            stop.store(true, Ordering::Relaxed);
        }
        match stop.load(Ordering::Relaxed) {
            true => ControlFlow::Break(()),
            false => ControlFlow::Continue(()),
        }
    };
    let grid = TimeGrid::new(0.0, 0.01, 100).unwrap();
    let mut vi = integrator(Midpoint.discretize(Kepler::default()));
    let stopped = tangent_watched(&mut vi, start.clone(), &grid, &options, watch).unwrap();
    assert_eq!(stopped.termination, Termination::Stopped { steps: 37 });
    assert_eq!(seen, (1..=37).collect::<Vec<_>>());

    let grid = TimeGrid::new(0.0, 0.01, 37).unwrap();
    let mut vi = integrator(Midpoint.discretize(Kepler::default()));
    let done = tangent(&mut vi, start, &grid, &options).unwrap();
    assert_eq!(done.termination, Termination::Completed);
    assert_eq!(stopped.state, done.state);
    assert_eq!(stopped.jacobian, done.jacobian);
    let steps = |t: &marsden::sensitivity::Tangent| -> Vec<usize> {
        t.samples.iter().map(|s| s.step).collect()
    };
    assert_eq!(steps(&stopped), [0, 10, 20, 30, 37]);
    assert_eq!(steps(&stopped), steps(&done));
}

/// A tangent run checkpointed at step 70 ([`TangentCheckpoint::of`]), stopped at 83, and
/// continued from the checkpoint in a freshly built integrator ([`tangent_continued`]) gives
/// the uninterrupted run's samples after step 70 and its final state and Jacobian bit for bit
/// (Kepler, e = 0.6, midpoint: Newton's warm start is part of what is carried).
#[test]
fn a_tangent_run_continued_from_its_checkpoint_is_the_uninterrupted_run_bit_for_bit() {
    let (q, p) = Kepler::pericentre(0.6);
    let options = TangentOptions { every: 10 };
    let grid = TimeGrid::new(0.0, 0.01, 200).unwrap();
    let build = || integrator(Midpoint.discretize(Kepler::default()));
    let whole = tangent(&mut build(), state(&q, &p), &grid, &options).unwrap();

    let mut saved = None;
    let watch = |vi: &_, s: &TangentSample| {
        if s.step == 70 {
            saved = TangentCheckpoint::of(vi, s);
        }
        match s.step {
            83 => ControlFlow::Break(()),
            _ => ControlFlow::Continue(()),
        }
    };
    let mut first = Vec::new();
    // 2n = 4 columns: no parameters.
    let from = TangentSample::start(state(&q, &p), 4);
    let mut vi = build();
    let stopped = tangent_continued(&mut vi, from, &grid, &options, watch, &mut |s| {
        first.push(s.clone());
    })
    .unwrap();
    assert_eq!(stopped.termination, Termination::Stopped { steps: 83 });
    let checkpoint = saved.expect("the integrator carries a checkpoint");
    assert_eq!(checkpoint.step, 70);

    let mut fresh = build();
    marsden::sensitivity::SensitiveStep::restore_carried(&mut fresh, &checkpoint.integrator)
        .unwrap();
    let mut rest = Vec::new();
    let never = |_: &_, _: &TangentSample| ControlFlow::Continue(());
    let resumed = tangent_continued(
        &mut fresh,
        checkpoint.sample(),
        &grid,
        &options,
        never,
        &mut |s| rest.push(s.clone()),
    )
    .unwrap();
    assert_eq!(resumed.termination, Termination::Completed);
    assert_eq!(resumed.state, whole.state);
    assert_eq!(resumed.jacobian, whole.jacobian);
    let after: Vec<_> = whole
        .samples
        .iter()
        .filter(|s| s.step > 70)
        .cloned()
        .collect();
    assert_eq!(rest, after, "the samples after the checkpoint");
    assert_eq!(first[..8], whole.samples[..8], "the samples before it");
}
