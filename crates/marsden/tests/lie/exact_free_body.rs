//! The exact free rigid body by Jacobi elliptic functions ([LL76] §37, `special::euler_top`):
//! its invariants, Euler's equations by finite differences, and a tight numerical integration
//! (the sixth-order composition of the LGVI at small h) on both sides of the separatrix.

use super::{R19_MOMENTS, composed, r19_pi0};
use marsden::discrete::rules::composition::CompositionScheme;
use marsden::lie::body::{Inertia, RigidBody};
use marsden::lie::lgvi::Lgvi;
use marsden::lie::potential::NoPotential;
use marsden::lie::so3::{Mat3, Vec3};
use marsden::lie::state::{BodyInitial, RigidState, RigidSystem};
use marsden::special::euler_top::EulerTop;

fn invariants(moments: [f64; 3], pi: [f64; 3]) -> (f64, f64) {
    let casimir = pi.iter().map(|p| p * p).sum();
    let energy = (0..3).map(|i| 0.5 * pi[i] * pi[i] / moments[i]).sum();
    (casimir, energy)
}

/// R19's motion winds about the axis of least inertia (M² = 1 < 2E J₂ = 1.294); the second
/// initial value about the largest (M² > 2E J₂).
fn cases() -> Vec<([f64; 3], [f64; 3])> {
    vec![
        (R19_MOMENTS, r19_pi0()),
        ([2.0, 1.0, 2.0 / 3.0], [0.9, 0.3, -0.1]),
    ]
}

#[test]
fn exact_solution_keeps_energy_and_casimir_and_solves_euler() {
    for (moments, pi0) in cases() {
        let exact = EulerTop::new(moments, pi0).unwrap();
        let start = exact.momentum(0.0).unwrap();
        for k in 0..3 {
            assert!((start[k] - pi0[k]).abs() <= 1e-14, "{start:?} vs {pi0:?}");
        }
        let (c0, e0) = invariants(moments, pi0);
        for t in [0.3, 1.7, 5.0, 23.4] {
            let pi = exact.momentum(t).unwrap();
            let (c, e) = invariants(moments, pi);
            assert!(
                (c - c0).abs() <= 1e-14 && (e - e0).abs() <= 1e-14,
                "t = {t}"
            );
            // Π̇ = Π × J⁻¹Π by a central difference.
            let d = 1e-5;
            let (plus, minus) = (
                exact.momentum(t + d).unwrap(),
                exact.momentum(t - d).unwrap(),
            );
            let p = Vec3::from(pi);
            let omega = Vec3::new(pi[0] / moments[0], pi[1] / moments[1], pi[2] / moments[2]);
            let rhs = p.cross(&omega);
            for k in 0..3 {
                let fd = (plus[k] - minus[k]) / (2.0 * d);
                assert!(
                    (fd - rhs[k]).abs() <= 1e-9,
                    "t = {t}, k = {k}: {fd} vs {}",
                    rhs[k]
                );
            }
        }
        let period = exact.period().unwrap();
        let back = exact.momentum(period).unwrap();
        assert!((0..3).all(|k| (back[k] - pi0[k]).abs() <= 1e-13));
    }
}

#[test]
fn exact_solution_matches_a_sixth_order_lgvi_run() {
    for (moments, pi0) in cases() {
        let exact = EulerTop::new(moments, pi0).unwrap();
        let body = RigidBody::fixed_point(Inertia::principal_unphysical(moments).unwrap());
        let system = RigidSystem::new(vec![body], NoPotential);
        let initial = BodyInitial::rotating(&Mat3::identity(), &Vec3::from(pi0));
        let state = RigidState::new(&system, 0.0, &[initial]).unwrap();
        let options = composed(Some(CompositionScheme::KahanLi6));
        let mut lgvi = Lgvi::new(system, state, 0.01, options).unwrap();
        let mut worst: f64 = 0.0;
        for k in 1..=1000 {
            lgvi.step().unwrap();
            let pi = exact.momentum(k as f64 * 0.01).unwrap();
            worst = worst.max((lgvi.state().momentum(0) - Vec3::from(pi)).amax());
        }
        assert!(
            worst <= 1e-11,
            "max |Π − Π_exact| = {worst:.2e} over T = 10"
        );
    }
}
