//! SO(3) and so(3): round trips, the Cayley map against the exponential (`cay(f) = exp(2f^) +
//! O(|f|³)`, [HLW06] §IV.8.3), orthonormality to round-off, the Cayley equation of the LGVI
//! against its matrix form `(a)^ = F J_d − J_d Fᵀ` ([LLM07] eq. (23)) for a non-diagonal inertia.

use crate::common::loglog_slope;
use marsden::NewtonOptions;
use marsden::error::{Error, InputError};
use marsden::lie::body::Inertia;
use marsden::lie::cayley::solve_cayley;
use marsden::lie::so3::{self, Mat3, Vec3};

fn samples() -> Vec<Vec3> {
    vec![
        Vec3::new(0.3, -0.2, 0.1),
        Vec3::new(-1.2, 0.4, 2.0),
        Vec3::new(0.0, 0.0, 3.0),
        Vec3::new(1e-9, -2e-9, 0.5e-9),
        Vec3::new(2.0, 1.0, -1.5),
        Vec3::new(3.0, 0.0, 0.1),
    ]
}

#[test]
fn hat_vee_round_trip_and_cross_product() {
    for xi in samples() {
        assert_eq!(so3::vee(&so3::hat(&xi)), xi);
        let v = Vec3::new(0.7, -0.1, 0.25);
        assert!((so3::hat(&xi) * v - xi.cross(&v)).amax() <= 1e-15);
    }
}

#[test]
fn exp_is_a_rotation_and_log_inverts_it() {
    for xi in samples() {
        let r = so3::exp(&xi);
        assert!(so3::orthogonality_defect(&r) <= 1e-15, "{xi}");
        assert!((r.determinant() - 1.0).abs() <= 1e-15);
        // log returns the angle in [0, π]: compare rotations, and vectors below π.
        let back = so3::log(&r);
        assert!((so3::exp(&back) - r).amax() <= 1e-15);
        if xi.norm() < std::f64::consts::PI {
            assert!(
                (back - xi).amax() <= 1e-14 * xi.norm().max(1e-9),
                "{xi} vs {back}"
            );
        }
    }
}

/// At and near a half turn the logarithm reads the axis off the symmetric part.
#[test]
fn log_near_a_half_turn() {
    let n = Vec3::new(0.6, 0.0, -0.8);
    for angle in [std::f64::consts::PI, std::f64::consts::PI - 1e-10, 1e-12] {
        let r = so3::exp(&(angle * n));
        let back = so3::log(&r);
        assert!((so3::exp(&back) - r).amax() <= 1e-15, "{angle}: {back}");
        assert!(
            (back.norm() - angle).abs() <= 1e-12 * angle.max(1e-3),
            "{angle}: {back}"
        );
    }
}

#[test]
fn cayley_round_trip_and_orthonormal() {
    for f in samples() {
        let r = so3::cay(&f);
        assert!(so3::orthogonality_defect(&r) <= 1e-15, "{f}");
        assert!((r.determinant() - 1.0).abs() <= 1e-15);
        let back = so3::cay_inv(&r).unwrap();
        assert!(
            (back - f).amax() <= 1e-14 * f.norm().max(1e-9),
            "{f} vs {back}"
        );
        // The rotation angle is 2 arctan |f|.
        let angle = so3::log(&r).norm();
        assert!((angle - 2.0 * f.norm().atan()).abs() <= 1e-14);
    }
    // A half turn has no Cayley parameters.
    assert!(so3::cay_inv(&so3::exp(&Vec3::new(std::f64::consts::PI, 0.0, 0.0))).is_none());
}

/// `cay(f) − exp(2f^) = O(|f|³)`: the fitted slope of the difference is 3.
#[test]
fn cayley_agrees_with_the_exponential_to_third_order() {
    let direction = Vec3::new(0.6, -0.3, 0.74);
    let sizes = [0.1, 0.05, 0.025, 0.0125];
    let errors: Vec<f64> = sizes
        .iter()
        .map(|s| (so3::cay(&(*s * direction)) - so3::exp(&(2.0 * *s * direction))).amax())
        .collect();
    let slope = loglog_slope(&sizes, &errors);
    assert!(
        (slope - 3.0).abs() < 0.05,
        "slope {slope}, errors {errors:?}"
    );
}

