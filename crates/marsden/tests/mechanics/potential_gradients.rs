//! Hand-written potential gradients and Hessians agree with the AD defaults
//! (`marsden::mechanics::potential`), and large separable systems skip the dense AD jet.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::excessive_precision)]

use marsden::error::SetupError;
use marsden::mechanics::potential::{gradient_defect, hessian_defect};
use marsden::systems::{Chain, Kepler, NBody, Pendulum};
use marsden::{Error, Initial, Lagrangian, MassMatrix, Problem, Scalar, Structure, TimeGrid};

fn cloud(bodies: usize) -> Vec<f64> {
    (0..3 * bodies)
        .map(|i| (i as f64 * 0.731).sin() * 1.3)
        .collect()
}

#[test]
fn kepler_and_pendulum_derivatives_match_ad() {
    for q in [[0.4, -0.3], [1.7, 0.05], [-0.2, -2.0]] {
        assert!(gradient_defect(&Kepler { mu: 1.3 }, 0.0, &q) <= 4.0 * f64::EPSILON);
        assert!(hessian_defect(&Kepler { mu: 1.3 }, 0.0, &q) <= 8.0 * f64::EPSILON);
    }
    let pendulum = Pendulum {
        m: 2.0,
        l: 0.5,
        g: 9.81,
    };
    for q in [-3.0, 0.1, 1.5, 2.9] {
        assert!(gradient_defect(&pendulum, 0.0, &[q]) <= 2.0 * f64::EPSILON);
        assert!(hessian_defect(&pendulum, 0.0, &[q]) <= 2.0 * f64::EPSILON);
    }
}

#[test]
fn nbody_hand_gradient_matches_ad() {
    // 21 bodies: two full chunks of the vectorised kernel and a padded one.
    let masses: Vec<f64> = (0..21).map(|i| 1.0 + 0.1 * i as f64).collect();
    let q = cloud(21);
    for softening in [0.0, 0.01, 0.3] {
        let system = NBody {
            masses: masses.clone(),
            g: 0.7,
            softening,
        };
        let d = gradient_defect(&system, 0.0, &q);
        assert!(d <= 64.0 * f64::EPSILON, "softening {softening}: {d:e}");
    }
}

#[test]
fn chain_derivatives_match_ad_and_are_tridiagonal() {
    let chain = Chain {
        n: 12,
        m: 1.5,
        k: 0.8,
        alpha: 0.25,
        beta: 1.2,
    };
    let q: Vec<f64> = (0..12).map(|i| (i as f64 * 0.9).cos() * 0.4).collect();
    assert_eq!(chain.potential_bandwidth(), Some(1));
    assert!(gradient_defect(&chain, 0.0, &q) <= 8.0 * f64::EPSILON);
    // Entries outside the band count in full: zero defect there proves the bandwidth.
    assert!(hessian_defect(&chain, 0.0, &q) <= 8.0 * f64::EPSILON);
}

#[test]
fn a_large_nbody_problem_is_set_up_without_the_dense_jet() {
    // 1024 bodies: the AD jet would take ~10⁵ evaluations of an O(N²) Lagrangian.
    let bodies = 1024;
    let system = NBody {
        masses: vec![1.0 / bodies as f64; bodies],
        g: 1.0,
        softening: 0.01,
    };
    let q = cloud(bodies);
    let v: Vec<f64> = q.iter().map(|x| 0.1 * x).collect();
    let grid = TimeGrid::new(0.0, 1e-3, 1).unwrap();
    let start = std::time::Instant::now();
    let problem = Problem::new(system, Initial::velocity(&q, &v), grid).unwrap();
    assert!(start.elapsed().as_secs_f64() < 20.0);
    let p = &problem.start().p;
    assert_eq!(p[5], v[5] / bodies as f64);
}

/// Separable in name only, with many degrees of freedom: the probes catch it.
#[derive(Debug)]
struct FalselySeparable(usize);
impl Lagrangian for FalselySeparable {
    fn dof(&self) -> usize {
        self.0
    }
    fn lagrangian<S: Scalar>(&self, _t: S, q: &[S], v: &[S]) -> S {
        let mut l = S::from(0.0);
        for (qi, vi) in q.iter().zip(v) {
            l += (qi.cos() + 2.0) * *vi * *vi * 0.5;
        }
        l
    }
    fn structure(&self) -> Structure {
        Structure::Separable {
            mass: MassMatrix::Diagonal(vec![3.0; self.0]),
        }
    }
}

#[test]
fn a_false_declaration_is_caught_by_the_probes() {
    let n = 40;
    let grid = TimeGrid::new(0.0, 0.1, 1).unwrap();
    let q = vec![0.3; n];
    let err = Problem::new(
        FalselySeparable(n),
        Initial::velocity(&q, &vec![1.0; n]),
        grid,
    )
    .unwrap_err();
    assert!(
        matches!(err, Error::Setup(SetupError::StructureMismatch { .. })),
        "{err:?}"
    );
}
