//! Tangent sensitivities against central finite differences of whole runs, for every kind of
//! rule (midpoint, trapezoid, α, Galerkin, a composition) and with forces.

use super::common::{central_differences, integrator, relative_distance, state, tangent_jacobian};
use crate::common::tight;
use marsden::discrete::rules::{Composition, CompositionScheme, Galerkin};
use marsden::systems::{DampedDrivenPendulum, Kepler, Pendulum};
use marsden::{GeneralizedMidpoint, Integrator, Midpoint, Rule, TimeGrid, Trapezoid};

/// Kepler e = 0.6 from pericentre, gauss-3, h = 0.01, 1000 steps: ∂(q, p)/∂(q₀, p₀) agrees with
/// central differences (ε = 1e-5) to 1e-6 relative.
#[test]
fn kepler_gauss3_1000_steps_matches_central_differences() {
    let (q, p) = Kepler::pericentre(0.6);
    let start = state(&q, &p);
    let grid = TimeGrid::new(0.0, 0.01, 1000).unwrap();
    let make = || integrator(Galerkin::gauss(3).unwrap().discretize(Kepler::default()));
    let ad = tangent_jacobian(&make, &start, &grid);
    let fd = central_differences(&make, &start, &grid, 1e-5);
    let d = relative_distance(&ad, &fd);
    println!("kepler gauss-3: relative distance to central differences {d:.2e}");
    assert!(d <= 1e-6, "relative distance {d:e}");
}

/// Every kind of rule on the pendulum (200 steps of 0.05) against central differences.
#[test]
fn every_rule_matches_central_differences_on_the_pendulum() {
    let start = state(&[1.2], &[0.4]);
    let grid = TimeGrid::new(0.0, 0.05, 200).unwrap();
    let l = Pendulum::default();
    let check = |name: &str, ad: Vec<f64>, fd: Vec<f64>| {
        let d = relative_distance(&ad, &fd);
        println!("pendulum / {name}: relative distance {d:.2e}");
        assert!(d <= 1e-6, "{name}: relative distance {d:e}");
    };
    macro_rules! rule {
        ($name:expr, $rule:expr) => {{
            let make = || integrator($rule.discretize(l));
            check(
                $name,
                tangent_jacobian(&make, &start, &grid),
                central_differences(&make, &start, &grid, 1e-5),
            );
        }};
    }
    rule!("midpoint", Midpoint);
    rule!("trapezoid", Trapezoid);
    rule!("alpha(0.3)", GeneralizedMidpoint { alpha: 0.3 });
    rule!("lobatto-3", Galerkin::lobatto(3).unwrap());
    rule!("gauss-2", Galerkin::gauss(2).unwrap());
    rule!(
        "suzuki-4(midpoint)",
        Composition::new(Midpoint, CompositionScheme::Suzuki4)
    );
    // A composition of Verlet steps: through the general path (the explicit one keeps no stages).
    let make = || {
        Integrator::new(Composition::new(Trapezoid, CompositionScheme::Suzuki4).discretize(l))
            .with_options(tight())
            .unwrap()
            .with_fast_paths(false)
    };
    check(
        "suzuki-4(trapezoid)",
        tangent_jacobian(&make, &start, &grid),
        central_differences(&make, &start, &grid, 1e-5),
    );
}

/// A forced system (the damped driven pendulum, discrete Lagrange–d'Alembert forces) with the
/// midpoint and gauss-2 rules against central differences over 400 steps of 0.05.
#[test]
fn forced_pendulum_matches_central_differences() {
    let start = state(&[0.5], &[0.1]);
    let grid = TimeGrid::new(0.0, 0.05, 400).unwrap();
    let sys = DampedDrivenPendulum::default();
    let make = || {
        Integrator::new(Midpoint.discretize(sys))
            .with_force(Midpoint.discretize_force(sys, 1))
            .with_options(tight())
            .unwrap()
    };
    let d = relative_distance(
        &tangent_jacobian(&make, &start, &grid),
        &central_differences(&make, &start, &grid, 1e-5),
    );
    println!("damped driven pendulum / midpoint: relative distance {d:.2e}");
    assert!(d <= 1e-6, "midpoint: relative distance {d:e}");
    let rule = Galerkin::gauss(2).unwrap();
    let make = || {
        Integrator::new(rule.discretize(sys))
            .with_force(rule.discretize_force(sys, 1))
            .with_options(tight())
            .unwrap()
    };
    let d = relative_distance(
        &tangent_jacobian(&make, &start, &grid),
        &central_differences(&make, &start, &grid, 1e-5),
    );
    println!("damped driven pendulum / gauss-2: relative distance {d:.2e}");
    assert!(d <= 1e-6, "gauss-2: relative distance {d:e}");
}
