//! R19: the free rigid body J = diag(2, 1, 2/3), Π₀ = (cos 1.1, 0, sin 1.1), R₀ = I. With U = 0
//! the LGVI is the discrete Moser–Veselov map ([LLM07] §3; Moser & Veselov 1991), which keeps
//! the energy H₀ = 0.6471252793138366, the Casimir |Π|² = 1 and the spatial momentum RΠ exactly
//! (to round-off); against the exact flow by elliptic functions ([LL76] §37) the plain step has
//! order 2, its triple jump 4 and Kahan–Li's composition 6 ([HLW06] §V.3).

use crate::lie::{R19_MOMENTS, composed, free_body, r19_pi0, tight};
use marsden::discrete::rules::composition::CompositionScheme;
use marsden::lie::invariants;
use marsden::lie::so3::Vec3;
use marsden::special::euler_top::EulerTop;

const H0: f64 = 0.6471252793138366;

#[test]
fn r19_moser_veselov_keeps_energy_casimir_and_spatial_momentum() {
    let mut lgvi = free_body(0.1, tight());
    let state = lgvi.state().clone();
    let e0 = invariants::energy(lgvi.system(), &state);
    assert!((e0 - H0).abs() <= 1e-15, "H₀ = {e0}");
    assert!((invariants::casimir(&state, 0) - 1.0).abs() <= 1e-15);
    let l0 = invariants::spatial_angular_momentum(&state);
    let (mut de, mut dc, mut dl): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for _ in 0..10_000 {
        lgvi.step().unwrap();
        let s = lgvi.state();
        de = de.max((invariants::energy(lgvi.system(), s) - H0).abs());
        dc = dc.max((invariants::casimir(s, 0) - 1.0).abs());
        dl = dl.max((invariants::spatial_angular_momentum(s) - l0).amax());
    }
    eprintln!("R19: max |H − H₀| {de:.2e}, ||Π|² − 1| {dc:.2e}, |RΠ − RΠ₀| {dl:.2e}");
    assert!(de <= 1e-12, "energy drift {de:.2e}");
    assert!(dc <= 1e-12, "|Π|² drift {dc:.2e}");
    assert!(dl <= 1e-12, "RΠ drift {dl:.2e}");
    assert!(invariants::orthogonality(lgvi.state()) <= 1e-13);
    let stats = lgvi.statistics();
    assert!(
        stats.newton_iterations as f64 / stats.steps as f64 <= 4.0,
        "{stats:?}"
    );
}

/// Max-norm error of Π at T = 4 against the elliptic-function solution.
fn error_at_t(h: f64, scheme: Option<CompositionScheme>) -> f64 {
    let t_end = 4.0;
    let steps = (t_end / h).round() as usize;
    let mut lgvi = free_body(h, composed(scheme));
    for _ in 0..steps {
        lgvi.step().unwrap();
    }
    let exact = EulerTop::new(R19_MOMENTS, r19_pi0()).unwrap();
    let pi = Vec3::from(exact.momentum(t_end).unwrap());
    (lgvi.state().momentum(0) - pi).amax()
}

fn fitted_order(hs: &[f64], scheme: Option<CompositionScheme>) -> (f64, Vec<f64>) {
    let errors: Vec<f64> = hs.iter().map(|&h| error_at_t(h, scheme)).collect();
    (crate::common::loglog_slope(hs, &errors), errors)
}

#[test]
fn r19_orders_2_4_6_against_the_elliptic_solution() {
    let (two, e2) = fitted_order(&[0.1, 0.05, 0.025, 0.0125], None);
    assert!(
        (two - 2.0).abs() < 0.1,
        "plain LGVI: slope {two}, errors {e2:?}"
    );
    let triple = Some(CompositionScheme::TripleJump { order: 4 });
    let (four, e4) = fitted_order(&[0.2, 0.1, 0.05, 0.025], triple);
    assert!(
        (four - 4.0).abs() < 0.1,
        "triple jump: slope {four}, errors {e4:?}"
    );
    let (six, e6) = fitted_order(&[0.4, 0.2, 0.1, 0.05], Some(CompositionScheme::KahanLi6));
    assert!(
        (six - 6.0).abs() < 0.15,
        "Kahan–Li 6: slope {six}, errors {e6:?}"
    );
}
