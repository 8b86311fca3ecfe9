//! The same mechanical system written as L and as H (the crate documentation, Conventions,
//! equivalences): for a constant mass matrix the midpoint VI of L *is* implicit midpoint on H and
//! the trapezoid VI *is* velocity Störmer–Verlet (same trajectories to 1e-12 over 10³ steps); for
//! the double pendulum (configuration-dependent mass matrix) the two forms agree pointwise (energy,
//! vector field, momentum maps) and both converge with order 2 to the same solution.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use crate::common::{loglog_slope, tight};
use marsden::hamiltonian::{
    Hamiltonian, HamiltonianIntegrator, HamiltonianMethod, ImplicitMidpoint, LegendreHamiltonian,
    Splitting, vector_field,
};
use marsden::symmetry::Sample;
use marsden::systems::{DoublePendulum, HenonHeiles, Kepler};
use marsden::{
    DiscreteAction, Integrator, Lagrangian, Midpoint, Rule, State, Trapezoid, mechanics,
};
use std::f64::consts::PI;

fn start(q: &[f64], p: &[f64]) -> State {
    State {
        t: 0.0,
        q: q.to_vec(),
        p: p.to_vec(),
    }
}

/// All states `(q, p)` of `steps` steps of a variational integrator, flattened.
/// Runs the general (AD) path: the Lagrangian construction itself is what these tests compare
/// with the Hamiltonian one (the structure-aware paths are compared with the general path in
/// `separable_fast_path.rs` and `explicit_fast_path.rs`).
fn lagrangian_run<A: DiscreteAction>(action: A, s: &State, h: f64, steps: usize) -> Vec<f64> {
    let mut integrator = Integrator::new(action)
        .with_fast_paths(false)
        .with_options(tight())
        .unwrap();
    let mut state = s.clone();
    let mut out = Vec::new();
    for k in 0..steps {
        integrator.step(&mut state, h).unwrap();
        state.t = (k + 1) as f64 * h;
        out.extend(state.q.iter().chain(&state.p));
    }
    out
}

fn hamiltonian_run<H: Hamiltonian, M: HamiltonianMethod<H>>(
    ham: H,
    method: M,
    s: &State,
    h: f64,
    steps: usize,
) -> Vec<f64> {
    let mut integrator = HamiltonianIntegrator::new(ham, method);
    let mut state = s.clone();
    let mut out = Vec::new();
    for k in 0..steps {
        integrator.step(&mut state, h).unwrap();
        state.t = (k + 1) as f64 * h;
        out.extend(state.q.iter().chain(&state.p));
    }
    out
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn midpoint() -> ImplicitMidpoint {
    ImplicitMidpoint::new(tight()).unwrap()
}

/// Max difference of the one-step maps of the two forms from the same states: the 10³ states
/// of the R10 orbit (Kepler e = 0.6, h = 2π/1000).
fn one_step_differences<A: DiscreteAction, H: Hamiltonian + Copy, M: HamiltonianMethod<H>>(
    action: A,
    ham: H,
    mut method: impl FnMut() -> M,
) -> f64 {
    let (q, p) = Kepler::pericentre(0.6);
    let h = 2.0 * PI / 1000.0;
    let mut integrator = Integrator::new(action).with_options(tight()).unwrap();
    let mut state = start(&q, &p);
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        let mut other = state.clone();
        HamiltonianIntegrator::new(ham, method())
            .step(&mut other, h)
            .unwrap();
        integrator.step(&mut state, h).unwrap();
        let a: Vec<f64> = state.q.iter().chain(&state.p).copied().collect();
        let b: Vec<f64> = other.q.iter().chain(&other.p).copied().collect();
        worst = worst.max(max_difference(&a, &b));
    }
    worst
}

