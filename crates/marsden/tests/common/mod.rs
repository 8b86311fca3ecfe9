//! Helpers shared by the integration tests: the reference cases' Newton options and runs, and an
//! observer of the stored samples only.
// Tests may unwrap; reference values are quoted with all the digits the reference cases give.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::excessive_precision,
    dead_code
)]

use std::ops::ControlFlow;

use marsden::{DiscreteAction, Integrator, NewtonOptions, Observer, State, StepView};

/// Newton options for conservation tests: converge to round-off (the crate documentation,
/// Conventions, discrete Noether). A residual tolerance of 1e-15 relative to the momenta is below
/// what f64 can always reach; the iteration then stops on the update-size criterion, i.e. at
/// round-off.
pub fn tight() -> NewtonOptions {
    NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    }
}

/// Runs `steps` steps of `h` from `(q0, p0)` and returns the final state.
pub fn run<A: DiscreteAction>(action: A, q0: &[f64], p0: &[f64], h: f64, steps: usize) -> State {
    let mut integrator = Integrator::new(action).with_options(tight()).unwrap();
    let mut state = State {
        t: 0.0,
        q: q0.to_vec(),
        p: p0.to_vec(),
    };
    for k in 0..steps {
        integrator.step(&mut state, h).unwrap();
        state.t = (k + 1) as f64 * h;
    }
    state
}

/// Runs and calls `f(k, state)` after every step.
pub fn run_with<A: DiscreteAction>(
    action: A,
    q0: &[f64],
    p0: &[f64],
    h: f64,
    steps: usize,
    mut f: impl FnMut(usize, &State),
) -> State {
    let mut integrator = Integrator::new(action).with_options(tight()).unwrap();
    let mut state = State {
        t: 0.0,
        q: q0.to_vec(),
        p: p0.to_vec(),
    };
    for k in 0..steps {
        integrator.step(&mut state, h).unwrap();
        state.t = (k + 1) as f64 * h;
        f(k + 1, &state);
    }
    state
}

/// The one-step matrix of a linear system: columns are the images of the unit vectors.
pub fn one_step_matrix<A: DiscreteAction + Clone>(action: &A, h: f64) -> [[f64; 2]; 2] {
    let a = run(action.clone(), &[1.0], &[0.0], h, 1);
    let b = run(action.clone(), &[0.0], &[1.0], h, 1);
    [[a.q[0], b.q[0]], [a.p[0], b.p[0]]]
}

/// Least-squares slope of log(err) against log(h).
pub fn loglog_slope(h: &[f64], err: &[f64]) -> f64 {
    let x: Vec<f64> = h.iter().map(|v| v.ln()).collect();
    let y: Vec<f64> = err.iter().map(|v| v.ln()).collect();
    marsden::analysis::diagnostics::least_squares_slope(&x, &y)
}

/// Asserts `|a − b| ≤ tol` with a readable message.
#[track_caller]
pub fn assert_close(a: f64, b: f64, tol: f64, what: &str) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: {a:.17e} vs {b:.17e} (diff {:.2e} > {tol:.0e})",
        (a - b).abs()
    );
}

/// Counts what it is shown, and asks to be shown only the stored samples (the run loop then
/// hands the stepper the steps between samples in one call).
pub struct SamplesOnly(pub usize);

impl Observer for SamplesOnly {
    fn observe(&mut self, _view: &StepView<'_>) -> ControlFlow<()> {
        self.0 += 1;
        ControlFlow::Continue(())
    }
    fn every_step(&self) -> bool {
        false
    }
}

/// The views of a stored run (every step, one coordinate), as the run loop shows them to an
/// observer: `start` at step 0, `observe` after (each expected to let the run go on).
pub fn feed<O: marsden::Observer>(
    observer: &mut O,
    run: &marsden::Trajectory,
    steps: std::ops::Range<usize>,
) {
    let report = marsden::StepReport::default();
    for k in steps {
        let view = marsden::StepView {
            step: k,
            t: run.times[k],
            q: &run.positions[k..k + 1],
            p: &run.momenta[k..k + 1],
            multipliers: &[],
            end_multipliers: &[],
            report: &report,
        };
        if k == 0 {
            observer.start(&view);
        } else {
            assert!(observer.observe(&view).is_continue());
        }
    }
}
