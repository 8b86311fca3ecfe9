//! Rules with inner control points: Gauss and Lobatto with one control value per quadrature
//! node converge to the continuous optimum with their own order (4 for `gauss-2` and
//! `lobatto-3`, 6 for `gauss-3`); a composition keeps one value per step and converges at
//! order 2 whatever its scheme's order. The oscillator's closed-form optimum is the one of
//! `linear_quadratic.rs` (`L = ½q̇² − ½q²`, force `u`, `J = ∫₀¹ ½u²`, rest at 0 to rest at 1):
//! `q(t) = (A t sin t − B t cos t + B sin t)/2`.
//!
//! Each solved step is then replayed by the core's integrator with the step's controls
//! ([`StepControl`]: the polynomial through the stage values), from `(q_k, p_k)`: the
//! transcription's constraints are the core's steps ([OJM11] §3, §4.2).
//!
//! [OJM11]: marsden_control#references

use marsden::analysis::diagnostics::least_squares_slope;
use marsden::discrete::rules::{Composition, CompositionScheme, Galerkin};
use marsden::numerics::dense::max_or_nan;
use marsden::systems::{HarmonicOscillator, Pendulum};
use marsden::{Initial, Midpoint, Problem, Rule, SolveOptions, TimeGrid};
use marsden_control::{InputMap, Solution, SqpOptions, StagedControls, Status, StepControl};

use super::linear_quadratic::{oscillator_coefficients, oscillator_optimum, rest_to_rest};
use super::swing_up::swing_up;

const OSCILLATOR: HarmonicOscillator = HarmonicOscillator { m: 1.0, k: 1.0 };

/// The continuous optimal trajectory of the oscillator.
fn oscillator_q(t: f64) -> f64 {
    let (a, b) = oscillator_coefficients();
    (a * t * t.sin() - b * t * t.cos() + b * t.sin()) / 2.0
}

/// `(|J_d − J*|, max_k |q_k − q(t_k)|)` of the discrete optimum with `steps` steps.
fn oscillator_errors<R: Rule + StagedControls>(rule: &R, steps: usize) -> (f64, f64) {
    let problem = rest_to_rest(OSCILLATOR, steps);
    let tight = SqpOptions {
        kkt_tolerance: 1e-11,
        constraint_tolerance: 1e-12,
        ..SqpOptions::default()
    };
    let s = problem.solve(rule, &tight).unwrap();
    assert!(s.converged(), "{} N = {steps}: {:?}", rule.name(), s.status);
    let nodes = (s.t.iter().zip(&s.q)).fold(0.0, |w, (&t, q)| {
        max_or_nan(w, (q[0] - oscillator_q(t)).abs())
    });
    ((s.cost - oscillator_optimum().cost).abs(), nodes)
}

/// The slopes of `log error` against `log h` (cost, nodes) over `ns`.
fn slopes<R: Rule + StagedControls>(rule: &R, ns: &[usize]) -> (f64, f64) {
    let log_h: Vec<f64> = ns.iter().map(|&n| (1.0 / n as f64).ln()).collect();
    let (mut cost, mut nodes) = (Vec::new(), Vec::new());
    for &n in ns {
        let (c, q) = oscillator_errors(rule, n);
        println!(
            "{} N = {n}: |J − J*| = {c:.3e}, max |q_k − q(t_k)| = {q:.3e}",
            rule.name()
        );
        cost.push(c.ln());
        nodes.push(q.ln());
    }
    let slopes = (
        least_squares_slope(&log_h, &cost),
        least_squares_slope(&log_h, &nodes),
    );
    println!(
        "{} slopes: cost {:.3}, nodes {:.3}",
        rule.name(),
        slopes.0,
        slopes.1
    );
    slopes
}

/// `gauss-2` (order 4) with control stages: the optimum converges at order 4.
#[test]
fn gauss_two_oscillator_optimum_converges_at_order_four() {
    let (cost, nodes) = slopes(&Galerkin::gauss(2).unwrap(), &[4, 8, 16, 32]);
    assert!((cost - 4.0).abs() <= 0.25, "cost slope {cost}");
    assert!((nodes - 4.0).abs() <= 0.25, "node slope {nodes}");
}

