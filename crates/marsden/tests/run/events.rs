//! Events located inside the step (`marsden::run::events`): crossing times against closed forms
//! (the pendulum's period 4K(k)/ω, reference case R8's system; Kepler's period, R10's), their
//! order of convergence, stopping, counts, and runs without events unchanged bit for bit.

use marsden::error::{Error, StepError};
use marsden::run::events::{Direction, Event, EventDetector, EventRecord};
use marsden::systems::{Kepler, Pendulum};
use marsden::{
    Initial, Midpoint, Problem, Rule, RunOptions, SolveOptions, Termination, TimeGrid, Trapezoid,
};

use crate::common::{feed, loglog_slope, tight};

/// An event function as a plain function pointer, so that several share one type.
type G = fn(f64, &[f64], &[f64], &[f64]) -> f64;

fn theta(_t: f64, q: &[f64], _v: &[f64], _p: &[f64]) -> f64 {
    q[0]
}

/// The radial velocity (times r): `q · v`, rising through zero at each pericentre.
fn radial(_t: f64, q: &[f64], v: &[f64], _p: &[f64]) -> f64 {
    q[0] * v[0] + q[1] * v[1]
}

pub(super) fn options() -> SolveOptions {
    SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    }
}

/// The pendulum `L = ½θ̇² + cos θ` released from θ₀ = 1.5 at rest, on `steps` steps of `h`.
pub(super) fn pendulum(h: f64, steps: usize) -> Problem<Pendulum> {
    let grid = TimeGrid::new(0.0, h, steps).unwrap();
    Problem::new(Pendulum::default(), Initial::velocity(&[1.5], &[0.0]), grid).unwrap()
}

/// Runs `problem` under `rule` with `events`; the trajectory and the records.
fn detect<L: marsden::Lagrangian, R: Rule>(
    problem: &Problem<L>,
    rule: &R,
    events: Vec<Event<G>>,
) -> (marsden::Trajectory, Vec<EventRecord>) {
    let mut detector = EventDetector::new(problem.lagrangian(), events).unwrap();
    let run = problem.solve_with(rule, &options(), &mut detector).unwrap();
    (run, detector.into_records())
}

/// Released at rest from θ₀, the pendulum passes θ = 0 at T/4, 3T/4, 5T/4, … (T = 4K(k)/ω,
/// k = sin(θ₀/2)), falling at T/4 + jT and rising at 3T/4 + jT. The located times converge at
/// the midpoint rule's order 2 (fitted over h = 0.1 … 0.0125), and are far closer to the exact
/// ones than the nearest grid time (within h/20 of them, and h/100 at the finest h, where a grid
/// time can be h/2 away).
#[test]
fn pendulum_zero_crossings_converge_at_order_two() {
    let period = Pendulum::default().period(1.5).unwrap();
    let steps_sizes = [0.1, 0.05, 0.025, 0.0125];
    let mut errors = Vec::new();
    for &h in &steps_sizes {
        let steps = (2.2 * period / h).ceil() as usize;
        let events = vec![Event::record(theta as G, Direction::Both)];
        let (run, records) = detect(&pendulum(h, steps), &Midpoint, events);
        assert_eq!(run.termination, Termination::Completed);
        assert_eq!(records.len(), 4, "h = {h}: four crossings in 2.2 periods");
        let mut worst: f64 = 0.0;
        for (j, record) in records.iter().enumerate() {
            let exact = (2 * j + 1) as f64 * period / 4.0;
            let expected = if j % 2 == 0 {
                Direction::Down
            } else {
                Direction::Up
            };
            assert_eq!(record.direction, expected);
            // The record lies inside its step, on the interpolant's zero of θ.
            assert!((record.step - 1) as f64 * h <= record.t && record.t <= record.step as f64 * h);
            assert!(record.q[0].abs() < 1e-14, "θ at the event: {}", record.q[0]);
            let error = (record.t - exact).abs();
            // The nearest grid time is up to h/2 away; the located time is far closer.
            let grid_error = (exact / h - (exact / h).round()).abs() * h;
            assert!(
                error < 0.05 * h,
                "h = {h}: event error {error:.3e}, grid error {grid_error:.3e}"
            );
            worst = worst.max(error);
        }
        errors.push(worst);
    }
    // Measured: 4.19e-3, 1.04e-3, 2.61e-4, 6.52e-5 (slope 2.001); a hundredth of h at the end.
    assert!(errors[3] < 0.01 * steps_sizes[3], "{errors:?}");
    let slope = loglog_slope(&steps_sizes, &errors);
    assert!(
        (slope - 2.0).abs() < 0.2,
        "order {slope} (errors {errors:?})"
    );
}

