//! The step Jacobian of a separable Lagrangian from `M` and `∇²V`
//! ([`marsden::separable::jacobian`]) against the general one (implicit function theorem on a
//! hyper-dual Hessian of the action): Kepler e = 0.6 (R5's problem) and an FPU α-β chain
//! (banded `∇²V`), for the midpoint rule, the trapezoid rule, an α = 0.3 rule and a symmetrised
//! α = 0.2 rule, at states along a run.
//!
//! * Same offset: the structured formula at the general step's own converged `Δ` equals the
//!   general Jacobian to round-off (≤ 1e-13 relative).
//! * Same integrator: where the step takes the separable or explicit path (midpoint, trapezoid,
//!   α), a fast-path integrator's `step_with_jacobian` is the structured formula at its own `Δ`
//!   bit for bit (it takes the structured Jacobian); every fast-path integrator agrees with the
//!   general one from the same state to the round-off of the two converged steps.

use super::common::{relative_distance, state};
use crate::common::tight;
use marsden::analysis::certificate::DifferentiableStep;
use marsden::separable::JacobianWorkspace;
use marsden::systems::{Chain, Kepler};
use marsden::{
    DiscreteAction, GeneralizedMidpoint, Integrator, Lagrangian, Midpoint, Rule, State,
    SymmetrizedMidpoint, Trapezoid,
};

/// `∂(q_{k+1}, p_{k+1})/∂(q_k, p_k)` of one step from `x` by `vi`, and the step's offset.
fn step<A: DiscreteAction>(vi: &mut Integrator<A>, x: &State, h: f64) -> (Vec<f64>, Vec<f64>) {
    let n = x.q.len();
    let mut jac = vec![0.0; 4 * n * n];
    let mut s = x.clone();
    vi.reset();
    vi.step_with_jacobian(&mut s, h, &mut jac).unwrap();
    (jac, vi.stage_offsets().to_vec())
}

/// The structured Jacobian of `action` at offset `delta` from `x`.
fn structured<A: DiscreteAction>(action: &A, x: &State, h: f64, delta: &[f64]) -> Vec<f64> {
    let n = x.q.len();
    let mut jac = vec![0.0; 4 * n * n];
    let step = action.separable_jacobian().expect("a two-point α rule");
    let mut ws = JacobianWorkspace::default();
    step.step_jacobian((x.t, h), (&x.q, delta), &mut jac, &mut ws)
        .expect("a separable Lagrangian")
        .unwrap();
    jac
}

/// Compares the three Jacobians at 40 states of a run of `rule` on `l` from `start`;
/// `separable_path`: the fast integrator's steps take the separable or explicit path.
fn check<R: Rule, L: Lagrangian + Clone>(
    name: &str,
    separable_path: bool,
    rule: &R,
    l: L,
    start: State,
    h: f64,
) {
    let action = rule.discretize(l.clone());
    let mut fast = Integrator::new(rule.discretize(l.clone()))
        .with_options(tight())
        .unwrap();
    let mut general = Integrator::new(rule.discretize(l))
        .with_options(tight())
        .unwrap()
        .with_fast_paths(false);
    let mut x = start;
    let mut worst = (0.0_f64, 0.0_f64);
    for k in 0..40 {
        let (jac_general, delta_general) = step(&mut general, &x, h);
        let (jac_fast, delta_fast) = step(&mut fast, &x, h);
        let same_offset =
            relative_distance(&structured(&action, &x, h, &delta_general), &jac_general);
        assert!(
            same_offset <= 1e-13,
            "{name}, step {k}: structured vs general at the same offset: {same_offset:.2e}"
        );
        if separable_path {
            assert_eq!(
                jac_fast,
                structured(&action, &x, h, &delta_fast),
                "{name}, step {k}: the fast integrator's Jacobian is not the structured one"
            );
        }
        let end_to_end = relative_distance(&jac_fast, &jac_general);
        assert!(
            end_to_end <= 1e-12,
            "{name}, step {k}: fast vs general integrator: {end_to_end:.2e}"
        );
        worst = (worst.0.max(same_offset), worst.1.max(end_to_end));
        for _ in 0..5 {
            fast.step(&mut x, h).unwrap();
        }
    }
    eprintln!(
        "{name}: structured vs general {:.1e} (same Δ), {:.1e} (own steps)",
        worst.0, worst.1
    );
}

fn kepler() -> (Kepler, State) {
    let (q, p) = Kepler::pericentre(0.6);
    (Kepler::default(), state(&q, &p))
}

fn chain() -> (Chain, State) {
    let chain = Chain {
        alpha: 0.25,
        ..Chain::new(12)
    };
    let q: Vec<f64> = (0..12).map(|i| 0.3 * (0.7 * i as f64).sin()).collect();
    let p: Vec<f64> = (0..12).map(|i| 0.2 * (1.3 * i as f64).cos()).collect();
    (chain, state(&q, &p))
}

fn alpha() -> GeneralizedMidpoint {
    GeneralizedMidpoint::new(0.3).unwrap()
}

fn symmetrized() -> SymmetrizedMidpoint {
    SymmetrizedMidpoint::new(0.2).unwrap()
}

#[test]
fn r5_kepler_structured_step_jacobian_equals_the_general_one() {
    let (l, x) = kepler();
    check("kepler midpoint", true, &Midpoint, l, x.clone(), 0.01);
    check("kepler trapezoid", true, &Trapezoid, l, x.clone(), 0.01);
    check("kepler alpha 0.3", true, &alpha(), l, x.clone(), 0.01);
    check("kepler symmetrized 0.2", false, &symmetrized(), l, x, 0.01);
}

#[test]
fn banded_chain_structured_step_jacobian_equals_the_general_one() {
    let (l, x) = chain();
    check("chain midpoint", true, &Midpoint, l, x.clone(), 0.05);
    check("chain trapezoid", true, &Trapezoid, l, x.clone(), 0.05);
    check("chain alpha 0.3", true, &alpha(), l, x.clone(), 0.05);
    check("chain symmetrized 0.2", false, &symmetrized(), l, x, 0.05);
}

/// A Lagrangian that is not separable has no structured Jacobian (the general one applies).
#[test]
fn non_separable_lagrangian_has_no_structured_step_jacobian() {
    let action = Midpoint.discretize(marsden::systems::DoublePendulum::default());
    let step = action.separable_jacobian().expect("the α rule offers it");
    let mut jac = vec![0.0; 16];
    let x = state(&[0.3, 0.2], &[0.0, 0.1]);
    let got = step.step_jacobian(
        (0.0, 0.01),
        (&x.q, &[0.01, 0.0]),
        &mut jac,
        &mut JacobianWorkspace::default(),
    );
    assert!(got.is_none());
}
