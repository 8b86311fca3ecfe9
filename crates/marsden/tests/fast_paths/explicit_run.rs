//! The explicit run loop ([`Integrator::advance`], `marsden::separable::explicit`) takes the same steps as
//! repeated [`Integrator::step`], bit for bit, counts the same work, and on a blow-up keeps the
//! last finite state and names the failing step. [`simulate`] uses it between stored samples
//! when its observer does not watch every step, without changing the trajectory.

// Tests may unwrap.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::SamplesOnly;
use marsden::error::{StepError, StepFailure};
use std::ops::ControlFlow;

use marsden::discrete::rules::{Composition, CompositionScheme};
use marsden::systems::{HenonHeiles, Kepler, NBody};
use marsden::{
    DiscreteAction, Error, Integrator, Lagrangian, MassMatrix, Rule, RunOptions, Scalar, State,
    Structure, Termination, TimeGrid, Trajectory, Trapezoid, simulate,
};

fn kepler_start() -> State {
    let (q, p) = Kepler::pericentre(0.6);
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

fn nbody_start() -> (NBody, State) {
    let mut system = NBody::new(vec![1.0, 1e-3, 2e-3]);
    system.softening = 0.01;
    let q = vec![0.0, 0.0, 0.0, 1.0, 0.0, 0.1, -1.5, 0.2, 0.0];
    let p = vec![0.0, -3e-3, 0.0, 0.0, 1e-3, 0.0, 2e-4, -1.6e-3, 0.0];
    (system, State { t: 0.0, q, p })
}

/// What a run leaves: the state, the gradients counted and the last step's offsets.
type Outcome = (State, usize, Vec<f64>);

/// `steps` single steps, with the time rewritten to the grid as `simulate` does.
fn by_steps<A: DiscreteAction>(action: A, start: &State, h: f64, steps: usize) -> Outcome {
    let mut integrator = Integrator::new(action);
    let mut s = start.clone();
    for k in 1..=steps {
        integrator.step(&mut s, h).unwrap();
        s.t = start.t + k as f64 * h;
    }
    let offsets = integrator.stage_offsets().to_vec();
    (s, integrator.statistics().potential_gradients, offsets)
}

/// The same steps in chunks of `chunk` by `advance`.
fn by_advance<A: DiscreteAction>(
    action: A,
    start: &State,
    h: f64,
    steps: usize,
    chunk: usize,
) -> Outcome {
    let mut integrator = Integrator::new(action);
    assert!(integrator.is_explicit());
    let mut s = start.clone();
    let mut done = 0;
    while done < steps {
        let n = chunk.min(steps - done);
        integrator.advance(&mut s, h, n).unwrap();
        done += n;
    }
    assert_eq!(integrator.statistics().explicit_steps, steps);
    let offsets = integrator.stage_offsets().to_vec();
    (s, integrator.statistics().potential_gradients, offsets)
}

fn assert_same_bits(a: &State, b: &State) {
    let bits = |s: &State| -> Vec<u64> { s.q.iter().chain(&s.p).map(|x| x.to_bits()).collect() };
    assert_eq!(bits(a), bits(b), "runs differ: {a:?} against {b:?}");
}

/// Same state, same gradient count, and the same offsets of the last step (which the
/// symplecticity certificate and the discrete momentum maps read).
fn assert_same_runs(a: &Outcome, b: &Outcome) {
    assert_same_bits(&a.0, &b.0);
    assert_eq!(a.1, b.1, "gradients");
    assert_eq!(a.2, b.2, "offsets of the last step");
}

#[test]
fn advance_equals_repeated_steps_bit_for_bit() {
    // Kepler (fixed-size loop, n = 2), Hénon–Heiles (n = 2), N-body (n = 9: slice loop) and a
    // composition (repeated composed steps): one gradient per step plus one to start, whatever
    // the chunking.
    let kepler = || Trapezoid.discretize(Kepler::default());
    let a = by_steps(kepler(), &kepler_start(), 0.01, 3000);
    assert_eq!(a.1, 3001);
    for chunk in [1, 2, 7, 3000] {
        assert_same_runs(
            &a,
            &by_advance(kepler(), &kepler_start(), 0.01, 3000, chunk),
        );
    }
    let hh_start = State {
        t: 0.0,
        q: vec![0.1, -0.2],
        p: vec![0.3, 0.25],
    };
    let hh = || Trapezoid.discretize(HenonHeiles::default());
    assert_same_runs(
        &by_steps(hh(), &hh_start, 0.1, 500),
        &by_advance(hh(), &hh_start, 0.1, 500, 500),
    );
    let (system, start) = nbody_start();
    assert_same_runs(
        &by_steps(Trapezoid.discretize(system.clone()), &start, 0.01, 400),
        &by_advance(Trapezoid.discretize(system), &start, 0.01, 400, 64),
    );
    let composed =
        || Composition::new(Trapezoid, CompositionScheme::Suzuki4).discretize(Kepler::default());
    assert_same_runs(
        &by_steps(composed(), &kepler_start(), 0.05, 200),
        &by_advance(composed(), &kepler_start(), 0.05, 200, 50),
    );
}

/// `V = −q⁴`: the particle is pushed out ever harder and leaves the floats in finite time.
#[derive(Debug, Clone)]
struct Runaway;
impl Lagrangian for Runaway {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        v[0] * v[0] * 0.5 + q[0].powi(4)
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![1.0]),
        }
    }
}