/// The down-crossings alone: T/4 and 5T/4, the up-crossing in between skipped.
#[test]
fn direction_selects_the_crossings() {
    let period = Pendulum::default().period(1.5).unwrap();
    let h = 0.01;
    let problem = pendulum(h, (1.6 * period / h) as usize);
    let (_, records) = detect(
        &problem,
        &Midpoint,
        vec![Event::record(theta as G, Direction::Down)],
    );
    let times: Vec<f64> = records.iter().map(|r| r.t).collect();
    assert_eq!(times.len(), 2, "{times:?}");
    assert!((times[0] - period / 4.0).abs() < 1e-3);
    assert!((times[1] - 5.0 * period / 4.0).abs() < 1e-3);
}

/// Kepler, e = 0.6, from pericentre: a `Stop` event on `q · v` rising through zero ends the run
/// at the next pericentre, one period 2π later (R10's orbit, a = 1, μ = 1); the located time
/// converges at order 2.
#[test]
fn stop_event_ends_kepler_orbit_at_its_pericentre() {
    let (q0, p0) = Kepler::pericentre(0.6);
    let period = 2.0 * std::f64::consts::PI;
    let steps_sizes = [0.004, 0.002, 0.001];
    let mut errors = Vec::new();
    for &h in &steps_sizes {
        let grid = TimeGrid::new(0.0, h, (2.0 * period / h) as usize).unwrap();
        let problem = Problem::new(Kepler::default(), Initial::momentum(&q0, &p0), grid).unwrap();
        let events = vec![Event::stop(radial as G, Direction::Up)];
        let (run, records) = detect(&problem, &Midpoint, events);
        let Termination::Event { event, steps, t } = run.termination else {
            panic!("{:?}", run.termination)
        };
        assert_eq!(event, 0);
        assert_eq!(records.len(), 1);
        assert_eq!(records[0].t, t);
        // The run ends with the step the event lies in, its last state stored.
        assert_eq!(run.steps, steps);
        assert_eq!(*run.step_indices.last().unwrap(), steps);
        assert!(((steps - 1) as f64) * h <= t && t <= steps as f64 * h);
        // At pericentre: q = (1 − e, 0) up to the orbit's precession, q · v = 0.
        let q = &records[0].q;
        assert!(
            (q[0].hypot(q[1]) - 0.4).abs() < 1e-3,
            "r = {}",
            q[0].hypot(q[1])
        );
        assert!(radial(t, q, &records[0].v, &records[0].p).abs() < 1e-12);
        errors.push((t - period).abs());
    }
    // Measured: 1.26e-3, 3.15e-4, 7.87e-5 (slope 2.000).
    assert!(errors[2] < 1e-4, "{errors:?}");
    let slope = loglog_slope(&steps_sizes, &errors);
    assert!(
        (slope - 2.0).abs() < 0.2,
        "order {slope} (errors {errors:?})"
    );
}

/// `count = n` stops at the n-th crossing (the earlier ones recorded); a `Record` event with a
/// count records that many and no more.
#[test]
fn count_stops_after_the_nth_crossing() {
    let period = Pendulum::default().period(1.5).unwrap();
    let h = 0.01;
    let problem = pendulum(h, (10.0 * period / h) as usize);
    let events = vec![
        Event::stop(theta as G, Direction::Both).count(3),
        Event::record(theta as G, Direction::Both).count(2),
    ];
    let (run, records) = detect(&problem, &Midpoint, events);
    let Termination::Event { event, t, .. } = run.termination else {
        panic!("{:?}", run.termination)
    };
    assert_eq!(event, 0);
    assert!((t - 5.0 * period / 4.0).abs() < 1e-3, "{t}");
    let of = |e: usize| records.iter().filter(|r| r.event == e).count();
    assert_eq!((of(0), of(1)), (3, 2));
    // Records come in time order.
    assert!(records.windows(2).all(|w| w[0].t <= w[1].t));
}

