//! Checkpoints of an integrator (`Integrator::checkpoint`, `Integrator::restore`): a run of N
//! steps, and the same run stopped after k steps, its checkpoint serialised to bytes and back
//! (postcard, through the crate's `serde` feature) and restored into a freshly built integrator
//! of the same problem, give the same states bit for bit — on every path a step can take.

use marsden::discrete::rules::Galerkin;
use marsden::error::{Error, InputError};
use marsden::holonomic::MomentumProjection;
use marsden::integrator::IntegratorCheckpoint;
use marsden::systems::{CartesianPendulum, Chain, DoublePendulum, Kepler, Pendulum};
use marsden::{
    Constraint, DiscreteAction, DiscreteForce, Integrator, Midpoint, Problem, Rule, State,
    TimeGrid, Trapezoid,
};

use crate::common::tight;

const STEPS: usize = 60;
const CUT: usize = 23;
const H: f64 = 0.05;

/// The states of `steps` steps from `state`, each at its grid time.
fn steps<A, F, C, P>(
    integrator: &mut Integrator<A, F, C, P>,
    state: &mut State,
    range: std::ops::Range<usize>,
    t0: f64,
) -> Vec<State>
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    range
        .map(|k| {
            integrator.step(state, H).unwrap();
            state.t = t0 + (k + 1) as f64 * H;
            state.clone()
        })
        .collect()
}

/// The bits of a state, so that equality is bit for bit (signed zeros, NaN payloads).
fn bits(state: &State) -> (u64, Vec<u64>, Vec<u64>) {
    let b = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect();
    (state.t.to_bits(), b(&state.q), b(&state.p))
}

/// Runs `STEPS` steps straight, and `CUT` steps + checkpoint → bytes → restore into `make()`
/// + the rest; asserts every state equal bit for bit and the work counters equal.
fn resumes_bit_for_bit<A, F, C, P>(make: impl Fn() -> Integrator<A, F, C, P>, start: &State)
where
    A: DiscreteAction,
    F: DiscreteForce,
    C: Constraint,
    P: MomentumProjection,
{
    let t0 = start.t;
    let mut straight = make();
    let whole = steps(&mut straight, &mut start.clone(), 0..STEPS, t0);

    let mut first = make();
    let mut state = start.clone();
    let before = steps(&mut first, &mut state, 0..CUT, t0);
    let bytes = postcard::to_allocvec(&first.checkpoint()).unwrap();
    drop(first);
    let checkpoint: IntegratorCheckpoint = postcard::from_bytes(&bytes).unwrap();
    assert_eq!(postcard::to_allocvec(&checkpoint).unwrap(), bytes);
    assert_eq!(checkpoint.steps(), CUT);

    let mut second = make();
    second.restore(&checkpoint).unwrap();
    let after = steps(&mut second, &mut state, CUT..STEPS, t0);
    for (k, (a, b)) in whole.iter().zip(before.iter().chain(&after)).enumerate() {
        assert_eq!(bits(a), bits(b), "state after step {}", k + 1);
    }
    assert_eq!(second.statistics(), straight.statistics());
}