#[test]
fn quaternions_and_rotation_vectors_round_trip() {
    for xi in samples() {
        let r = so3::exp(&xi);
        let q = so3::to_quaternion(&r);
        assert!(q[0] >= 0.0);
        let norm: f64 = q.iter().map(|c| c * c).sum();
        assert!((norm - 1.0).abs() <= 4e-16);
        assert!((so3::from_quaternion(&q).unwrap() - r).amax() <= 1e-15);
        assert!((so3::from_rotation_vector(&so3::to_rotation_vector(&r)) - r).amax() <= 1e-15);
    }
    // A quarter turn about e₃: q = (cos π/4, 0, 0, sin π/4).
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let r = so3::from_quaternion(&[2.0 * s, 0.0, 0.0, 2.0 * s]).unwrap();
    let expected = Mat3::new(0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0);
    assert!((r - expected).amax() <= 1e-15);
    assert!(so3::from_quaternion(&[0.0; 4]).is_err());
}

/// A typed attitude within 1e-10 of SO(3) is re-orthonormalised to round-off; beyond, or a
/// reflection, is a typed error with the defect and the determinant.
#[test]
fn typed_attitudes_are_checked_and_reorthonormalised() {
    let r = so3::exp(&Vec3::new(0.4, -0.9, 0.2));
    let mut rows = so3::rows(&r);
    rows[1] += 5e-11;
    rows[5] -= 3e-11;
    let fixed = so3::attitude("R0", &rows).unwrap();
    assert!(so3::orthogonality_defect(&fixed) <= 4e-16);
    assert!((fixed - r).amax() <= 1e-10);
    rows[1] += 1e-6;
    match so3::attitude("R0", &rows) {
        Err(Error::Input(InputError::NotARotation { defect, .. })) => {
            assert!(defect > 1e-7 && defect < 2e-6, "{defect}")
        }
        other => panic!("{other:?}"),
    }
    let reflection = so3::rows(&(-r));
    match so3::attitude("R0", &reflection) {
        Err(Error::Input(InputError::NotARotation { determinant, .. })) => {
            assert!((determinant + 1.0).abs() < 1e-12)
        }
        other => panic!("{other:?}"),
    }
}

/// The Cayley equation `a + a×f + (a·f)f − 2Jf = 0` solved by Newton gives `F = cay(f)` with
/// `vee(F J_d − J_d Fᵀ) = a` (the matrix form, independent of the algebra that derived the
/// equation), for a non-diagonal inertia, in 2–4 iterations.
#[test]
fn cayley_equation_solves_the_matrix_momentum_equation() {
    let inertia = Inertia::matrix(&[3.0, 0.4, -0.2, 0.4, 2.5, 0.3, -0.2, 0.3, 1.7]).unwrap();
    let jd = inertia.nonstandard();
    let options = NewtonOptions {
        residual_tolerance: 1e-15,
        ..NewtonOptions::default()
    };
    for a in [
        Vec3::new(0.1, -0.05, 0.2),
        Vec3::new(0.8, 1.0, -0.7),
        Vec3::zeros(),
    ] {
        let (f, report) = solve_cayley(inertia.tensor(), &a, &options).unwrap();
        let turn = so3::cay(&f);
        let matrix = turn * jd - jd * turn.transpose();
        // vee halves the skew part; F J_d − J_d Fᵀ is skew already.
        assert!(
            (so3::vee(&matrix) - a).amax() <= 1e-14 * a.amax().max(1.0),
            "{a}"
        );
        assert!((matrix + matrix.transpose()).amax() <= 1e-14);
        assert!(report.iterations <= 5, "{report:?}");
    }
}