/// A count of zero is refused with a typed error.
#[test]
fn count_zero_is_refused() {
    let problem = pendulum(0.1, 10);
    let events = vec![Event::stop(theta as G, Direction::Up).count(0)];
    let error = EventDetector::new(problem.lagrangian(), events).unwrap_err();
    assert!(matches!(error, Error::Input(_)), "{error:?}");
}

/// With events that never fire, the run (states, samples, reports, statistics) is the run
/// without a detector, bit for bit: on the Newton path (midpoint) and the explicit one
/// (trapezoid = Störmer–Verlet, chunked between samples without observer), with a stride.
#[test]
fn runs_without_events_are_unchanged() {
    let never = |_t: f64, q: &[f64], _v: &[f64], _p: &[f64]| q[0] - 10.0;
    let options = SolveOptions {
        run: RunOptions { stride: 7 },
        ..options()
    };
    let problem = pendulum(0.05, 500);
    let plain = problem.solve(&Midpoint, &options).unwrap();
    let mut detector = EventDetector::new(
        problem.lagrangian(),
        vec![Event::stop(never, Direction::Both)],
    )
    .unwrap();
    let watched = problem
        .solve_with(&Midpoint, &options, &mut detector)
        .unwrap();
    assert_eq!(plain, watched);
    assert!(detector.records().is_empty());
    let plain = problem.solve(&Trapezoid, &options).unwrap();
    let watched = problem
        .solve_with(&Trapezoid, &options, &mut detector)
        .unwrap();
    assert_eq!(plain, watched);
}

/// An event function that returns NaN fails the run with a typed step error naming the event,
/// and the trajectory up to that step is kept.
#[test]
fn non_finite_event_fails_the_run_and_keeps_the_trajectory() {
    let bad = |t: f64, _q: &[f64], _v: &[f64], _p: &[f64]| if t > 0.5 { f64::NAN } else { 1.0 };
    let problem = pendulum(0.1, 20);
    let mut detector = EventDetector::new(
        problem.lagrangian(),
        vec![Event::record(bad, Direction::Up)],
    )
    .unwrap();
    let failure = problem
        .solve_with(&Midpoint, &options(), &mut detector)
        .unwrap_err();
    let Error::Step(step) = &failure.error else {
        panic!("{:?}", failure.error)
    };
    assert!(matches!(
        step.cause,
        StepError::EventNotFinite { event: 0, .. }
    ));
    assert_eq!(failure.trajectory.steps, 6);
}

/// `θ̇`: zero at the pendulum's turning points.
fn theta_dot(_t: f64, _q: &[f64], v: &[f64], _p: &[f64]) -> f64 {
    v[0]
}

/// An event that reads `v`: released at rest from θ₀ = 1.5, the pendulum turns (θ̇ = 0) at
/// t = jT/2, T = 4K(k²), k = sin(θ₀/2) (R7, the period of R8's system), θ̇ rising through zero
/// at odd j and falling at even j. The detector computes `v = FL⁻¹(q, p)` at every step for
/// it; the located times converge at the midpoint rule's order 2 (fitted over h = 0.1 …
/// 0.0125), within h/20 of the exact ones, with θ̇ = 0 on the interpolant at the event.
#[test]
fn r07_pendulum_turning_points_read_v_and_converge_at_order_two() {
    let period = Pendulum::default().period(1.5).unwrap();
    let steps_sizes = [0.1, 0.05, 0.025, 0.0125];
    let mut errors = Vec::new();
    for &h in &steps_sizes {
        let steps = (2.2 * period / h).ceil() as usize;
        let events = vec![Event::record(theta_dot as G, Direction::Both)];
        let (run, records) = detect(&pendulum(h, steps), &Midpoint, events);
        assert_eq!(run.termination, Termination::Completed);
        assert_eq!(
            records.len(),
            4,
            "h = {h}: four turning points in 2.2 periods"
        );
        let mut worst: f64 = 0.0;
        for (j, record) in records.iter().enumerate() {
            let expected = if j % 2 == 0 {
                Direction::Up
            } else {
                Direction::Down
            };
            assert_eq!(record.direction, expected);
            assert!(record.v[0].abs() < 1e-12, "θ̇ at the event: {}", record.v[0]);
            // At a turning point |θ| = θ₀ up to the run's O(h²) energy error.
            assert!(
                (record.q[0].abs() - 1.5).abs() < h * h,
                "θ = {}",
                record.q[0]
            );
            let error = (record.t - (j + 1) as f64 * period / 2.0).abs();
            assert!(error < 0.05 * h, "h = {h}: event error {error:.3e}");
            worst = worst.max(error);
        }
        errors.push(worst);
    }
    let slope = loglog_slope(&steps_sizes, &errors);
    assert!(
        (slope - 2.0).abs() < 0.2,
        "order {slope} (errors {errors:?})"
    );
}