/// `lobatto-3` (Lobatto IIIA–IIIB, order 4) with control stages: order 4.
#[test]
fn lobatto_three_oscillator_optimum_converges_at_order_four() {
    let (cost, nodes) = slopes(&Galerkin::lobatto(3).unwrap(), &[4, 8, 16, 32]);
    assert!((cost - 4.0).abs() <= 0.25, "cost slope {cost}");
    assert!((nodes - 4.0).abs() <= 0.25, "node slope {nodes}");
}

/// `gauss-3` (order 6) with control stages: order 6.
#[test]
fn gauss_three_oscillator_optimum_converges_at_order_six() {
    let (cost, nodes) = slopes(&Galerkin::gauss(3).unwrap(), &[4, 8, 16]);
    assert!((cost - 6.0).abs() <= 0.35, "cost slope {cost}");
    assert!((nodes - 6.0).abs() <= 0.35, "node slope {nodes}");
}

/// A fourth-order composition with one control value per step: order 2, the limit of
/// piecewise-constant controls (said in `marsden_control::stages`).
#[test]
fn composition_optimum_converges_at_order_two_with_one_control_per_step() {
    let rule = Composition::new(Midpoint, CompositionScheme::TripleJump { order: 4 });
    let (cost, nodes) = slopes(&rule, &[8, 16, 32, 64]);
    assert!((cost - 2.0).abs() <= 0.2, "cost slope {cost}");
    assert!((nodes - 2.0).abs() <= 0.2, "node slope {nodes}");
}

/// `max_k |(q, p)_{k+1} − Φ_k(q_k, p_k)|`, `Φ_k` one core step with the step's controls.
fn replay<R: Rule>(rule: &R, s: &Solution) -> f64 {
    let sigma = s.stages.count();
    let h = s.t[1] - s.t[0];
    let mut worst = 0.0;
    for k in 0..s.q.len() - 1 {
        let control = StepControl {
            force: InputMap::full(1),
            step: (s.t[k], h),
            stages: &s.stages,
            u: &s.u[k * sigma..(k + 1) * sigma],
        };
        let grid = TimeGrid::new(s.t[k], h, 1).unwrap();
        let initial = Initial::momentum(&s.q[k], &s.p[k]);
        let problem = Problem::new(Pendulum::default(), initial, grid)
            .unwrap()
            .with_force(control);
        let run = problem.solve(rule, &SolveOptions::default()).unwrap();
        let got = run.q(1).iter().chain(run.p(1));
        let want = s.q[k + 1].iter().chain(&s.p[k + 1]);
        worst = got
            .zip(want)
            .fold(worst, |w, (a, b)| max_or_nan(w, (a - b).abs()));
    }
    worst
}

/// The swing-up with `gauss-2`: converged, its nodes are the core's steps with its stage
/// controls, and the stage rows are laid out step by step at `t_k + c_i h`.
#[test]
fn gauss_two_swing_up_reproduces_itself_in_the_core_integrator() {
    let rule = Galerkin::gauss(2).unwrap();
    let s = swing_up(40).solve(&rule, &SqpOptions::default()).unwrap();
    assert_eq!(s.status, Status::Converged, "{:?}", s.history.last());
    assert_eq!(
        (s.u.len(), s.control_times.len(), s.inner.len()),
        (80, 80, 40)
    );
    let h = s.t[1] - s.t[0];
    let c = &s.stages.times;
    assert!((s.control_times[3] - (s.t[1] + c[1] * h)).abs() < 1e-15);
    let defect = replay(&rule, &s);
    println!(
        "gauss-2 swing-up: cost {:.6}, replay defect {defect:.2e}",
        s.cost
    );
    assert!(defect <= 1e-9, "{defect:e}");
}

/// The same with a composition (one control per step, substeps of negative length).
#[test]
fn composition_swing_up_reproduces_itself_in_the_core_integrator() {
    let rule = Composition::new(Midpoint, CompositionScheme::Suzuki4);
    let s = swing_up(40).solve(&rule, &SqpOptions::default()).unwrap();
    assert_eq!(s.status, Status::Converged);
    assert_eq!((s.u.len(), s.inner[0].len()), (40, 4));
    let defect = replay(&rule, &s);
    println!(
        "suzuki-4(midpoint) swing-up: cost {:.6}, replay defect {defect:.2e}",
        s.cost
    );
    assert!(defect <= 1e-9, "{defect:e}");
}
