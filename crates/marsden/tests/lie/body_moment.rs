//! The body moment `M` (left-trivialised derivative of `−U`, [LLM07] eq. (9)) and `∂U/∂x` by AD,
//! against central finite differences of `U` along `R exp(εξ^)` and `x + εe_a`; the heavy top's
//! closed form `M = mgl (Rᵀe₃) × e₃`; a bad inertia is a typed error with the numbers.

use marsden::Scalar;
use marsden::error::{Error, InputError};
use marsden::lie::body::Inertia;
use marsden::lie::potential::{Configuration, Loads, NoLoads, RigidPotential, UniformGravity};
use marsden::lie::so3::{self, Vec3};

/// Two bodies coupled through their attitudes and positions, depending on time (no symmetry).
struct Coupled;

impl RigidPotential for Coupled {
    fn value<S: Scalar>(&self, t: S, r: &[S], x: &[S]) -> S {
        // (R₁e₁)·(R₂e₂) (1 + 0.3t) + 2 (e₃·R₁e₃)² + sin(R₁₂) + x₁·(R₂e₁) + ½|x₁ − x₂|²
        let column = |b: usize, c: usize| [r[9 * b + c], r[9 * b + 3 + c], r[9 * b + 6 + c]];
        let (a, b) = (column(0, 0), column(1, 1));
        let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let e1 = column(1, 0);
        let mut u = dot * (t * 0.3 + 1.0) + r[8].powi(2) * 2.0 + r[1].sin();
        for k in 0..3 {
            u += x[k] * e1[k] + (x[k] - x[3 + k]).powi(2) * 0.5;
        }
        u
    }
}

fn value(r: &[f64], x: &[f64]) -> f64 {
    Coupled.value(0.7, r, x)
}

#[test]
fn moment_by_ad_matches_finite_differences_along_r_exp_xi() {
    let r1 = so3::exp(&Vec3::new(0.3, -0.8, 1.1));
    let r2 = so3::exp(&Vec3::new(-1.4, 0.2, 0.5));
    let mut rotations = so3::rows(&r1).to_vec();
    rotations.extend_from_slice(&so3::rows(&r2));
    let positions = [0.2, -0.4, 1.0, -0.3, 0.5, 0.8];
    let free = [0, 1];
    let mut loads = Loads::new(2);
    let config = Configuration {
        t: 0.7,
        rotations: &rotations,
        positions: &positions,
        free: &free,
    };
    loads.evaluate(&Coupled, &NoLoads, config);
    let eps = 1e-5;
    for body in 0..2 {
        for a in 0..3 {
            let mut xi = Vec3::zeros();
            xi[a] = eps;
            let turned = |sign: f64| {
                let r = if body == 0 { r1 } else { r2 };
                let mut rows = rotations.clone();
                rows[9 * body..9 * body + 9]
                    .copy_from_slice(&so3::rows(&(r * so3::exp(&(sign * xi)))));
                value(&rows, &positions)
            };
            // dU/dε = −M·ξ.
            let fd = -(turned(1.0) - turned(-1.0)) / (2.0 * eps);
            let ad = loads.moments[body][a];
            assert!(
                (fd - ad).abs() <= 1e-9 * ad.abs().max(1.0),
                "M[{body}][{a}]: {ad} vs {fd}"
            );
            let moved = |sign: f64| {
                let mut x = positions;
                x[3 * body + a] += sign * eps;
                value(&rotations, &x)
            };
            let fd = -(moved(1.0) - moved(-1.0)) / (2.0 * eps);
            let ad = loads.forces[body][a];
            assert!(
                (fd - ad).abs() <= 1e-9 * ad.abs().max(1.0),
                "f[{body}][{a}]: {ad} vs {fd}"
            );
        }
    }
}

/// R20's potential `U = mgl e₃·(R e₃)`: `M = mgl (Rᵀe₃) × e₃ = mgl (R₃₂, −R₃₁, 0)`.
#[test]
fn heavy_top_moment_is_mgl_gamma_cross_e3() {
    let r = so3::exp(&Vec3::new(0.4, 1.2, -0.7));
    let rotations = so3::rows(&r);
    let mut loads = Loads::new(1);
    let config = Configuration {
        t: 0.0,
        rotations: &rotations,
        positions: &[0.0; 3],
        free: &[],
    };
    loads.evaluate(&UniformGravity::top(20.0), &NoLoads, config);
    let gamma = r.transpose() * Vec3::z();
    let expected = 20.0 * gamma.cross(&Vec3::z());
    assert!(
        (loads.moments[0] - expected).amax() <= 1e-14,
        "{} vs {expected}",
        loads.moments[0]
    );
    assert_eq!(loads.forces[0], Vec3::zeros());
}

#[test]
fn bad_inertia_is_a_typed_error_with_the_numbers() {
    let reason = |rows: [f64; 9]| match Inertia::matrix(&rows) {
        Err(Error::Input(InputError::InvalidInertia {
            reason, principal, ..
        })) => (reason, principal),
        other => panic!("{other:?}"),
    };
    let (why, _) = reason([1.0, 0.5, 0.0, 0.4, 1.0, 0.0, 0.0, 0.0, 1.0]);
    assert!(why.contains("not symmetric"), "{why}");
    let (why, principal) = reason([1.0, 0.0, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0, 1.0]);
    assert!(why.contains("positive definite"), "{why}");
    assert_eq!(principal, [-2.0, 1.0, 1.0]);
    let (why, principal) = reason([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.5]);
    assert!(why.contains("triangle"), "{why}");
    assert_eq!(principal, [1.0, 1.0, 2.5]);
    assert!(matches!(
        Inertia::principal([1.0, f64::NAN, 1.0]),
        Err(Error::Input(InputError::NonFinite { .. }))
    ));
    // A flat body (J₃ = J₁ + J₂) is a mass distribution: accepted.
    assert!(Inertia::principal([1.0, 2.0, 3.0]).is_ok());
    // R19's test body violates 2 ≤ 1 + 2/3: refused as a mass distribution, accepted as a
    // positive definite J, with J_d = ½ tr(J) I − J indefinite.
    let (why, _) = reason([2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0 / 3.0]);
    assert!(why.contains("triangle"), "{why}");
    let j = Inertia::principal_unphysical([2.0, 1.0, 2.0 / 3.0]).unwrap();
    let jd = j.nonstandard();
    assert!((jd.diagonal() - Vec3::new(-1.0 / 6.0, 5.0 / 6.0, 7.0 / 6.0)).amax() <= 1e-15);
}