/// An event declared not to read `v` ([`Event::without_velocity`]) has its velocities computed
/// only at the ends of a step with a sign change. For the pendulum (mass 1) `v = p` whichever
/// way it is computed, so the located crossings of θ — times, states, velocities — are those
/// of the same event computing `v` at every step, bit for bit, over three periods.
#[test]
fn velocities_at_the_crossing_alone_locate_the_same_events() {
    let period = Pendulum::default().period(1.5).unwrap();
    let h = 0.05;
    let problem = pendulum(h, (3.0 * period / h) as usize);
    let every_step = vec![Event::record(theta as G, Direction::Both)];
    let at_crossings = vec![Event::record(theta as G, Direction::Both).without_velocity()];
    let (run, records) = detect(&problem, &Midpoint, every_step);
    let (lazy_run, lazy_records) = detect(&problem, &Midpoint, at_crossings);
    assert_eq!(records.len(), 6);
    assert_eq!(records, lazy_records);
    assert_eq!(run, lazy_run);
    // The records carry the interpolant's velocities, not the NaN g was shown.
    assert!(lazy_records.iter().all(|r| r.v[0].is_finite()));
}

/// A `g` declared not to read `v` that reads it all the same sees NaN velocities: the run fails
/// at its first step with a typed error naming the event, instead of reading stale numbers.
#[test]
fn an_event_reading_v_declared_without_it_fails_the_run() {
    let problem = pendulum(0.1, 20);
    let events = vec![Event::record(theta_dot as G, Direction::Both).without_velocity()];
    let mut detector = EventDetector::new(problem.lagrangian(), events).unwrap();
    let failure = problem
        .solve_with(&Midpoint, &options(), &mut detector)
        .unwrap_err();
    let Error::Step(step) = &failure.error else {
        panic!("{:?}", failure.error)
    };
    assert!(matches!(
        step.cause,
        StepError::EventNotFinite { event: 0, .. }
    ));
}

/// The pendulum without its declared mass matrix: the detector's inverse Legendre transform
/// is then the general one, Newton's method on `∂L/∂v = p`.
struct Undeclared(Pendulum);

impl marsden::Lagrangian for Undeclared {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: marsden::Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        self.0.lagrangian(t, q, v)
    }
}