#[test]
fn constant_mass_midpoint_vi_is_implicit_midpoint_on_h() {
    // The same map: from the same state the two forms agree to 8 ε |z| (|z| ≤ 2 on this orbit),
    // as [GI] checks for its VPRKGauss(1) against PMVImidpoint.
    let kepler = Kepler::default();
    let d = one_step_differences(Midpoint.discretize(kepler), kepler, midpoint);
    println!("kepler e = 0.6, one step, midpoint VI vs implicit midpoint: {d:.2e}");
    assert!(d <= 8.0 * f64::EPSILON * 2.0, "{d:e}");

    // The same trajectory over 10³ steps, to 1e-12.
    let h = 2.0 * PI / 1000.0;
    let (q, p) = Kepler::pericentre(0.3);
    let on_l = lagrangian_run(Midpoint.discretize(kepler), &start(&q, &p), h, 1000);
    let on_h = hamiltonian_run(kepler, midpoint(), &start(&q, &p), h, 1000);
    let from_l = hamiltonian_run(
        LegendreHamiltonian::new(kepler),
        midpoint(),
        &start(&q, &p),
        h,
        1000,
    );
    let (d, d_adapter) = (max_difference(&on_l, &on_h), max_difference(&on_h, &from_l));
    println!("kepler e = 0.3, 10³ steps: L vs H {d:.2e}, H vs H(L) {d_adapter:.2e}");
    assert!(d <= 1e-12 && d_adapter <= 1e-12, "{d:e} {d_adapter:e}");

    let hh = HenonHeiles::default();
    let s = start(&[0.1, -0.2], &[0.35, 0.1]);
    let on_l = lagrangian_run(Midpoint.discretize(hh), &s, 0.1, 1000);
    let on_h = hamiltonian_run(hh, midpoint(), &s, 0.1, 1000);
    let d = max_difference(&on_l, &on_h);
    println!("Hénon–Heiles, 10³ steps: L vs H {d:.2e}");
    assert!(d <= 1e-12, "{d:e}");
}

/// Kepler e = 0.6 over one full period (10³ steps): the orbit amplifies round-off about 10³-fold
/// by the end (one ulp of p₀ moves the final state by 4.5e-13), so two implementations whose
/// steps differ by a few ulps (above) end 4e-12 apart. 1e-12 is below this floor; the test pins
/// the measured agreement relative to the floor it measures.
#[test]
fn constant_mass_equivalences_on_the_eccentric_orbit_are_at_the_round_off_floor() {
    let (q, p) = Kepler::pericentre(0.6);
    let h = 2.0 * PI / 1000.0;
    let kepler = Kepler::default();
    let reference = lagrangian_run(Midpoint.discretize(kepler), &start(&q, &p), h, 1000);
    let nudged = lagrangian_run(
        Midpoint.discretize(kepler),
        &start(&q, &[p[0], p[1] + 4.4e-16]),
        h,
        1000,
    );
    let floor = max_difference(&reference[3996..], &nudged[3996..]);
    let on_h = hamiltonian_run(kepler, midpoint(), &start(&q, &p), h, 1000);
    let trapezoid = lagrangian_run(Trapezoid.discretize(kepler), &start(&q, &p), h, 1000);
    let verlet = hamiltonian_run(kepler, Splitting::stormer_verlet(), &start(&q, &p), h, 1000);
    let (d_mid, d_sv) = (
        max_difference(&reference, &on_h),
        max_difference(&trapezoid, &verlet),
    );
    println!(
        "kepler e = 0.6, 10³ steps: 1-ulp floor {floor:.2e}; midpoint L vs H {d_mid:.2e}; \
         trapezoid vs Störmer–Verlet {d_sv:.2e}"
    );
    assert!(
        d_mid <= 20.0 * floor && d_sv <= 20.0 * floor,
        "{d_mid:e} {d_sv:e} (floor {floor:e})"
    );
    let d = one_step_differences(
        Trapezoid.discretize(kepler),
        kepler,
        Splitting::stormer_verlet,
    );
    println!("kepler e = 0.6, one step, trapezoid VI vs Störmer–Verlet: {d:.2e}");
    assert!(d <= 8.0 * f64::EPSILON * 2.0, "{d:e}");
}

#[test]
fn constant_mass_trapezoid_vi_is_stormer_verlet() {
    let (q, p) = Kepler::pericentre(0.3);
    let h = 2.0 * PI / 1000.0;
    let on_l = lagrangian_run(
        Trapezoid.discretize(Kepler::default()),
        &start(&q, &p),
        h,
        1000,
    );
    let on_h = hamiltonian_run(
        Kepler::default(),
        Splitting::stormer_verlet(),
        &start(&q, &p),
        h,
        1000,
    );
    let d = max_difference(&on_l, &on_h);
    println!("kepler e = 0.3 trapezoid vs Störmer–Verlet: {d:.2e}");
    assert!(d <= 1e-12, "{d:e}");
}

