//! Group actions, momentum maps and symmetry checks: declared symmetries are confirmed to
//! round-off, a declared non-symmetry is reported with the size of ⟨dL, ξ_TQ⟩, bad generators
//! are typed errors naming the symmetry, SO(3) momentum maps are equivariant, and J_L = FL*J_H.
#![allow(clippy::unwrap_used, clippy::expect_used)] // tests may unwrap

use marsden::error::{InputError, SetupError};
use marsden::hamiltonian::{Hamiltonian, HamiltonianLagrangian};
use marsden::symmetry::check::{
    DEFAULT_TOLERANCE, check_discrete, check_hamiltonian, check_lagrangian,
    discrete_invariance_defect,
};
use marsden::symmetry::{
    AxisRotation, DeclaresSymmetries, GroupAction, Rotations, Sample, cotangent_lift,
    equivariance_defect, lagrangian_momentum_map, momentum_map, validate,
};
use marsden::systems::{HenonHeiles, Kepler, NBody};
use marsden::{Error, Lagrangian, Midpoint, Rule, Scalar, Trapezoid};
use std::f64::consts::PI;

#[test]
fn kepler_rotation_is_a_symmetry_of_l_ld_and_h() {
    let kepler = Kepler::default();
    let rotation = AxisRotation::planar(1);
    let samples = Sample::random(2, 50, 7, 2.0);
    let l = check_lagrangian(&kepler, &rotation, &samples, DEFAULT_TOLERANCE).unwrap();
    assert!(l.is_symmetry(), "{l}");
    assert!(l.generators[0].max_relative < 1e-15, "{l}");
    for report in [
        check_discrete(
            &Midpoint.discretize(kepler),
            &rotation,
            0.1,
            &samples,
            DEFAULT_TOLERANCE,
        ),
        check_discrete(
            &Trapezoid.discretize(kepler),
            &rotation,
            0.1,
            &samples,
            DEFAULT_TOLERANCE,
        ),
        check_hamiltonian(&kepler, &rotation, &samples, DEFAULT_TOLERANCE),
    ] {
        let report = report.unwrap();
        assert!(report.is_symmetry(), "{report}");
        assert!(report.generators[0].max_relative < 1e-14, "{report}");
    }
    // The catalog declares it.
    assert_eq!(kepler.symmetries()[0].name(), rotation.name());
}

#[test]
fn henon_heiles_rotation_is_reported_as_no_symmetry_with_its_defect() {
    let hh = HenonHeiles::default();
    let rotation = AxisRotation::planar(1);
    // ⟨dL, ξ_TQ⟩ = −∇V·(−y, x) = −λ(x³ − 3xy²): at (0.5, 0.2) it is −0.065.
    let sample = [Sample::new(0.0, &[0.5, 0.2], &[0.3, -0.1])];
    let report = check_lagrangian(&hh, &rotation, &sample, DEFAULT_TOLERANCE).unwrap();
    assert!(!report.is_symmetry());
    let worst = report.worst().unwrap();
    assert!((worst.max_defect - 0.065).abs() < 1e-15, "{report}");
    assert!(worst.max_relative > 0.1, "{report}");
    let message = report.to_string();
    assert!(message.contains("is NOT a symmetry of L"), "{message}");
    match report.into_result() {
        Err(Error::Setup(SetupError::NotASymmetry {
            symmetry,
            of,
            defect,
            ..
        })) => {
            assert_eq!(symmetry, "planar rotations SO(2) of 1 particles");
            assert_eq!(of, "L");
            assert!((defect - 0.065).abs() < 1e-15);
        }
        other => panic!("expected NotASymmetry, got {other:?}"),
    }
    // Random samples: the discrete L_d is not invariant either.
    let samples = Sample::random(2, 20, 3, 0.5);
    let ld = check_discrete(
        &Midpoint.discretize(hh),
        &rotation,
        0.1,
        &samples,
        DEFAULT_TOLERANCE,
    );
    assert!(!ld.unwrap().is_symmetry());
    // What Hénon–Heiles does have is the discrete symmetry of order three.
    let ld = Midpoint.discretize(hh);
    let third = discrete_invariance_defect(&ld, &rotation, &[2.0 * PI / 3.0], 0.1, &samples);
    assert!(third.unwrap() < 1e-14);
    let other = discrete_invariance_defect(&ld, &rotation, &[0.3], 0.1, &samples);
    assert!(other.unwrap() > 1e-3);
}