/// With the general inverse Legendre transform, velocities computed only at the crossings (from
/// the secant guess) and at every step (from the previous velocities) locate R7's zeros of θ
/// (t = T/4 + jT/2) alike, to Newton's tolerance, both within h/20 of the closed form; and a
/// detector checkpointed half-way (through postcard's bytes) and restored into a fresh one
/// locates the rest to the bit, as the uninterrupted one.
#[test]
fn r07_general_inverse_at_the_crossings_alone_resumes_bit_for_bit() {
    let period = Pendulum::default().period(1.5).unwrap();
    let h = 0.05;
    let steps = (3.0 * period / h) as usize;
    let grid = TimeGrid::new(0.0, h, steps).unwrap();
    let lagrangian = Undeclared(Pendulum::default());
    let problem = Problem::new(lagrangian, Initial::velocity(&[1.5], &[0.0]), grid).unwrap();
    let run = problem.solve(&Midpoint, &options()).unwrap();
    assert_eq!(run.times.len(), steps + 1, "every step stored");
    let lazy = || Event::record(theta as G, Direction::Both).without_velocity();
    let detector = |event: Event<G>| EventDetector::new(problem.lagrangian(), vec![event]).unwrap();

    let mut every_step = detector(Event::record(theta as G, Direction::Both));
    feed(&mut every_step, &run, 0..steps + 1);
    let mut whole = detector(lazy());
    feed(&mut whole, &run, 0..steps + 1);
    assert_eq!(whole.records().len(), 6);
    for (j, (a, b)) in whole.records().iter().zip(every_step.records()).enumerate() {
        assert!((a.t - b.t).abs() < 1e-12, "{} against {}", a.t, b.t);
        let exact = (2 * j + 1) as f64 * period / 4.0;
        assert!((a.t - exact).abs() < 0.05 * h, "t = {}, exact {exact}", a.t);
    }

    let half = steps / 2;
    let mut first = detector(lazy());
    feed(&mut first, &run, 0..half + 1);
    let bytes = postcard::to_allocvec(&first.checkpoint()).unwrap();
    let checkpoint: marsden::run::events::DetectorCheckpoint =
        postcard::from_bytes(&bytes).unwrap();
    let mut resumed = detector(lazy());
    resumed.restore(&checkpoint).unwrap();
    feed(&mut resumed, &run, half + 1..steps + 1);
    let bits = |records: &[EventRecord]| -> Vec<(u64, u64, u64)> {
        (records.iter())
            .map(|r| (r.t.to_bits(), r.q[0].to_bits(), r.v[0].to_bits()))
            .collect()
    };
    assert!(first.records().len() < 6 && !first.records().is_empty());
    assert_eq!(bits(resumed.records()), bits(whole.records()));
}

/// The detector shown every step by the run loop (as beside an every-step observer).
struct EveryStep<'d, 'l>(&'d mut EventDetector<'l, Kepler, G>);

impl marsden::Observer for EveryStep<'_, '_> {
    fn start(&mut self, initial: &marsden::StepView<'_>) {
        self.0.start(initial);
    }
    fn observe(&mut self, view: &marsden::StepView<'_>) -> std::ops::ControlFlow<()> {
        self.0.observe(view)
    }
    fn termination(&self) -> Option<Termination> {
        self.0.termination()
    }
}

/// Kepler, e = 0.6, from its pericentre on the x axis, 8000 steps of 0.003 under `rule` with
/// `events`, in one long stretch (nothing stored between the first and the last state):
/// watched by the detector (`watch_steps`) and shown to it every step by the run loop; the
/// runs and their records.
fn watched_and_shown<R: Rule>(
    rule: &R,
    events: fn() -> Vec<Event<G>>,
) -> [(marsden::Trajectory, Vec<EventRecord>); 2] {
    let (q0, p0) = Kepler::pericentre(0.6);
    let grid = TimeGrid::new(0.0, 0.003, 8000).unwrap();
    let problem = Problem::new(Kepler::default(), Initial::momentum(&q0, &p0), grid).unwrap();
    let stretches = SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..options()
    };
    let mut watching = EventDetector::new(problem.lagrangian(), events()).unwrap();
    let watched = (problem.solve_with(rule, &stretches, &mut watching)).unwrap();
    let mut shown = EventDetector::new(problem.lagrangian(), events()).unwrap();
    let every = (problem.solve_with(rule, &stretches, &mut EveryStep(&mut shown))).unwrap();
    [
        (watched, watching.into_records()),
        (every, shown.into_records()),
    ]
}

/// Watched and shown, the detector locates, records and stops alike: the same records bit for
/// bit, the run ended by the stopping event at the same step with the same last state.
fn assert_alike(runs: &[(marsden::Trajectory, Vec<EventRecord>); 2], records: usize, what: &str) {
    let [(watched, a), (every, b)] = runs;
    assert!(matches!(
        watched.termination,
        Termination::Event { event: 1, .. }
    ));
    assert_eq!(watched.termination, every.termination);
    assert_eq!(a, b);
    assert_eq!(a.len(), records, "{what}");
    let last = |run: &marsden::Trajectory| (run.steps, run.q(run.len() - 1).to_vec());
    assert_eq!(last(watched), last(every));
}

