//! Samples at chosen times (`marsden::run::events::TimeSampler`): states between grid points
//! against the pendulum's closed form (reference case R7's system), their order of convergence,
//! grid times and the start sampled exactly, bad lists refused, and a sampler checkpointed
//! half-way resuming bit for bit.

use marsden::error::{Error, InputError};
use marsden::run::events::{Sample, SamplerCheckpoint, TimeSampler};
use marsden::special::pendulum::Pendulum as ExactPendulum;
use marsden::systems::Pendulum;
use marsden::{Midpoint, Problem, Termination};

use super::events::{options, pendulum};
use crate::common::{feed, loglog_slope};

/// Times that are no multiple of any step used below (irrational fractions of the run).
fn requested() -> Vec<f64> {
    (1..=7)
        .map(|j| j as f64 * std::f64::consts::E / 2.0)
        .collect()
}

/// Samples of the midpoint run of `problem` at `times`.
fn sample(problem: &Problem<Pendulum>, times: &[f64]) -> (marsden::Trajectory, Vec<Sample>) {
    let mut sampler = TimeSampler::new(problem.lagrangian(), times).unwrap();
    let run = problem
        .solve_with(&Midpoint, &options(), &mut sampler)
        .unwrap();
    (run, sampler.into_samples())
}

/// R7's system: the samples at seven times between grid points follow the closed-form
/// pendulum `θ(t)` (Jacobi elliptic functions) with an error that converges at the midpoint
/// rule's order 2 as h is halved (fitted over h = 0.1 … 0.0125) — the interpolant adds no
/// error of a lower order — and their momenta `p = FL(q, v) = θ̇` converge at order 2 too.
#[test]
fn r07_samples_between_grid_points_converge_at_order_two() {
    let exact = ExactPendulum::new(1.5, 0.0, 1.0).unwrap();
    let times = requested();
    let step_sizes: [f64; 4] = [0.1, 0.05, 0.025, 0.0125];
    let (mut q_errors, mut p_errors) = (Vec::new(), Vec::new());
    for &h in &step_sizes {
        let steps = (10.0 / h).ceil() as usize;
        let (run, samples) = sample(&pendulum(h, steps), &times);
        assert_eq!(run.termination, Termination::Completed);
        assert_eq!(samples.len(), times.len(), "h = {h}");
        let (mut worst_q, mut worst_p): (f64, f64) = (0.0, 0.0);
        for (s, &t) in samples.iter().zip(&times) {
            assert_eq!(s.t, t);
            let (theta, theta_dot) = exact.state(t).unwrap();
            assert_eq!(s.step, (t / h).ceil() as usize, "the step t = {t} lies in");
            worst_q = worst_q.max((s.q[0] - theta).abs());
            worst_p = worst_p.max((s.p[0] - theta_dot).abs());
            assert_eq!(s.v, s.p, "unit mass: v = p");
        }
        assert!(worst_q < 0.1 * h, "h = {h}: θ error {worst_q:.3e}");
        q_errors.push(worst_q);
        p_errors.push(worst_p);
    }
    for (what, errors) in [("θ", &q_errors), ("p", &p_errors)] {
        let slope = loglog_slope(&step_sizes, errors);
        assert!(
            (slope - 2.0).abs() < 0.2,
            "{what}: order {slope} (errors {errors:?})"
        );
    }
}

/// At grid times (and the start) the samples are the run's stored states, bit for bit; between
/// two grid points on a stretch where θ falls, the sample lies between the two stored states.
#[test]
fn grid_times_and_the_start_are_the_states_themselves() {
    let h = 0.125;
    let problem = pendulum(h, 80);
    // Multiples of 1/8 are exact in binary: t₀ + k h hits them to the bit.
    let times = [0.0, 0.125, 1.0, 2.5, 10.0];
    let (run, samples) = sample(&problem, &times);
    let stored = problem.solve(&Midpoint, &options()).unwrap();
    assert_eq!(samples.len(), times.len());
    for s in &samples {
        let k = (s.t / h) as usize;
        assert_eq!(s.step, k);
        assert_eq!(stored.times[k], s.t);
        assert_eq!(
            s.q[0].to_bits(),
            stored.positions[k].to_bits(),
            "q at {}",
            s.t
        );
        assert_eq!(
            s.p[0].to_bits(),
            stored.momenta[k].to_bits(),
            "p at {}",
            s.t
        );
    }
    assert_eq!(run.termination, Termination::Completed);
    // Between two grid points, θ lies between the neighbouring states' on a monotone stretch.
    let (_, between) = sample(&problem, &[0.3]);
    let (a, b) = (stored.positions[2], stored.positions[3]);
    assert!(
        between[0].q[0] < a && between[0].q[0] > b,
        "{a} > {} > {b}",
        between[0].q[0]
    );
}

/// Times before the start and after the end are never reached; an empty list samples nothing.
#[test]
fn times_outside_the_run_are_not_sampled() {
    let problem = pendulum(0.1, 10);
    let (_, samples) = sample(&problem, &[-1.0, 0.55, 1.0, 7.0]);
    let t: Vec<f64> = samples.iter().map(|s| s.t).collect();
    assert_eq!(t.len(), 2);
    assert_eq!(t[0], 0.55);
    // The last grid time, t₀ + 10 h = 1 in floating point: the state itself.
    assert_eq!(t[1], 1.0);
    let (_, none) = sample(&problem, &[]);
    assert!(none.is_empty());
}

/// Times that are not finite, repeated or decreasing are refused, naming the offending value.
#[test]
fn unordered_or_non_finite_times_are_refused() {
    let lagrangian = Pendulum::default();
    for (times, bad) in [
        (vec![1.0, 0.5], 0.5),
        (vec![1.0, 1.0], 1.0),
        (vec![0.0, f64::INFINITY], f64::INFINITY),
    ] {
        let error = TimeSampler::new(&lagrangian, &times).unwrap_err();
        let Error::Input(InputError::InvalidOption { name, value, .. }) = error else {
            panic!("{error:?}")
        };
        assert_eq!((name, value), ("times", bad));
    }
}

/// A sampler checkpointed half-way (through postcard's bytes), restored into a fresh one and
/// shown the rest of the run takes the same samples, to the bit, as one that saw it all —
/// including a requested time in the step right after the checkpoint.
#[test]
fn a_sampler_resumed_from_its_checkpoint_samples_the_same_bits() {
    let h = 0.05;
    let problem = pendulum(h, 200);
    let run = problem.solve(&Midpoint, &options()).unwrap();
    let half = 100;
    let times = [0.33, 5.0 + 0.4 * h, 7.77, 9.99];
    let sampler = || TimeSampler::new(problem.lagrangian(), &times).unwrap();
    let mut whole = sampler();
    feed(&mut whole, &run, 0..201);
    assert_eq!(whole.samples().len(), 4);

    let mut first = sampler();
    feed(&mut first, &run, 0..half + 1);
    let bytes = postcard::to_allocvec(&first.checkpoint()).unwrap();
    let checkpoint: SamplerCheckpoint = postcard::from_bytes(&bytes).unwrap();
    let mut resumed = sampler();
    resumed.restore(&checkpoint).unwrap();
    feed(&mut resumed, &run, half + 1..201);
    assert_eq!(first.samples().len(), 1);
    let bits = |samples: &[Sample]| -> Vec<(u64, u64, u64)> {
        (samples.iter())
            .map(|s| (s.t.to_bits(), s.q[0].to_bits(), s.p[0].to_bits()))
            .collect()
    };
    assert_eq!(bits(resumed.samples()), bits(whole.samples()));
}