/// A user-defined action whose generator has a singular point: ξ_Q(q) = q/|q| (radial).
struct Radial;
impl GroupAction for Radial {
    fn name(&self) -> String {
        "radial unit field".into()
    }
    fn dof(&self) -> usize {
        2
    }
    fn algebra_dim(&self) -> usize {
        1
    }
    fn generator<S: Scalar>(&self, _a: usize, q: &[S], out: &mut [S]) {
        let r = (q[0] * q[0] + q[1] * q[1]).sqrt();
        out[0] = q[0] / r;
        out[1] = q[1] / r;
    }
}

/// A user-defined action that forgets to write its second component.
struct Forgetful;
impl GroupAction for Forgetful {
    fn name(&self) -> String {
        "forgetful shift".into()
    }
    fn dof(&self) -> usize {
        2
    }
    fn algebra_dim(&self) -> usize {
        1
    }
    fn generator<S: Scalar>(&self, _a: usize, _q: &[S], out: &mut [S]) {
        out[0] = S::from(1.0);
    }
}

#[test]
fn bad_generators_are_typed_errors_naming_the_symmetry() {
    let kepler = Kepler::default();
    let samples = Sample::random(2, 3, 1, 1.0);
    // Wrong number of components: SO(3) of two particles (6 components) on a 2-dof system.
    match check_lagrangian(&kepler, &Rotations::new(2), &samples, DEFAULT_TOLERANCE) {
        Err(e @ Error::Input(InputError::SymmetryDimension { .. })) => {
            let message = e.to_string();
            assert!(
                message.contains("rotations SO(3) of 2 particles"),
                "{message}"
            );
            assert!(
                message.contains("6 components") && message.contains("2 degrees"),
                "{message}"
            );
        }
        other => panic!("expected SymmetryDimension, got {other:?}"),
    }
    // Not finite: the radial field at the origin, and a zero rotation axis.
    match validate(&Radial, 2, &[0.0, 0.0]) {
        Err(Error::Input(InputError::InvalidGenerator {
            symmetry,
            generator,
            component,
            value,
            ..
        })) => {
            assert_eq!(symmetry, "radial unit field");
            assert_eq!((generator, component), (0, 0));
            assert!(value.is_nan());
        }
        other => panic!("expected InvalidGenerator, got {other:?}"),
    }
    assert!(validate(&Radial, 2, &[1.0, 0.0]).is_ok());
    let zero_axis = AxisRotation::about(1, [0.0, 0.0, 0.0]);
    assert!(matches!(
        validate(&zero_axis, 3, &[1.0, 2.0, 3.0]),
        Err(Error::Input(InputError::InvalidGenerator { .. }))
    ));
    // A component left unwritten is caught too.
    match validate(&Forgetful, 2, &[1.0, 1.0]) {
        Err(e @ Error::Input(InputError::InvalidGenerator { component: 1, .. })) => {
            assert!(e.to_string().contains("forgetful shift"));
        }
        other => panic!("expected InvalidGenerator for component 1, got {other:?}"),
    }
}