/// The detector watching the steps inside one long stretch of the run is the every-step
/// detector bit for bit, with an event that reads the velocities (every pericentre recorded,
/// and a stop at the third apocentre).
#[test]
fn a_detector_watching_stretches_of_steps_is_the_every_step_detector_bit_for_bit() {
    let events = || {
        vec![
            Event::record(radial as G, Direction::Up),
            Event::stop(radial as G, Direction::Down).count(3),
        ]
    };
    let runs = watched_and_shown(&Midpoint, events);
    assert_alike(&runs, 5, "three apocentres, two pericentres between");
}

/// The height `y` of the Kepler orbit: zero at each pericentre and apocentre of an orbit
/// released at its pericentre on the x axis (an event of the positions alone).
fn height(_t: f64, q: &[f64], _v: &[f64], _p: &[f64]) -> f64 {
    q[1]
}

/// An event of the positions alone, watched inside long stretches: the midpoint rule's
/// Newton steps keep the start of each step for the watch (no copy of the state per step),
/// the trapezoid's explicit steps on Kepler do not (the watch copies each state); both locate,
/// record and stop exactly as when every step is shown: the same records bit for bit, the
/// run ended at the same step with the same last state (the first apocentre, the pericentre
/// after it, and the stop at the second apocentre).
#[test]
fn a_watch_of_the_positions_is_the_every_step_detector_bit_for_bit_with_or_without_kept_starts() {
    let events = || {
        vec![
            Event::record(height as G, Direction::Up),
            Event::stop(height as G, Direction::Down).count(2),
        ]
    };
    let midpoint = watched_and_shown(&Midpoint, events);
    let trapezoid = watched_and_shown(&Trapezoid, events);
    let what = "an apocentre, a pericentre, the stop at the next apocentre";
    assert_alike(&midpoint, 3, what);
    assert_alike(&trapezoid, 3, what);
    assert_ne!(
        midpoint[0].1[0].t, trapezoid[0].1[0].t,
        "two rules, two runs"
    );
}

/// The pendulum whose Lagrangian turns NaN after t = 0.52: the step across it fails.
struct FailingAfter(Pendulum);

impl marsden::Lagrangian for FailingAfter {
    fn dof(&self) -> usize {
        1
    }
    fn lagrangian<S: marsden::Scalar>(&self, t: S, q: &[S], v: &[S]) -> S {
        let l = self.0.lagrangian(t, q, v);
        match t.re() > 0.52 {
            true => l * S::from(f64::NAN),
            false => l,
        }
    }
}

/// A step that fails inside a stretch the detector watches (nothing stored between the first
/// and the last state) ends the run as it does without events: the same step error, the
/// trajectory kept up to the last good state, that state bit for bit.
#[test]
fn a_step_failing_inside_a_watched_stretch_fails_the_run_as_without_events() {
    let grid = TimeGrid::new(0.0, 0.1, 20).unwrap();
    let lagrangian = FailingAfter(Pendulum::default());
    let problem = Problem::new(lagrangian, Initial::velocity(&[1.5], &[0.0]), grid).unwrap();
    let stretches = SolveOptions {
        run: RunOptions { stride: usize::MAX },
        ..options()
    };
    let never = |_t: f64, q: &[f64], _v: &[f64], _p: &[f64]| q[0] - 3.0;
    let mut detector = EventDetector::new(
        problem.lagrangian(),
        vec![Event::record(never, Direction::Both)],
    )
    .unwrap();
    let watched = (problem.solve_with(&Midpoint, &stretches, &mut detector)).unwrap_err();
    let plain = problem.solve(&Midpoint, &stretches).unwrap_err();
    let (Error::Step(a), Error::Step(b)) = (&watched.error, &plain.error) else {
        panic!("{:?} and {:?}", watched.error, plain.error)
    };
    assert_eq!((a.step, a.t.to_bits()), (b.step, b.t.to_bits()));
    assert_eq!(
        watched.trajectory.steps, 5,
        "t = 0.5 is the last good state"
    );
    assert_eq!(watched.trajectory.steps, plain.trajectory.steps);
    let last = |run: &marsden::Trajectory| run.q(run.len() - 1)[0].to_bits();
    assert_eq!(last(&watched.trajectory), last(&plain.trajectory));
    assert!(detector.records().is_empty());
}