#[test]
fn a_blow_up_keeps_the_last_finite_state_and_names_the_step() {
    let start = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![0.0],
    };
    let h = 0.1;
    // Where single steps fail: the reference for the step index and the last good state.
    let mut one = Integrator::new(Trapezoid.discretize(Runaway));
    let mut s1 = start.clone();
    let failed_at = loop {
        let k = one.statistics().steps;
        if one.step(&mut s1, h).is_err() {
            break k;
        }
        s1.t = (k + 1) as f64 * h;
    };
    assert!(failed_at > 3, "the run should take a few steps first");
    let mut run = Integrator::new(Trapezoid.discretize(Runaway));
    let mut s2 = start.clone();
    let err = run.advance(&mut s2, h, 1000).unwrap_err();
    match err {
        Error::Step(StepFailure {
            step,
            t,
            cause: StepError::NonFinite { .. },
        }) => {
            assert_eq!(step, failed_at);
            assert!((t - failed_at as f64 * h).abs() < 1e-12, "t = {t}");
        }
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert_same_bits(&s1, &s2);
    assert!(s2.q[0].is_finite() && s2.p[0].is_finite());
    assert_eq!(run.statistics().steps, failed_at);
    assert_eq!(run.statistics().failed_steps, 1);
}

/// `simulate` with nobody watching each step (chunks between samples) and with a watcher
/// (single steps) store the same samples, bit for bit; a failure keeps the last good state.
#[test]
fn simulate_in_chunks_stores_the_same_samples() {
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let options = RunOptions { stride: 64 };
    let run = |watch: bool| -> Trajectory {
        let mut integrator = Integrator::new(Trapezoid.discretize(Kepler::default()));
        if watch {
            let mut seen = 0;
            let mut observer = |_: &marsden::StepView<'_>| {
                seen += 1;
                ControlFlow::Continue(())
            };
            let t = simulate(
                &mut integrator,
                kepler_start(),
                &grid,
                &options,
                &mut observer,
            );
            assert_eq!(seen, 1000);
            t
        } else {
            simulate(&mut integrator, kepler_start(), &grid, &options, &mut ())
        }
    };
    let (chunked, single) = (run(false), run(true));
    // An observer that does not watch every step sees only the stored samples (after step
    // 64, 128, …, 1000): proof that the steps between samples ran in one loop.
    let mut samples_only = SamplesOnly(0);
    let mut integrator = Integrator::new(Trapezoid.discretize(Kepler::default()));
    simulate(
        &mut integrator,
        kepler_start(),
        &grid,
        &options,
        &mut samples_only,
    );
    assert_eq!(samples_only.0, chunked.len() - 1);
    assert_eq!(samples_only.0, 16);
    assert_eq!(chunked.step_indices, single.step_indices);
    assert_eq!(chunked.times, single.times);
    for i in 0..chunked.len() {
        assert_eq!(chunked.q(i), single.q(i));
        assert_eq!(chunked.p(i), single.p(i));
    }
    assert_eq!(chunked.statistics, single.statistics);
    let start = State {
        t: 0.0,
        q: vec![1.0],
        p: vec![0.0],
    };
    let grid = TimeGrid::new(0.0, 0.1, 1000).unwrap();
    let mut integrator = Integrator::new(Trapezoid.discretize(Runaway));
    let failed = simulate(&mut integrator, start, &grid, &options, &mut ());
    assert!(
        matches!(
            failed.termination,
            Termination::Failed(Error::Step(StepFailure {
                cause: StepError::NonFinite { .. },
                ..
            }))
        ),
        "{:?}",
        failed.termination
    );
    let last = failed.len() - 1;
    assert_eq!(failed.step_indices[last], failed.steps);
    assert!(failed.q(last)[0].is_finite());
}
