//! R20: the heavy symmetric top (Simo & Wong 1991 data) J = diag(5, 5, 1), U = mgl e₃·(R e₃),
//! mgl = 20, R₀ = exp(0.05 ê₁), Ω₀ = (0, 0, 50): H₀ = 1250 + 20 cos 0.05 = 1269.975005207899,
//! the vertical spatial momentum e₃·RΠ = 50 cos 0.05 = 49.937513019748 (left action about e₃) and
//! Π₃ = 50 (right action about the symmetry axis) are kept by the LGVI to round-off ([LLM07]
//! §3.3, discrete Noether); its energy error is bounded and of order 2 in h.

use crate::lie::{heavy_top, tight};
use marsden::lie::invariants;
use marsden::lie::so3::Vec3;

const H0: f64 = 1269.975005207899;
const VERTICAL: f64 = 49.937513019748;

fn vertical(state: &marsden::lie::state::RigidState) -> f64 {
    Vec3::z().dot(&invariants::spatial_angular_momentum(state))
}

/// Max |E − H₀| over T = 10, and the max over each half.
fn energy_errors(h: f64) -> (f64, f64, f64) {
    let steps = (10.0 / h).round() as usize;
    let mut lgvi = heavy_top(h, tight());
    let (mut first, mut second): (f64, f64) = (0.0, 0.0);
    for k in 1..=steps {
        lgvi.step().unwrap();
        let e = (invariants::energy(lgvi.system(), lgvi.state()) - H0).abs();
        if k <= steps / 2 {
            first = first.max(e);
        } else {
            second = second.max(e);
        }
    }
    (first.max(second), first, second)
}

#[test]
fn r20_initial_invariants_and_momenta_to_round_off() {
    let mut lgvi = heavy_top(0.001, tight());
    let s = lgvi.state().clone();
    assert!((invariants::energy(lgvi.system(), &s) - H0).abs() <= 1e-12 * H0);
    assert!((vertical(&s) - VERTICAL).abs() <= 1e-13 * VERTICAL);
    let (mut dv, mut d3): (f64, f64) = (0.0, 0.0);
    for _ in 0..10_000 {
        lgvi.step().unwrap();
        dv = dv.max((vertical(lgvi.state()) - VERTICAL).abs());
        d3 = d3.max((lgvi.state().momentum(0).z - 50.0).abs());
    }
    eprintln!("R20: |e₃·RΠ − L₀| {dv:.2e}, |Π₃ − 50| {d3:.2e}");
    assert!(dv <= 1e-12 * VERTICAL, "e₃·RΠ drift {dv:.2e}");
    assert!(d3 <= 1e-12 * 50.0, "Π₃ drift {d3:.2e}");
}

#[test]
fn r20_energy_error_bounded_and_second_order() {
    let hs = [0.002, 0.001, 0.0005];
    let runs: Vec<(f64, f64, f64)> = hs.iter().map(|&h| energy_errors(h)).collect();
    let errors: Vec<f64> = runs.iter().map(|r| r.0).collect();
    let slope = crate::common::loglog_slope(&hs, &errors);
    assert!(
        (slope - 2.0).abs() < 0.1,
        "slope {slope}, errors {errors:?}"
    );
    // No drift: the second half of the run does not exceed the first by more than 10 %.
    for (h, (_, first, second)) in hs.iter().zip(&runs) {
        assert!(
            *second <= 1.1 * first,
            "h = {h}: {first:.3e} then {second:.3e}"
        );
    }
}

/// `max |RᵀR − I|` after `steps` steps of `h = 0.001`.
fn defect_after(steps: usize) -> f64 {
    let mut lgvi = heavy_top(0.001, tight());
    let start = std::time::Instant::now();
    for _ in 0..steps {
        lgvi.step().unwrap();
    }
    let defect = invariants::orthogonality(lgvi.state());
    eprintln!(
        "R20: max |RᵀR − I| = {defect:.2e} after {steps} steps ({:.1} s)",
        start.elapsed().as_secs_f64()
    );
    defect
}

#[test]
fn r20_attitude_stays_orthonormal_over_a_hundred_thousand_steps() {
    let defect = defect_after(100_000);
    assert!(defect <= 1e-13, "max |RᵀR − I| = {defect:.2e}");
}

/// The case's 10⁶ steps: 7.7e-14 measured; 10.6 s in the dev profile on the shared machine,
/// above the suite's 5 s budget, hence ignored (`cargo test -- --ignored r20`).
#[test]
#[ignore = "10⁶ steps: about 10 s in the dev profile"]
fn r20_attitude_stays_orthonormal_over_a_million_steps() {
    let defect = defect_after(1_000_000);
    assert!(defect <= 1e-13, "max |RᵀR − I| = {defect:.2e}");
}
