//! Samples reached by steps of their own size (`TimeSampler::by_steps`): each sample is bit for
//! bit the final state of the run asked to end at its time (`TimeGrid::ending_at`), the run
//! itself is bit for bit the run without the sampler, on every step path (the explicit
//! trapezoid, the separable midpoint Newton step, the general Newton path, gauss-2 with its
//! predictor, compensated summation); and against reference case R7's closed form the samples
//! of gauss-2 converge at its order 4 where the interpolant's momenta stop at 3.

use marsden::discrete::rules::Galerkin;
use marsden::run::events::{Sample, TimeSampler};
use marsden::special::pendulum::Pendulum as ExactPendulum;
use marsden::systems::Pendulum;
use marsden::{Initial, Midpoint, Problem, Rule, SolveOptions, Termination, TimeGrid, Trapezoid};

use super::events::options;
use crate::common::loglog_slope;

/// The pendulum `L = ½θ̇² + cos θ` released from θ₀ = 1.5 at rest on `grid`.
fn pendulum(grid: TimeGrid) -> Problem<Pendulum> {
    Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), grid).unwrap()
}

/// Times between the grid points of every `h` used below (irrational fractions of the run).
fn requested() -> Vec<f64> {
    (1..=5)
        .map(|j| j as f64 * std::f64::consts::E / 3.0)
        .collect()
}

/// The run of `rule` from 0 to 5 with steps of `h` and the samples at `times`, read off the
/// interpolant or reached by steps.
fn sampled<R: Rule>(
    rule: &R,
    h: f64,
    options: &SolveOptions,
    times: &[f64],
    by_steps: bool,
) -> (marsden::Trajectory, Vec<Sample>) {
    let problem = pendulum(TimeGrid::ending_at(0.0, 5.0, h).unwrap());
    let sampler = TimeSampler::new(problem.lagrangian(), times).unwrap();
    let mut sampler = match by_steps {
        true => sampler.by_steps(),
        false => sampler,
    };
    let run = problem.solve_with(rule, options, &mut sampler).unwrap();
    assert_eq!(run.termination, Termination::Completed);
    (run, sampler.into_samples())
}

/// The final `(q, p)` of the run of `rule` from 0 to `t_end` with steps of `h`.
fn end_at<R: Rule>(rule: &R, h: f64, options: &SolveOptions, t_end: f64) -> (f64, f64) {
    let problem = pendulum(TimeGrid::ending_at(0.0, t_end, h).unwrap());
    let run = problem.solve(rule, options).unwrap();
    let last = run.len() - 1;
    assert_eq!(run.t(last), t_end);
    (run.q(last)[0], run.p(last)[0])
}

/// Each sample = the end of the run that stops at its time, and the sampled run = the run
/// without samples, both to the bit, for `rule` with `options`.
fn check_bits<R: Rule>(rule: &R, options: &SolveOptions, what: &str) {
    let h = 0.05;
    let times = requested();
    let (run, samples) = sampled(rule, h, options, &times, true);
    let (plain, _) = sampled(rule, h, options, &[], false);
    assert_eq!(samples.len(), times.len(), "{what}");
    for (sample, &t) in samples.iter().zip(&times) {
        assert_eq!(sample.t, t);
        assert_eq!(
            sample.step,
            (t / h).ceil() as usize,
            "{what}: the step t = {t} lies in"
        );
        let (q, p) = end_at(rule, h, options, t);
        assert_eq!((sample.q[0], sample.p[0]), (q, p), "{what}: t = {t}");
        assert_eq!(sample.v, sample.p, "{what}: unit mass, v = p");
    }
    let last = run.len() - 1;
    assert_eq!(run.len(), plain.len());
    assert_eq!(
        (run.q(last), run.p(last)),
        (plain.q(last), plain.p(last)),
        "{what}: the steps aside leave the run unchanged"
    );
    assert_eq!(
        run.statistics.steps, plain.statistics.steps,
        "{what}: the steps aside are not counted as the run's"
    );
}

#[test]
fn samples_by_steps_are_the_ends_of_runs_stopping_there_on_every_step_path() {
    let fast = options();
    let general = SolveOptions {
        general_path: true,
        ..options()
    };
    let compensated = SolveOptions {
        compensated: true,
        ..options()
    };
    check_bits(&Trapezoid, &fast, "trapezoid (explicit)");
    check_bits(&Midpoint, &fast, "midpoint (separable Newton)");
    check_bits(&Midpoint, &general, "midpoint (general Newton)");
    check_bits(&Midpoint, &compensated, "midpoint (compensated)");
    check_bits(&Galerkin::gauss(2).unwrap(), &fast, "gauss-2 (predictor)");
}

/// R7's system with gauss-2 (order 4): the worst error of the samples at five times between
/// grid points, against the closed-form `θ(t)`, `θ̇(t)`, over h = 0.2 … 0.025. Reached by
/// steps, positions and momenta converge at order 4; read off the cubic Hermite interpolant,
/// the momenta (its derivative) converge at order 3 only.
#[test]
fn r07_gauss2_samples_by_steps_converge_at_order_four() {
    let exact = ExactPendulum::new(1.5, 0.0, 1.0).unwrap();
    let times = requested();
    let step_sizes: [f64; 4] = [0.2, 0.1, 0.05, 0.025];
    let gauss = Galerkin::gauss(2).unwrap();
    let worst = |samples: &[Sample]| {
        let (mut q, mut p): (f64, f64) = (0.0, 0.0);
        for s in samples {
            let (theta, theta_dot) = exact.state(s.t).unwrap();
            q = q.max((s.q[0] - theta).abs());
            p = p.max((s.p[0] - theta_dot).abs());
        }
        (q, p)
    };
    let (mut by_steps, mut interpolated) = (Vec::new(), Vec::new());
    for &h in &step_sizes {
        let (_, stepped) = sampled(&gauss, h, &options(), &times, true);
        let (_, read) = sampled(&gauss, h, &options(), &times, false);
        by_steps.push(worst(&stepped));
        interpolated.push(worst(&read));
    }
    let slope = |errors: &[(f64, f64)], pick: fn(&(f64, f64)) -> f64| {
        let errors: Vec<f64> = errors.iter().map(pick).collect();
        loglog_slope(&step_sizes, &errors)
    };
    let (q4, p4) = (slope(&by_steps, |e| e.0), slope(&by_steps, |e| e.1));
    let p3 = slope(&interpolated, |e| e.1);
    assert!((q4 - 4.0).abs() < 0.3, "by steps: θ order {q4:.3}");
    assert!((p4 - 4.0).abs() < 0.3, "by steps: p order {p4:.3}");
    assert!((p3 - 3.0).abs() < 0.3, "interpolant: p order {p3:.3}");
    let (last_steps, last_read) = (by_steps[3].1, interpolated[3].1);
    assert!(
        last_steps < 0.1 * last_read,
        "at h = 0.025 the stepped momenta are the better: {last_steps:.2e} vs {last_read:.2e}"
    );
}
