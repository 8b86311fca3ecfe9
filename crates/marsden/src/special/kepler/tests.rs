//! Tests of Kepler's equation and of the exact two-body propagation.

use super::*;
use proptest::prelude::*;

const Q0: [f64; 2] = [0.4, 0.0];
const P0: [f64; 2] = [0.0, 2.0];

fn reference() -> KeplerOrbit<2> {
    KeplerOrbit::new(1.0, Q0, P0).unwrap()
}

fn max_diff<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, crate::numerics::dense::max_or_nan)
}

fn rotate(v: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

#[test]
fn project_reference_values() {
    let orbit = reference();
    #[rustfmt::skip]
    let cases = [
        (1.0, [-0.6289481768266243, 0.7996647309700393], [-0.9825156909388113, -0.0227631700974305]),
        (PI, [-1.6, 0.0], [0.0, -0.5]),
        (10.0, [-1.5350235919098134, -0.2836684064997811], [0.2271507320774986, -0.4791877582032195]),
    ];
    for (t, q, p) in cases {
        let (qt, pt) = orbit.state(t).unwrap();
        let err = max_diff(&qt, &q).max(max_diff(&pt, &p));
        assert!(err < 2e-15, "t={t}: {qt:?} {pt:?}, error {err:e}");
    }
}

#[test]
fn elements_of_the_reference_orbit() {
    let orbit = reference();
    assert_eq!(orbit.energy(), -0.5);
    assert_eq!(orbit.semi_major_axis(), 1.0);
    assert!((orbit.eccentricity() - 0.6).abs() < 1e-16);
    assert!((orbit.angular_momentum() - 0.8).abs() < 1e-16);
    assert!((orbit.period() - TAU).abs() < 1e-15);
    assert_eq!(orbit.mean_anomaly_at_epoch(), 0.0);
    let ev = orbit.eccentricity_vector();
    assert!((ev[0] - 0.6).abs() < 1e-15 && ev[1].abs() < 1e-16);
}

#[test]
fn conserves_energy_angular_momentum_and_is_periodic() {
    let orbit = reference();
    for k in 0..200 {
        let t = -37.0 + 0.41 * f64::from(k);
        let (q, p) = orbit.state(t).unwrap();
        assert!((kepler_energy(1.0, &q, &p) + 0.5).abs() < 1e-14, "t={t}");
        assert!((q[0] * p[1] - q[1] * p[0] - 0.8).abs() < 1e-14, "t={t}");
        let (q2, p2) = orbit.state(t + TAU).unwrap();
        assert!(max_diff(&q, &q2).max(max_diff(&p, &p2)) < 1e-13, "t={t}");
    }
    let (q, p) = orbit.state(TAU).unwrap();
    assert!(max_diff(&q, &Q0).max(max_diff(&p, &P0)) < 1e-15);
}

#[test]
fn satisfies_the_equation_of_motion() {
    let orbit = KeplerOrbit::new(2.5, [0.3, -1.1, 0.2], [0.9, 0.4, -0.3]).unwrap();
    let h = 1e-4;
    for t in [-2.0, 0.3, 5.0] {
        let (q, p) = orbit.state(t).unwrap();
        let (qp, pp) = orbit.state(t + h).unwrap();
        let (qm, pm) = orbit.state(t - h).unwrap();
        let r3 = q.iter().map(|x| x * x).sum::<f64>().powf(1.5);
        for i in 0..3 {
            assert!(((qp[i] - qm[i]) / (2.0 * h) - p[i]).abs() < 1e-7);
            assert!(((pp[i] - pm[i]) / (2.0 * h) + 2.5 * q[i] / r3).abs() < 1e-7);
        }
    }
}

#[test]
fn rotated_and_reversed_orbits() {
    let orbit = reference();
    for angle in [0.7, -2.3, 3.0] {
        let rotated = KeplerOrbit::new(1.0, rotate(Q0, angle), rotate(P0, angle)).unwrap();
        for t in [0.5, 4.0, -7.5] {
            let (q, p) = orbit.state(t).unwrap();
            let (qr, pr) = rotated.state(t).unwrap();
            let err = max_diff(&qr, &rotate(q, angle)).max(max_diff(&pr, &rotate(p, angle)));
            assert!(err < 1e-14, "angle={angle}, t={t}");
        }
    }
    // Mirror image (clockwise motion, L = −0.8).
    let mirror = KeplerOrbit::new(1.0, Q0, [0.0, -2.0]).unwrap();
    assert!((mirror.angular_momentum() + 0.8).abs() < 1e-16);
    for t in [1.0, 10.0] {
        let (q, p) = orbit.state(t).unwrap();
        let (qm, pm) = mirror.state(t).unwrap();
        assert!(max_diff(&qm, &[q[0], -q[1]]).max(max_diff(&pm, &[p[0], -p[1]])) < 1e-15);
    }
}

#[test]
fn started_elsewhere_round_trips() {
    let orbit = reference();
    for t1 in [1.0, 2.9, -4.4] {
        let (q1, p1) = orbit.state(t1).unwrap();
        let later = KeplerOrbit::new(1.0, q1, p1).unwrap();
        assert!(
            (later.eccentricity() - 0.6).abs() < 1e-14,
            "{}",
            later.eccentricity()
        );
        for dt in [0.0, 0.8, -3.3, 12.0] {
            let (a, b) = (later.state(dt).unwrap(), orbit.state(t1 + dt).unwrap());
            assert!(
                max_diff(&a.0, &b.0).max(max_diff(&a.1, &b.1)) < 1e-14,
                "{t1} {dt}"
            );
        }
        let (q0, p0) = later.state(-t1).unwrap();
        let err = max_diff(&q0, &Q0).max(max_diff(&p0, &P0));
        // Back at pericentre |ṗ| = μ/r² = 6.25: a timing error of a few ulps shows in p.
        assert!(err < 4e-14, "{t1}: {q0:?} {p0:?} {err:e}");
        // Time reversal: (q, −p) runs the orbit backwards.
        let reversed = KeplerOrbit::new(1.0, q1, [-p1[0], -p1[1]]).unwrap();
        let (q, p) = reversed.state(1.7).unwrap();
        let (qb, pb) = orbit.state(t1 - 1.7).unwrap();
        assert!(max_diff(&q, &qb).max(max_diff(&p, &[-pb[0], -pb[1]])) < 1e-14);
    }
}

#[test]
fn circular_and_three_dimensional_orbits() {
    let circle = KeplerOrbit::new(1.0, [1.0, 0.0], [0.0, 1.0]).unwrap();
    assert_eq!(circle.eccentricity(), 0.0);
    for t in [0.3, 2.0, 50.0] {
        let (q, p) = circle.state(t).unwrap();
        let (s, c) = f64::sin_cos(t);
        assert!(
            max_diff(&q, &[c, s]).max(max_diff(&p, &[-s, c])) < 1e-14,
            "t={t}"
        );
    }
    // The reference orbit embedded in a tilted plane: columns u, v orthonormal.
    let (u, v) = ([0.6, 0.0, 0.8], [0.0, 1.0, 0.0]);
    let lift = |w: [f64; 2]| -> [f64; 3] { std::array::from_fn(|i| w[0] * u[i] + w[1] * v[i]) };
    let orbit3 = KeplerOrbit::new(1.0, lift(Q0), lift(P0)).unwrap();
    let l = orbit3.angular_momentum();
    assert!((l.iter().map(|x| x * x).sum::<f64>().sqrt() - 0.8).abs() < 1e-15);
    for t in [1.0, 10.0] {
        let (q, p) = reference().state(t).unwrap();
        let (q3, p3) = orbit3.state(t).unwrap();
        assert!(max_diff(&q3, &lift(q)).max(max_diff(&p3, &lift(p))) < 1e-14);
    }
}

#[test]
fn invalid_orbits_are_errors() {
    assert!(matches!(
        KeplerOrbit::new(1.0, [1.0, 0.0], [0.0, 2.0]),
        Err(SpecialError::Unbound { .. })
    ));
    assert!(matches!(
        KeplerOrbit::new(1.0, [1.0, 0.0], [0.0, 2.0_f64.sqrt()]),
        Err(SpecialError::Unbound { .. })
    ));
    assert!(matches!(
        KeplerOrbit::new(1.0, [1.0, 0.0], [0.5, 0.0]),
        Err(SpecialError::Degenerate(_))
    ));
    assert!(KeplerOrbit::new(1.0, [0.0, 0.0], [0.5, 0.0]).is_err());
    assert!(KeplerOrbit::new(0.0, Q0, P0).is_err());
    assert!(KeplerOrbit::new(1.0, [f64::NAN, 0.0], P0).is_err());
    assert!(reference().state(f64::NAN).is_err());
    assert!(solve_kepler(1.0, 1.0).is_err());
    assert!(solve_kepler(1.0, -0.1).is_err());
    assert!(solve_kepler(f64::INFINITY, 0.1).is_err());
}

#[test]
fn kepler_equation_hard_cases() {
    for e in [0.0, 1e-10, 0.5, 0.9, 0.99, 0.999999, 1.0 - 1e-15] {
        for m in [
            0.0, 1e-12, 1e-6, 0.01, 0.5, 2.0, 3.1, PI, -1.0, 7.0, -100.0, 1e6,
        ] {
            let ecc = solve_kepler(m, e).unwrap();
            // Residual relative to the size of the terms (ε·|E| is the attainable accuracy).
            let residual = ecc - e * ecc.sin() - m;
            assert!(
                residual.abs() <= 4.0 * f64::EPSILON * ecc.abs().max(1e-300),
                "{m} {e}"
            );
        }
    }
    // Small M, e → 1: E ≈ (6M)^{1/3}.
    let ecc = solve_kepler(1e-12, 1.0 - 1e-15).unwrap();
    assert!((ecc / (6e-12_f64).cbrt() - 1.0).abs() < 1e-3);
}

proptest! {
    #[test]
    fn kepler_equation_is_solved(m in -50.0_f64..50.0, e in 0.0_f64..0.9999) {
        let ecc = solve_kepler(m, e).unwrap();
        prop_assert!((ecc - e * ecc.sin() - m).abs() <= 4.0 * f64::EPSILON * ecc.abs().max(1.0));
        let shifted = solve_kepler(m + TAU, e).unwrap();
        prop_assert!((shifted - ecc - TAU).abs() < 1e-13);
        prop_assert!((solve_kepler(-m, e).unwrap() + ecc).abs() < 1e-14 * ecc.abs().max(1.0));
    }
}