#[test]
fn so3_momentum_map_is_equivariant() {
    let rotations = Rotations::new(3);
    let s = &Sample::random(9, 1, 11, 2.0)[0];
    let xi = [0.3, -0.7, 1.1];
    let defect = equivariance_defect(&rotations, &xi, &s.q, &s.v).unwrap();
    assert!(defect < 1e-14, "equivariance defect {defect:e}");
    // The check is not vacuous: the momentum map does move under the group.
    let (mut j, mut rj) = ([0.0; 3], [0.0; 3]);
    momentum_map(&rotations, &s.q, &s.v, &mut j);
    marsden::symmetry::FiniteAction::coadjoint(&rotations, &xi, &j, &mut rj);
    let moved = j
        .iter()
        .zip(&rj)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(moved > 0.1, "{moved}");
    // J_H is the total angular momentum Σ q × p.
    let l = NBody::angular_momentum(&s.q, &s.v);
    for a in 0..3 {
        assert!((j[a] - l[a]).abs() < 1e-14);
    }
    // Cotangent lift of ê₂: (e₂ × q, e₂ × p).
    let (mut dq, mut dp) = ([0.0; 9], [0.0; 9]);
    cotangent_lift(&rotations, 2, &s.q, &s.v, &mut dq, &mut dp);
    for i in 0..3 {
        let (q, p) = (&s.q[3 * i..3 * i + 3], &s.v[3 * i..3 * i + 3]);
        assert_eq!(&dq[3 * i..3 * i + 3], &[-q[1], q[0], 0.0]);
        assert_eq!(&dp[3 * i..3 * i + 3], &[-p[1], p[0], 0.0]);
    }
}

/// A charged particle in the plane in a uniform magnetic field B ẑ (symmetric gauge):
/// L = ½|v|² + (B/2)(x v_y − y v_x), so p = v + A(q) with A = (B/2)(−y, x).
#[derive(Clone, Copy)]
struct Magnetic {
    b: f64,
}
impl Lagrangian for Magnetic {
    fn dof(&self) -> usize {
        2
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        (v[0] * v[0] + v[1] * v[1]) * 0.5 + (q[0] * v[1] - q[1] * v[0]) * (0.5 * self.b)
    }
}
/// Its Hamiltonian H = ½|p − A(q)|².
impl Hamiltonian for Magnetic {
    fn dof(&self) -> usize {
        2
    }
    fn hamiltonian<S: Scalar>(&self, _t: S, q: &[S], p: &[S]) -> S {
        let (px, py) = (p[0] + q[1] * (0.5 * self.b), p[1] - q[0] * (0.5 * self.b));
        (px * px + py * py) * 0.5
    }
}

#[test]
fn lagrangian_momentum_map_is_the_pullback_of_the_hamiltonian_one() {
    let system = Magnetic { b: 1.7 };
    let rotation = AxisRotation::planar(1);
    for s in Sample::random(2, 10, 5, 1.5) {
        let (q, v) = (&s.q, &s.v);
        let mut j_l = [0.0];
        lagrangian_momentum_map(&system, &rotation, 0.0, q, v, &mut j_l);
        // FL(q, v) = v + A(q); J_H(q, p) = x p_y − y p_x.
        let p = [v[0] - 0.85 * q[1], v[1] + 0.85 * q[0]];
        let mut j_h = [0.0];
        momentum_map(&rotation, q, &p, &mut j_h);
        let kinetic = q[0] * v[1] - q[1] * v[0];
        let canonical = kinetic + 0.85 * (q[0] * q[0] + q[1] * q[1]);
        assert!((j_l[0] - j_h[0]).abs() < 1e-14 && (j_h[0] - canonical).abs() < 1e-14);
        // The same through the Lagrangian built from H by FL (Newton inside, exact by AD).
        let from_h = HamiltonianLagrangian::new(system);
        let mut j_lh = [0.0];
        lagrangian_momentum_map(&from_h, &rotation, 0.0, q, v, &mut j_lh);
        assert!(
            (j_lh[0] - j_h[0]).abs() < 1e-13,
            "{} vs {}",
            j_lh[0],
            j_h[0]
        );
    }
    // Rotations are a symmetry of both forms (the gauge is symmetric).
    let samples = Sample::random(2, 20, 9, 1.0);
    assert!(
        check_lagrangian(&system, &rotation, &samples, DEFAULT_TOLERANCE)
            .unwrap()
            .is_symmetry()
    );
    assert!(
        check_hamiltonian(&system, &rotation, &samples, DEFAULT_TOLERANCE)
            .unwrap()
            .is_symmetry()
    );
}