fn state(q: &[f64], p: &[f64]) -> State {
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

/// Explicit Störmer–Verlet (the trapezoid rule of a separable `L`): the gradient carried from
/// one step to the next.
#[test]
fn explicit_verlet_resumes_bit_for_bit() {
    let (q, p) = Kepler::pericentre(0.6);
    let make = || Integrator::new(Trapezoid.discretize(Kepler::default()));
    assert!(make().is_explicit());
    resumes_bit_for_bit(make, &state(&q, &p));
}

/// The separable Newton step with its reused Jacobian: Kepler (n = 2) and an FPU chain
/// (n = 8, banded).
#[test]
fn separable_newton_resumes_bit_for_bit() {
    let (q, p) = Kepler::pericentre(0.6);
    let make = || {
        Integrator::new(Midpoint.discretize(Kepler::default()))
            .with_options(tight())
            .unwrap()
    };
    resumes_bit_for_bit(make, &state(&q, &p));
    let chain = Chain::new(8);
    let q: Vec<f64> = (0..8).map(|i| 0.3 * (i as f64 * 0.7).sin()).collect();
    let make = || Integrator::new(Midpoint.discretize(chain));
    resumes_bit_for_bit(make, &state(&q, &[0.0; 8]));
}

/// The statically sized kernel (a non-separable Lagrangian with n = 2).
#[test]
fn small_kernel_resumes_bit_for_bit() {
    let make = || Integrator::new(Midpoint.discretize(DoublePendulum::default()));
    resumes_bit_for_bit(make, &state(&[1.0, 0.5], &[0.0, 0.0]));
}

/// The general Newton path (fast paths off), and Galerkin gauss-2 (two stages, order 4).
#[test]
fn general_path_and_galerkin_resume_bit_for_bit() {
    let make = || {
        Integrator::new(Midpoint.discretize(Pendulum::default()))
            .with_fast_paths(false)
            .with_options(tight())
            .unwrap()
    };
    resumes_bit_for_bit(make, &state(&[1.5], &[0.0]));
    let gauss = Galerkin::gauss(2).unwrap();
    let make = || Integrator::new(gauss.discretize(DoublePendulum::default()));
    resumes_bit_for_bit(make, &state(&[1.0, 0.5], &[0.0, 0.0]));
}

/// Compensated summation: the rounding errors carried in q and p.
#[test]
fn compensated_summation_resumes_bit_for_bit() {
    let (q, p) = Kepler::pericentre(0.6);
    let gauss = Galerkin::gauss(2).unwrap();
    let make = || {
        Integrator::new(gauss.discretize(Kepler::default()))
            .with_compensated_summation(true)
            .with_options(tight())
            .unwrap()
    };
    assert!(make().is_compensated());
    resumes_bit_for_bit(make, &state(&q, &p));
}

/// Constrained steps with the RATTLE projection: the small SHAKE kernel, and the general path
/// (fast paths off), on the Cartesian pendulum (`Dφ(q_k)` carried from the last projection).
#[test]
fn constrained_rattle_resumes_bit_for_bit() {
    let pendulum = CartesianPendulum::default();
    let grid = TimeGrid::new(0.0, H, STEPS).unwrap();
    let problem = Problem::new(pendulum, pendulum.initial(1.0, 0.0), grid)
        .unwrap()
        .with_constraint(pendulum)
        .unwrap();
    let start = problem.start().clone();
    let make = || problem.integrator(&Midpoint, tight()).unwrap();
    resumes_bit_for_bit(make, &start);
    let make = || {
        problem
            .integrator(&Midpoint, tight())
            .unwrap()
            .with_fast_paths(false)
    };
    resumes_bit_for_bit(make, &start);
}

/// The checkpoint is what makes the difference: a fresh integrator without it starts its
/// predictor afresh and spends more Newton iterations on the next step.
#[test]
fn without_the_checkpoint_the_next_step_differs() {
    let make = || {
        Integrator::new(Midpoint.discretize(DoublePendulum::default()))
            .with_options(tight())
            .unwrap()
    };
    let mut first = make();
    let mut state = state(&[1.0, 0.5], &[0.0, 0.0]);
    let _ = steps(&mut first, &mut state, 0..CUT, 0.0);
    let (mut restored, mut fresh) = (make(), make());
    restored.restore(&first.checkpoint()).unwrap();
    let warm = restored.step(&mut state.clone(), H).unwrap();
    let cold = fresh.step(&mut state.clone(), H).unwrap();
    assert!(
        cold.iterations > warm.iterations,
        "{} vs {}",
        cold.iterations,
        warm.iterations
    );
}

/// A checkpoint of another problem's shape, or of another path, is refused with a typed error.
#[test]
fn mismatched_checkpoints_are_refused() {
    let pendulum = Integrator::new(Midpoint.discretize(Pendulum::default()));
    let mut kepler = Integrator::new(Midpoint.discretize(Kepler::default()));
    let error = kepler.restore(&pendulum.checkpoint()).unwrap_err();
    assert!(
        matches!(
            error,
            Error::Input(InputError::DimensionMismatch {
                expected: 2,
                found: 1,
                ..
            })
        ),
        "{error:?}"
    );
    let mut general =
        Integrator::new(Midpoint.discretize(Pendulum::default())).with_fast_paths(false);
    let error = general.restore(&pendulum.checkpoint()).unwrap_err();
    assert!(
        matches!(error, Error::Input(InputError::InvalidOption { .. })),
        "{error:?}"
    );
}

/// The run loop's checkpoints: an observer that asks for a checkpoint at step `CUT`
/// ([`marsden::Observer::checkpoint_due`]) receives what the integrator carries, and
/// [`Problem::solve_resumed`] from it reaches the uninterrupted run's last state bit for bit,
/// with the whole run's statistics.
#[test]
fn solve_resumed_from_a_run_loop_checkpoint_is_bit_for_bit() {
    use marsden::run::Resumed;
    use marsden::{SolveOptions, StepView};
    use std::ops::ControlFlow;

    struct TakeAt(Option<(Resumed, IntegratorCheckpoint)>);
    impl marsden::Observer for TakeAt {
        fn observe(&mut self, _: &StepView<'_>) -> ControlFlow<()> {
            ControlFlow::Continue(())
        }
        fn checkpoint_due(&self, step: usize) -> bool {
            step == CUT
        }
        fn checkpoint(
            &mut self,
            v: &StepView<'_>,
            carried: &IntegratorCheckpoint,
        ) -> ControlFlow<()> {
            let state = State {
                t: v.t,
                q: v.q.to_vec(),
                p: v.p.to_vec(),
            };
            self.0 = Some((
                Resumed {
                    step: v.step,
                    state,
                },
                carried.clone(),
            ));
            ControlFlow::Break(())
        }
    }
    let pendulum = DoublePendulum::default();
    let grid = TimeGrid::new(0.0, H, STEPS).unwrap();
    let problem = Problem::new(
        pendulum,
        marsden::Initial::velocity(&[1.0, -0.5], &[0.0, 0.3]),
        grid,
    )
    .unwrap();
    let options = SolveOptions {
        newton: tight(),
        ..SolveOptions::default()
    };
    let whole = problem.solve_with(&Midpoint, &options, &mut ()).unwrap();
    let mut take = TakeAt(None);
    let cut = problem.solve_with(&Midpoint, &options, &mut take).unwrap();
    assert_eq!(cut.steps, CUT, "the checkpoint's Break stops the run there");
    let (from, carried) = take.0.expect("a checkpoint at step CUT");
    let bytes = postcard::to_allocvec(&carried).unwrap();
    let carried: IntegratorCheckpoint = postcard::from_bytes(&bytes).unwrap();
    let resumed = problem
        .solve_resumed(&Midpoint, &options, &mut (), from, &carried)
        .unwrap();
    let last = |t: &marsden::Trajectory| {
        let i = t.len() - 1;
        bits(&State {
            t: t.t(i),
            q: t.q(i).to_vec(),
            p: t.p(i).to_vec(),
        })
    };
    assert_eq!(resumed.steps, STEPS);
    assert_eq!(last(&resumed), last(&whole));
    assert_eq!(resumed.statistics, whole.statistics);
}