#[test]
fn double_pendulum_l_and_h_agree_pointwise() {
    let dp = DoublePendulum::default();
    let from_l = LegendreHamiltonian::new(dp);
    let (mut worst_e, mut worst_x): (f64, f64) = (0.0, 0.0);
    for s in Sample::random(2, 100, 17, 2.0) {
        let (q, v) = (&s.q, &s.v);
        // Energy: E_L(q, v) = H(q, FL(q, v)), for the closed-form H and the adapter.
        let mut p = [0.0; 2];
        mechanics::momentum(&dp, 0.0, q, v, &mut p);
        let e_l = mechanics::energy(&dp, 0.0, q, v);
        let e_h: f64 = dp.hamiltonian(0.0, q, &p);
        let e_adapter = from_l.try_value(0.0, q, &p).unwrap();
        worst_e = worst_e.max((e_l - e_h).abs()).max((e_l - e_adapter).abs());
        // Vector field: X_H of the closed form vs X_H of H built from L by AD through FH.
        let (mut dq, mut dpp, mut dq2, mut dp2) = ([0.0; 2], [0.0; 2], [0.0; 2], [0.0; 2]);
        vector_field(&dp, 0.0, q, &p, &mut dq, &mut dpp);
        vector_field(&from_l, 0.0, q, &p, &mut dq2, &mut dp2);
        // And against the Lagrangian side: q̇ = v, ṗ = ∂L/∂q.
        let mut dl_dq = [0.0; 2];
        mechanics::dl_dq(&dp, 0.0, q, v, &mut dl_dq);
        for i in 0..2 {
            worst_x = worst_x
                .max((dq[i] - dq2[i]).abs())
                .max((dpp[i] - dp2[i]).abs())
                .max((dq[i] - v[i]).abs())
                .max((dpp[i] - dl_dq[i]).abs());
        }
    }
    println!("double pendulum: energy {worst_e:.2e}, vector field {worst_x:.2e}");
    assert!(worst_e <= 1e-12, "energy {worst_e:e}");
    assert!(worst_x <= 1e-12, "vector field {worst_x:e}");
    assert_eq!(from_l.dof(), Lagrangian::dof(&dp));
}

/// Final state at t = 2 of the double pendulum with `steps` steps.
fn final_state(form: &str, steps: usize) -> Vec<f64> {
    let s = start(&[1.0, -0.5], &[0.3, 0.2]);
    let h = 2.0 / steps as f64;
    let dp = DoublePendulum::default();
    let run = match form {
        "L midpoint" => lagrangian_run(Midpoint.discretize(dp), &s, h, steps),
        "L trapezoid" => lagrangian_run(Trapezoid.discretize(dp), &s, h, steps),
        _ => hamiltonian_run(dp, midpoint(), &s, h, steps),
    };
    run[run.len() - 4..].to_vec()
}

#[test]
fn double_pendulum_both_forms_converge_with_order_2_to_the_same_solution() {
    // Reference: implicit midpoint on H at h = 2/12800 and 2/6400, Richardson-extrapolated
    // (symmetric method: error C h² + O(h⁴)).
    let (fine, coarse) = (final_state("H", 12_800), final_state("H", 6_400));
    let reference: Vec<f64> = fine
        .iter()
        .zip(&coarse)
        .map(|(f, c)| (4.0 * f - c) / 3.0)
        .collect();
    let steps = [50, 100, 200, 400];
    let hs: Vec<f64> = steps.iter().map(|&n| 2.0 / n as f64).collect();
    for form in ["L midpoint", "L trapezoid", "H"] {
        let errors: Vec<f64> = steps
            .iter()
            .map(|&n| max_difference(&final_state(form, n), &reference))
            .collect();
        let slope = loglog_slope(&hs, &errors);
        println!("{form}: errors {errors:?}, order {slope:.3}");
        // A method converging to a different limit would plateau (slope → 0) against this
        // common reference.
        assert!((slope - 2.0).abs() < 0.05, "{form}: order {slope}");
    }
    // The midpoint VI is implicit midpoint on H even with a configuration-dependent mass matrix:
    // p̄ = (p₀ + p₁)/2 = M(q̄)v gives v = FH(q̄, p̄), and ∂L/∂q(q̄, v) = −∂H/∂q(q̄, p̄). The
    // trapezoid VI is a different method (its difference from H is O(h²)).
    for &n in &steps {
        let d = max_difference(&final_state("L midpoint", n), &final_state("H", n));
        assert!(
            d <= 1e-12,
            "midpoint VI vs implicit midpoint, {n} steps: {d:e}"
        );
    }
    let gap: Vec<f64> = steps
        .iter()
        .map(|&n| max_difference(&final_state("L trapezoid", n), &final_state("H", n)))
        .collect();
    assert!(gap[0] > 1e-6, "{gap:?}");
    assert!((loglog_slope(&hs, &gap) - 2.0).abs() < 0.1, "{gap:?}");
}
